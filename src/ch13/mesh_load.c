/* mesh_load.c: reading, placing and adding the meshes a scene names
 * (chapter 4). */
#include "mesh_load.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include "memory.h"
#include "obj.h"

/* <<the budget left for a mesh>> ch04 */
/* What the scene's budget leaves for one more mesh. */
static mesh_budget budget_left(const scene *s)
{
    long long triangles = s->triangle_budget - s->triangle_total;
    long long bytes = s->geometry_budget - s->geometry_total;
    triangles = triangles < MESH_MAX_TRIANGLES ? triangles
                                               : MESH_MAX_TRIANGLES;
    return (mesh_budget){triangles > 0 ? (long)triangles : 0,
                         bytes > 0 ? bytes : 0};
}

/* <<reading a mesh file>> ch04 */
/* Moves an error that is not the OBJ text's fault to the scene line that
 * named the file (at at); false. */
static bool mesh_file_error(parser *p, const scene *s, const char *at,
                            const char *path)
{
    parse_error *err = p->err;
    char why[sizeof err->message];
    snprintf(why, sizeof why, "%s", err->message);
    int line = err->line;
    if (err->kind == PARSE_CANNOT_READ)
        return parse_fail_with(p, err->kind, at,
                               "cannot read mesh file '%s': %s", path, why);
    if (err->kind == PARSE_OVER_BUDGET)
        return parse_fail_with(
            p, err->kind, at,
            "mesh file '%s' would pass the scene's budget of %lld triangles "
            "and %lld bytes of geometry: at its line %d, %s",
            path, s->triangle_budget, s->geometry_budget, line, why);
    if (line == 0)
        return parse_fail_with(p, PARSE_NO_MEMORY, at, "mesh file '%s': %s",
                               path, why);
    return parse_fail_with(p, PARSE_NO_MEMORY, at,
                           "mesh file '%s': %s (at its line %d)", path, why,
                           line);
}

/* <<loading a mesh's OBJ file>> ch12 */
static bool load_mesh_file(parser *p, const scene *s, const char *at,
                           const char *path, mesh *m)
{
    if (mesh_load_obj_on(m, path, budget_left(s), s->bvh_settings.threads,
                         p->err))
        return true;
    if (p->err->kind == PARSE_BAD_INPUT)
        return false; /* the OBJ file's own line and column */
    return mesh_file_error(p, s, at, path);
}

/* <<placing a mesh>> ch04 */
static bool smooth_within_budget(parser *p, const scene *s, mesh *m)
{
    long long normals = ((long long)m->vertex_count + 1) * sizeof(vec3);
    long long corners =
        ((long long)m->triangle_count + 1) * sizeof(mesh_triangle);
    if (mesh_bytes(m) + normals + corners > budget_left(s).bytes)
        return parse_fail_with(p, PARSE_OVER_BUDGET, p->line,
                               "the mesh's smooth normals would pass the "
                               "scene's budget of %lld bytes of geometry",
                               s->geometry_budget);
    return mesh_smooth_normals(m) ||
           parse_fail_with(p, PARSE_NO_MEMORY, p->line,
                           "out of memory for the mesh's normals");
}

static bool place_mesh(parser *p, const scene *s, mesh *m,
                       const mesh_source *source)
{
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = vec3_add(vec3_scale(m->vertices[k], source->scale),
                          source->offset);
        double largest = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
        if (!(largest <= PARSE_MAX_COORDINATE))
            return parse_fail_at(
                p, p->line,
                "vertex %d of the mesh lies beyond 1e50 once placed", k + 1);
        m->vertices[k] = v;
    }
    if (source->smooth && m->normal_count == 0 &&
        !smooth_within_budget(p, s, m))
        return false;
    mesh_compute_bounds(m);
    return true;
}

/* <<adding a mesh file>> ch04 */
int mesh_load_into(parser *p, scene *s, const char *at,
                   const mesh_source *source)
{
    mesh m = {0};
    int k = -1;
    if (load_mesh_file(p, s, at, source->path, &m) &&
        place_mesh(p, s, &m, source)) {
        m.source = *source;
        if ((m.source.path = memory_copy_string(source->path)) == NULL)
            parse_fail_with(p, PARSE_NO_MEMORY, p->line, "out of memory");
        else if ((k = scene_add_mesh(s, m)) < 0)
            parse_no_room(p, p->line, s->mesh_count, SCENE_MAX_MESHES,
                          "meshes");
    }
    if (k < 0)
        mesh_free(&m);
    return k;
}
