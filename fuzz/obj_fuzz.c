/* obj_fuzz.c: libFuzzer target for the OBJ reader of the latest chapter.
 *
 * Each input is parsed as an OBJ file, and three properties are checked
 * besides the sanitizers' (a failed property aborts: a finding):
 *
 * - A rejected file gets a located error whose line and column exist in the
 *   input.
 * - An accepted file is what the grammar allows: every face corner is v,
 *   v/vt, v//vn or v/vt/vn, read here independently of the reader.
 * - An accepted file round-trips: the loaded mesh written back as OBJ loads
 *   again into the same vertices, normals and triangles.
 *
 * Then the mesh gets smooth normals and its bounding box, and a fan of rays
 * through the box is intersected with it: the vertices the parser let
 * through reach the watertight test and the normal interpolation, whose
 * results must be finite. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obj.h"

/* ------------------------------------------------------------ located errors */

/* The line and column of err exist in text[0..size). */
static void check_error_is_located(const char *text, size_t size, const parse_error *err)
{
    const char *end = text + size, *line = text;
    if (size >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        line += 3; /* columns of the first line count from after the mark */
    if (strcmp(err->file, "fuzz.obj") != 0 || err->line < 1 || err->col < 1)
        abort();
    for (int k = 1; k < err->line; k++) {
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        if (eol == NULL)
            abort(); /* the file has fewer lines */
        line = eol + 1;
    }
    if (line >= end)
        abort();
    const char *eol = memchr(line, '\n', (size_t)(end - line));
    long length = (eol ? eol : end) - line;
    if (err->col > length + 1)
        abort();
}

/* ------------------------------------------------------------ the grammar of a corner */

static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/* -?[0-9]+ at *c, before end; moves *c past it. */
static bool is_index(const char **c, const char *end)
{
    const char *digits = *c += *c < end && **c == '-';
    while (*c < end && **c >= '0' && **c <= '9')
        (*c)++;
    return *c > digits;
}

static bool is_corner(const char *c, const char *end)
{
    if (!is_index(&c, end))
        return false;
    if (c == end)
        return true; /* v */
    if (*c++ != '/')
        return false;
    if (c < end && *c == '/')
        return ++c, is_index(&c, end) && c == end; /* v//vn */
    if (!is_index(&c, end))
        return false;
    if (c == end)
        return true; /* v/vt */
    return *c++ == '/' && is_index(&c, end) && c == end; /* v/vt/vn */
}

/* Every corner of every face line of [line, eol) is a corner. */
static void check_face(const char *line, const char *eol)
{
    int token = 0;
    bool face = false;
    for (const char *c = line; c < eol;) {
        while (c < eol && is_blank(*c))
            c++;
        if (c == eol || *c == '#')
            return; /* a comment starts only outside a token */
        const char *start = c;
        while (c < eol && !is_blank(*c))
            c++;
        if (token++ == 0)
            face = c - start == 1 && *start == 'f';
        else if (face && !is_corner(start, c))
            abort();
    }
}

static void check_faces(const char *text, size_t size)
{
    const char *end = text + size, *line = text;
    if (size >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        line += 3;
    while (line < end) {
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        eol = eol ? eol : end;
        check_face(line, eol);
        line = eol < end ? eol + 1 : end;
    }
}

/* ------------------------------------------------------------ the round trip */

/* The mesh as OBJ text: vertices and normals to the last bit (%.17g), and
 * triangles with their corners' normals. */
static char *write_obj(const mesh *m, size_t *length)
{
    char *text = NULL;
    FILE *out = open_memstream(&text, length);
    if (out == NULL)
        abort();
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = m->vertices[k];
        fprintf(out, "v %.17g %.17g %.17g\n", v.x, v.y, v.z);
    }
    for (int k = 0; k < m->normal_count; k++) {
        vec3 n = m->normals[k];
        fprintf(out, "vn %.17g %.17g %.17g\n", n.x, n.y, n.z);
    }
    for (int k = 0; k < m->triangle_count; k++) {
        fputc('f', out);
        for (int i = 0; i < 3; i++) {
            fprintf(out, " %d", m->triangles[k].v[i] + 1);
            int n = m->triangle_normals ? m->triangle_normals[k].v[i] : -1;
            if (n >= 0)
                fprintf(out, "//%d", n + 1);
        }
        fputc('\n', out);
    }
    if (fclose(out) != 0)
        abort();
    return text;
}

static bool same(const void *a, const void *b, int count, size_t size)
{
    return count == 0 || memcmp(a, b, (size_t)count * size) == 0;
}

static void check_round_trip(const mesh *m)
{
    size_t length;
    char *text = write_obj(m, &length);
    mesh again = {0};
    parse_error err;
    if (!mesh_parse_obj(&again, text, length, "again.obj", &err))
        abort();
    if (again.vertex_count != m->vertex_count || again.normal_count != m->normal_count ||
        again.triangle_count != m->triangle_count)
        abort();
    if (!same(again.vertices, m->vertices, m->vertex_count, sizeof(vec3)) ||
        !same(again.normals, m->normals, m->normal_count, sizeof(vec3)) ||
        !same(again.triangles, m->triangles, m->triangle_count, sizeof(mesh_triangle)) ||
        !same(again.triangle_normals, m->triangle_normals, m->triangle_count,
              sizeof(mesh_triangle)))
        abort();
    mesh_free(&again);
    free(text);
}

/* ------------------------------------------------------------ rays */

/* Rays from in front of the box towards points spread over it. */
static void shoot_rays(const mesh *m)
{
    vec3 centre = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    vec3 size = vec3_sub(m->bounds.hi, m->bounds.lo);
    vec3 origin = vec3_sub(centre, (vec3){0.3 * size.x, 0.2 * size.y, 2 * size.z + 1});
    for (int k = 0; k < 16; k++) {
        vec3 target = vec3_add(m->bounds.lo, (vec3){size.x * (k % 4) / 3.0, size.y * (k / 4) / 3.0,
                                             size.z * 0.5});
        vec3 d = vec3_sub(target, origin);
        if (!(vec3_dot(d, d) > 0) || !isfinite(vec3_dot(d, d)))
            continue;
        hit h;
        long long tests = 0;
        ray r = {origin, vec3_normalize(d)};
        if (mesh_intersect(m, r, 0, INFINITY, &h, &tests) &&
            !(isfinite(h.t) && isfinite(h.normal.x) && isfinite(h.normal.y) &&
              isfinite(h.normal.z)))
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    mesh m = {0};
    parse_error err;
    if (!mesh_parse_obj(&m, text, size, "fuzz.obj", &err)) {
        check_error_is_located(text, size, &err);
    } else {
        check_faces(text, size);
        check_round_trip(&m);
        if (m.vertex_count > 0) {
            if (m.normal_count == 0 && !mesh_smooth_normals(&m)) /* as `mesh ... smooth` does */
                abort();
            mesh_compute_bounds(&m);
            shoot_rays(&m);
        }
    }
    mesh_free(&m);
    return 0;
}
