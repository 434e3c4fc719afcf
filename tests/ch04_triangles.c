/* ch04_triangles.c: ray-triangle intersection, meshes, and OBJ files
 * (chapter 04).
 *
 * Expected values are worked out by hand (stated beside each). OBJ and scene
 * files are written to a temporary folder by the tests themselves. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh.h"
#include "obj.h"
#include "render.h"
#include "scene.h"
#include "search.h"
#include "triangle.h"
#include "test_util.h"

static const struct {
    const char *name;
    triangle_method test;
} methods[] = {
    {"sheet", triangle_hit_sheet},
    {"moller-trumbore", triangle_hit_moller_trumbore},
    {"watertight", triangle_hit_watertight},
    {"sheet float", triangle_hit_sheet_float},
    {"moller-trumbore float", triangle_hit_moller_trumbore_float},
    {"watertight float", triangle_hit_watertight_float},
};
#define N_METHODS (int)(sizeof methods / sizeof methods[0])

/* The tests that every method must pass run once a method, as Check's loop
 * tests: iteration _i is the method of exercise 4.(_i + 1) (the watertight
 * one's shear is 4.4), methods[_i] in double and methods[_i +
 * METHODS_OF_EXERCISES] in float, so that each exercise's tests call its
 * own code only. */
#define METHODS_OF_EXERCISES 3
#define EACH_BUILD_OF_THIS_METHOD(m)                                           \
    for (int m = _i; m < N_METHODS; m += METHODS_OF_EXERCISES)

/* The triangle (0,0,2), (2,0,2), (0,2,2) in the plane z = 2, facing the eye. */
static const vec3 A = {0, 0, 2}, B = {2, 0, 2}, C = {0, 2, 2};

static ray toward(vec3 target)
{
    vec3 origin = {0.25, 0.25, -1};
    return (ray){origin, vec3_normalize(vec3_sub(target, origin))};
}

/* ------------------------------------------------------------ formulas */

START_TEST(test_barycentric_coordinates_rebuild_the_hit_point)
{
    /* Aimed at 0.2 A + 0.3 B + 0.5 C = (0.6, 1.0, 2). */
    vec3 target = {0.6, 1.0, 2};
    EACH_BUILD_OF_THIS_METHOD(m)
    {
        triangle_hit th;
        ck_assert_msg(
            methods[m].test(A, B, C, toward(target), 0, INFINITY, &th), "%s",
            methods[m].name);
        double tolerance = m < 3 ? 1e-14 : 1e-6; /* double, or float's 2^-24 */
        ck_assert_double_eq_tol(th.b[0] + th.b[1] + th.b[2], 1, tolerance);
        ck_assert_double_eq_tol(th.b[0], 0.2, tolerance);
        ck_assert_double_eq_tol(th.b[1], 0.3, tolerance);
        ck_assert_double_eq_tol(th.b[2], 0.5, tolerance);
        ck_assert(th.b[0] >= 0 && th.b[1] >= 0 && th.b[2] >= 0);
        /* t is the distance from (0.25, 0.25, -1): sqrt(0.35^2 + 0.75^2 + 9) */
        ck_assert_double_eq_tol(th.t, sqrt(0.35 * 0.35 + 0.75 * 0.75 + 9),
                                tolerance * 4);
    }
}
END_TEST

START_TEST(test_hits_on_an_edge_and_a_vertex)
{
    /* Along the z axis through (x, y): exact, so the edge case is exact. */
    const vec3 points[] = {
        {1, 0, 2}, {0, 1, 2}, {1, 1, 2}, {0, 0, 2}, {2, 0, 2}};
    EACH_BUILD_OF_THIS_METHOD(m)
    for (int k = 0; k < 5; k++) {
        ray r = {{points[k].x, points[k].y, 0}, {0, 0, 1}};
        triangle_hit th;
        ck_assert_msg(methods[m].test(A, B, C, r, 0, INFINITY, &th),
                      "%s misses point %d", methods[m].name, k);
        ck_assert(th.t == 2);
    }
}
END_TEST

START_TEST(test_ray_parallel_to_the_plane_misses)
{
    EACH_BUILD_OF_THIS_METHOD(m)
    {
        triangle_hit th;
        ray in_plane = {{-1, 0.5, 2}, {1, 0, 0}},
            beside = {{-1, 0.5, 1}, {1, 0, 0}};
        ck_assert(!methods[m].test(A, B, C, in_plane, 0, INFINITY, &th));
        ck_assert(!methods[m].test(A, B, C, beside, 0, INFINITY, &th));
    }
}
END_TEST

START_TEST(test_degenerate_triangle_is_never_hit)
{
    const vec3 same = {0.5, 0.5, 2},
               on_line[3] = {{0, 0, 2}, {1, 1, 2}, {2, 2, 2}};
    EACH_BUILD_OF_THIS_METHOD(m)
    {
        triangle_hit th;
        ray r = {{0.5, 0.5, 0}, {0, 0, 1}}, r2 = {{1, 1, 0}, {0, 0, 1}};
        ck_assert_msg(!methods[m].test(same, same, same, r, 0, INFINITY, &th),
                      "%s", methods[m].name);
        ck_assert_msg(!methods[m].test(on_line[0], on_line[1], on_line[2], r2,
                                       0, INFINITY, &th),
                      "%s: collinear", methods[m].name);
    }
}
END_TEST

START_TEST(test_t_outside_the_interval_is_rejected)
{
    ray r = {{0.5, 0.5, 0}, {0, 0, 1}}; /* hits at t = 2 */
    EACH_BUILD_OF_THIS_METHOD(m)
    {
        triangle_hit th;
        ck_assert(!methods[m].test(A, B, C, r, 0, 2, &th));
        ck_assert(!methods[m].test(A, B, C, r, 2, INFINITY, &th));
        ck_assert(methods[m].test(A, B, C, r, 1.9, 2.1, &th));
        ray away = {{0.5, 0.5, 3}, {0, 0, 1}};
        ck_assert(!methods[m].test(A, B, C, away, 0, INFINITY, &th));
    }
}
END_TEST

START_TEST(test_winding_decides_the_normal)
{
    /* (B - A) x (C - A) = (2,0,0) x (0,2,0) = (0,0,4); swapping B and C flips
     * it. */
    vec3 n = vec3_cross(vec3_sub(B, A), vec3_sub(C, A));
    ck_assert(n.x == 0 && n.y == 0 && n.z == 4);
    vec3 flipped = vec3_cross(vec3_sub(C, A), vec3_sub(B, A));
    ck_assert(flipped.z == -4);
    mesh m = {0};
    vec3 corners[3] = {A, B, C};
    m.vertices = corners;
    m.vertex_count = 3;
    mesh_triangle tri = {{0, 1, 2}};
    m.triangles = &tri;
    m.triangle_count = 1;
    mesh_compute_bounds(&m);
    hit h;
    long long tests = 0;
    ck_assert(mesh_intersect(&m, (ray){{0.5, 0.5, 0}, {0, 0, 1}}, 0, INFINITY,
                             &h, &tests));
    ck_assert(h.normal.x == 0 && h.normal.y == 0 && h.normal.z == 1);
    tri = (mesh_triangle){{0, 2, 1}};
    ck_assert(mesh_intersect(&m, (ray){{0.5, 0.5, 0}, {0, 0, 1}}, 0, INFINITY,
                             &h, &tests));
    ck_assert(h.normal.z == -1);
    ck_assert_int_eq(tests, 2);
}
END_TEST

/* ------------------------------------------------------------ leaks */

/* An octahedron with corners off the axes (so that nothing is exact):
 * 6 vertices, 8 faces, 12 edges. */
static vec3 octa[6];
static const int octa_faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4},
                                     {3, 0, 4}, {2, 0, 5}, {1, 2, 5},
                                     {3, 1, 5}, {0, 3, 5}};

static void make_octahedron(void)
{
    const vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                          {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (int k = 0; k < 6;
         k++) /* rotate by an awkward angle and move off the origin */
        octa[k] = (vec3){0.3 + axes[k].x * cos(0.7) - axes[k].y * sin(0.7),
                         -0.2 + axes[k].x * sin(0.7) + axes[k].y * cos(0.7),
                         5 + axes[k].z};
}

/* Rays aimed at points of every edge and at every vertex, from origins out
 * along the direction from the centre tilted a little (so that each ray
 * enters the solid at its target rather than grazing it); returns how many
 * hit none of the faces touching their target. */
static int count_leaks(triangle_method test, int *n_rays)
{
    int leaks = 0;
    *n_rays = 0;
    for (int f = 0; f < 8; f++)
        for (int e = 0; e < 3; e++) {
            int a = octa_faces[f][e], b = octa_faces[f][(e + 1) % 3];
            for (int s = 0; s <= 16; s++) { /* s = 0 and 16 are the vertices */
                vec3 target = vec3_add(
                    octa[a], vec3_scale(vec3_sub(octa[b], octa[a]), s / 16.0));
                vec3 out =
                    vec3_normalize(vec3_sub(target, (vec3){0.3, -0.2, 5}));
                for (int o = 0; o < 12; o++) {
                    double angle =
                        o * 0.5236 + 0.1; /* a tilt of 0.25 around out */
                    vec3 tilt = {0.25 * cos(angle), 0.25 * sin(angle),
                                 0.25 * cos(3 * angle)};
                    vec3 origin =
                        vec3_add(target, vec3_scale(vec3_add(out, tilt), 3));
                    ray r = {origin, vec3_normalize(vec3_sub(target, origin))};
                    bool hit = false;
                    triangle_hit th;
                    for (int g = 0; g < 8 && !hit; g++) {
                        const int *v = octa_faces[g];
                        bool touches = v[0] == a || v[1] == a || v[2] == a ||
                                       v[0] == b || v[1] == b || v[2] == b;
                        hit = touches && test(octa[v[0]], octa[v[1]],
                                              octa[v[2]], r, 0, INFINITY, &th);
                    }
                    leaks += !hit;
                    (*n_rays)++;
                }
            }
        }
    return leaks;
}

START_TEST(test_watertight_leaks_no_ray_where_others_do)
{
    make_octahedron();
    int n, sheet = count_leaks(triangle_hit_sheet, &n);
    int mt = count_leaks(triangle_hit_moller_trumbore, &n);
    ck_assert_msg(sheet > 0 && mt > 0,
                  "the test must show leaks: sheet %d, MT %d of %d", sheet, mt,
                  n);
    ck_assert_int_eq(count_leaks(triangle_hit_watertight, &n), 0);
    ck_assert_int_eq(count_leaks(triangle_hit_watertight_float, &n), 0);
}
END_TEST

/* ------------------------------------------------------------ boxes and
 * normals */

START_TEST(test_bounding_box_never_culls_a_grazing_ray)
{
    vec3 lo = {0, 0, 2}, hi = {2, 2, 2}; /* a flat box: the triangle's own */
    ck_assert(box_hit(lo, hi, (ray){{0.5, 0.5, 0}, {0, 0, 1}}, 0, INFINITY));
    ck_assert(box_hit(lo, hi, (ray){{2, 2, 0}, {0, 0, 1}}, 0,
                      INFINITY)); /* the corner */
    ck_assert(box_hit(lo, hi, (ray){{-1, 1, 2}, {1, 0, 0}}, 0,
                      INFINITY)); /* in its plane */
    ck_assert(box_hit(lo, hi, (ray){{1, 1, 2}, {0, 0, 1}}, -1,
                      INFINITY)); /* starts inside */
    ck_assert(!box_hit(lo, hi, (ray){{2.5, 0.5, 0}, {0, 0, 1}}, 0, INFINITY));
    ck_assert(!box_hit(lo, hi, (ray){{0.5, 0.5, 0}, {0, 0, 1}}, 0,
                       1.5)); /* too short */
    ck_assert(!box_hit(lo, hi, (ray){{0.5, 0.5, 3}, {0, 0, 1}}, 0,
                       INFINITY)); /* behind */
    /* An oblique ray through the far corner of a real box. */
    vec3 lo3 = {-1, -1, -1}, hi3 = {1, 1, 1};
    vec3 origin = {-3, -2, -5};
    ray r = {origin, vec3_normalize(vec3_sub(hi3, origin))};
    ck_assert(box_hit(lo3, hi3, r, 0, INFINITY));
}
END_TEST

START_TEST(test_smooth_normals_are_unit_and_blend_the_vertices)
{
    /* Two triangles folded along the y axis: the shared vertices get the mean.
     */
    vec3 v[4] = {{0, 0, 2}, {0, 2, 2}, {1, 0, 1}, {-1, 0, 1}};
    mesh_triangle t[2] = {{{0, 1, 2}}, {{0, 3, 1}}};
    mesh m = {0};
    m.vertices = malloc(sizeof v);
    m.triangles = malloc(sizeof t);
    memcpy(m.vertices, v, sizeof v);
    memcpy(m.triangles, t, sizeof t);
    m.vertex_count = 4, m.triangle_count = 2;
    ck_assert(mesh_smooth_normals(&m));
    mesh_compute_bounds(&m);
    /* Shared vertex 0: the faces' normals (-2,0,-2) and (2,0,-2) average to -z.
     */
    vec3 n0 = vec3_normalize(m.normals[0]);
    ck_assert(fabs(n0.x) < 1e-15 && n0.z < 0);
    /* Stored as area-weighted sums, not normalised: |n0| = 4, |n2| = 2 sqrt 2.
     */
    ck_assert(m.normals[0].x == 0 && m.normals[0].z == -4);
    ck_assert(m.normals[2].x == -2 && m.normals[2].z == -2);
    hit h;
    long long tests = 0;
    /* x = 0.5 on the first triangle is b2 = 0.5: the sums blend to (-1, 0, -3);
     * blending unit normals would give (-1, 0, -1 - sqrt 2), 4.1 degrees away.
     */
    ck_assert(mesh_intersect(&m, (ray){{0.5, 0.5, -5}, {0, 0, 1}}, 0, INFINITY,
                             &h, &tests));
    vec3 expected = {-1 / sqrt(10), 0, -3 / sqrt(10)};
    ck_assert_msg(vec3_dot(h.normal, expected) > cos(1e-6),
                  "normal (%g, %g, %g)", h.normal.x, h.normal.y, h.normal.z);
    for (double x = 0.05; x < 0.7;
         x += 0.1) { /* inside: x <= 1 - y/2 at y = 0.5 */
        ray r = {{x, 0.5, -5}, {0, 0, 1}};
        ck_assert(mesh_intersect(&m, r, 0, INFINITY, &h, &tests));
        ck_assert_double_eq_tol(vec3_length(h.normal), 1, 4 * DBL_EPSILON);
    }
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ OBJ files */

START_TEST(test_obj_reads_every_face_form)
{
    const char *path = write_file(
        "forms.obj",
        "# a comment\n"
        "o object\ng group\ns 1\nusemtl red\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\n"
        "vn 0 0 1\n"
        "f 1 2 3\n"
        "f 1/1 2/2 3/3\n"
        "f 1//1 2//1 3//1\n"
        "f 1/1/1 2/2/1 3/3/1\n"
        "f -4 -3 -2 -1\n"); /* a quad by relative indices: 2 triangles */
    mesh m = {0};
    scene_error err;
    ck_assert_msg(mesh_load_obj(&m, path, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    ck_assert_int_eq(m.vertex_count, 4);
    ck_assert_int_eq(m.normal_count, 1);
    ck_assert_int_eq(m.texcoord_count, 3);
    ck_assert_int_eq(m.triangle_count, 6);
    ck_assert(m.triangle_normals[0].v[0] == -1 &&
              m.triangle_normals[2].v[2] == 0);
    /* The fan of the quad: (1, 2, 3) and (1, 3, 4), zero-based. */
    ck_assert(m.triangles[4].v[0] == 0 && m.triangles[4].v[1] == 1 &&
              m.triangles[4].v[2] == 2);
    ck_assert(m.triangles[5].v[0] == 0 && m.triangles[5].v[1] == 2 &&
              m.triangles[5].v[2] == 3);
    mesh_free(&m);
}
END_TEST

static void expect_obj_error(const char *text, int line, int col,
                             const char *part)
{
    const char *path = write_file("bad.obj", text);
    mesh m = {0};
    scene_error err;
    ck_assert_msg(!mesh_load_obj(&m, path, &err), "accepted: %s", text);
    expect_error_at(&err, path, line, col, part, text);
    mesh_free(&m);
}

START_TEST(test_obj_rejects_bad_indices)
{
    const char *square = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
    char text[256];
    snprintf(text, sizeof text, "%sf 1 2 0\n", square);
    expect_obj_error(text, 4, 7, "index 0");
    snprintf(text, sizeof text, "%sf 1 2 4\n", square);
    expect_obj_error(text, 4, 7,
                     "vertex index 4 is out of range (3 defined so far)");
    snprintf(text, sizeof text, "%sf -1 -2 -4\n", square);
    expect_obj_error(text, 4, 9, "vertex index -4 is out of range");
    expect_obj_error("f 1 2 3\nv 0 0 0\n", 1, 3,
                     "vertex index 1 is out of range (0 defined");
    snprintf(text, sizeof text, "%sf 1/1 2/1 3/1\n", square);
    expect_obj_error(text, 4, 5, "texture coordinate index 1 is out of range");
    snprintf(text, sizeof text, "%svn 0 0 1\nf 1//2 2//1 3//1\n", square);
    expect_obj_error(text, 5, 6, "normal index 2 is out of range");
    snprintf(text, sizeof text, "%sf 1 2 x\n", square);
    expect_obj_error(text, 4, 7, "expected a vertex index");
    snprintf(text, sizeof text, "%sf 1 2 3x\n", square);
    expect_obj_error(text, 4, 7, "expected a vertex index");
    snprintf(text, sizeof text, "%sf 1 2 99999999999999999999\n", square);
    expect_obj_error(text, 4, 7, "out of range");
}
END_TEST

START_TEST(test_obj_rejects_short_faces_and_bad_numbers)
{
    expect_obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, 6,
                     "a face needs at least 3");
    expect_obj_error("v 0 0 0\nf\n", 2, 2, "a face needs at least 3");
    expect_obj_error("v 0 0\n", 1, 6,
                     "expected a vertex coordinate, found end of line");
    expect_obj_error("v 0 zero 0\n", 1, 5, "found 'zero'");
    expect_obj_error("v 0 nan 0\n", 1, 5, "finite");
    expect_obj_error("v 0 1e999 0\n", 1, 5, "finite");
    expect_obj_error("v 0 1e60 0\n", 1, 5, "between -1e50 and 1e50");
    expect_obj_error("vn 0 0\n", 1, 7, "found end of line");
    expect_obj_error("vt\n", 1, 3, "expected a texture coordinate");
    expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", 4, 5,
                     "expected a texture coordinate index");
    expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/", 4, 9,
                     "expected a texture coordinate index");
}
END_TEST

START_TEST(test_obj_reports_a_missing_file)
{
    mesh m = {0};
    scene_error err;
    ck_assert(!mesh_load_obj(&m, "/nonexistent/mesh.obj", &err));
    ck_assert_int_eq(err.line, 0);
    ck_assert(strstr(err.message, "No such file") != NULL);
}
END_TEST

START_TEST(test_obj_rejects_more_vertices_than_the_limit)
{
    /* MESH_MAX_VERTICES + 65536 lines "v 0 0 0": 34 MB. */
    char path[160];
    snprintf(path, sizeof path, "%s/huge.obj", tmpdir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    static char block[8 * 65536];
    for (size_t k = 0; k < sizeof block; k += 8)
        memcpy(block + k, "v 0 0 0\n", 8);
    for (long written = 0; written <= MESH_MAX_VERTICES; written += 65536)
        ck_assert_int_eq(fwrite(block, 1, sizeof block, f), sizeof block);
    fclose(f);
    mesh m = {0};
    scene_error err;
    ck_assert(!mesh_load_obj(&m, path, &err));
    ck_assert_int_eq(err.line, MESH_MAX_VERTICES + 1);
    ck_assert(strstr(err.message, "more than 4194304 vertices") != NULL);
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ statements */

START_TEST(test_triangle_and_mesh_statements)
{
    write_file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char scene_path[160];
    snprintf(scene_path, sizeof scene_path, "%s/test.scene", tmpdir);
    scene s;
    scene_error err;
    const char *text =
        "triangle a 0 0 4 b 1 0 4 c 0 1 4 color 1 0 0\n"
        "mesh file tri.obj scale 2 offset 1 1 10 smooth color 0 1 0\n";
    ck_assert_msg(parse_named(&s, text, strlen(text), scene_path, &err),
                  "%d:%d %s", err.line, err.col, err.message);
    ck_assert_int_eq(s.object_count, 2);
    ck_assert_int_eq(s.mesh_count, 1); /* a triangle statement costs no mesh */
    ck_assert(s.objects[0].kind == SHAPE_TRIANGLE && s.objects[0].color.x == 1);
    ck_assert(s.objects[1].kind == SHAPE_MESH && s.objects[1].color.y == 1);
    const mesh *m = &s.meshes[s.objects[1].mesh];
    ck_assert(m->vertices[1].x == 3 && m->vertices[1].z == 10); /* 2 * 1 + 1 */
    ck_assert(m->normal_count == 3);                            /* smooth */
    ck_assert(m->bounds.lo.x == 1 && m->bounds.hi.y == 3);
    render_stats stats = {0};
    hit h;
    ck_assert(scene_intersect(&s, (ray){{0.2, 0.2, 0}, {0, 0, 1}}, 0, INFINITY,
                              &h, &stats));
    ck_assert(h.t == 4 && h.color.x == 1);
    scene_free(&s);
}
END_TEST

static void expect_scene_error(const char *text, int line, int col,
                               const char *part)
{
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s", tmp_path("bad.scene"));
    expect_parse_error_named(scene_path, text, strlen(text), line, col, part);
}

START_TEST(test_triangle_and_mesh_statements_reject_bad_input)
{
    expect_scene_error("triangle a 0 0", 1, 15, "found end of line");
    expect_scene_error("triangle d 0 0 0", 1, 10,
                       "expected a triangle setting");
    expect_scene_error("mesh", 1, 5, "a mesh needs an OBJ file");
    expect_scene_error("mesh file", 1, 10, "expected the name of an OBJ file");
    expect_scene_error("mesh file missing.obj", 1, 11, "cannot read mesh file");
    expect_scene_error("mesh file x.obj scale 0", 1, 23,
                       "from 1e-100 to 1e100");
    expect_scene_error("mesh file x.obj material glass", 1, 26,
                       "material defined above");
    write_file("far.obj", "v 1e49 0 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_scene_error("mesh file far.obj scale 100", 1, 1, "beyond 1e50");
    write_file("broken.obj", "v 0 0 0\nf 1 2 3\n");
    char errors[160];
    snprintf(errors, sizeof errors, "%s/broken.obj", tmpdir);
    scene s;
    scene_error err;
    char scene_path[160];
    snprintf(scene_path, sizeof scene_path, "%s/x.scene", tmpdir);
    ck_assert(!parse_named(&s, "mesh file broken.obj", 20, scene_path, &err));
    ck_assert_str_eq(err.file, errors); /* the OBJ file's own location */
    ck_assert(err.line == 2 && err.col == 5);
    scene_free(&s);
}
END_TEST

START_TEST(test_cli_reports_obj_errors_and_writes_nothing)
{
    write_file("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    write_file("nul.obj", "v 0 0 0\n");
    write_bytes("nul.obj", "v 0 0 0\nv 1\0 0 0\n", 16);
    const char *cases[][2] = {
        {"mesh file broken.obj\n", "broken.obj:3:7: error: vertex index 3"},
        {"mesh file nul.obj\n", "nul.obj:2:4: error: unexpected NUL byte"},
        {"mesh file none.obj\n", "1:11: error: cannot read mesh file"}};
    for (int k = 0; k < 3; k++) {
        const char *scene_path = write_file("bad.scene", cases[k][0]);
        char scene_copy[192], out[192], errors[2048];
        snprintf(scene_copy, sizeof scene_copy, "%s", scene_path);
        snprintf(out, sizeof out, "%s", tmp_path("out.png"));
        const char *args[] = {scene_copy, "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, cases[k][1]) != NULL, "stderr: %s",
                      errors);
        ck_assert(!file_exists(out));
    }
}
END_TEST

/* The OBJ file at path is rejected at line:col with part in the message. */
static void expect_error_at_file(const char *path, int line, int col,
                                 const char *part)
{
    mesh m = {0};
    scene_error err;
    ck_assert_msg(!mesh_load_obj(&m, path, &err), "accepted: %s", path);
    expect_error_at(&err, path, line, col, part, path);
    mesh_free(&m);
}

START_TEST(test_obj_corners_end_after_their_last_index)
{
    const char *square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\n";
    char text[256];
    snprintf(text, sizeof text, "%sf 1/1/1/1 2 3\n", square);
    expect_obj_error(text, 6, 8, "expected the end of the face corner");
    snprintf(text, sizeof text, "%sf 1//1/junk 2 3\n", square);
    expect_obj_error(text, 6, 7, "expected the end of the face corner");
    snprintf(text, sizeof text, "%sf 1#a 2 3\n", square);
    expect_obj_error(text, 6, 3, "expected a vertex index");
    /* Found by fuzz/obj_fuzz's check of the corner grammar: "f 1# 2 3" was
     * read as the face 1, 2, 3, the '#' and what followed it ignored. */
    expect_error_at_file("tests/data/fuzz-obj-hash-in-corner.obj", 4, 3,
                         "expected a vertex index");
    snprintf(text, sizeof text, "%sf 1/1#a 2 3\n", square);
    expect_obj_error(text, 6, 5, "expected a texture coordinate index");
    /* A '#' outside a token still starts a comment. */
    snprintf(text, sizeof text, "%sf 1/1/1 2 3 # the end\n", square);
    mesh m = {0};
    scene_error err;
    ck_assert_msg(mesh_load_obj(&m, write_file("ok.obj", text), &err), "%s",
                  err.message);
    ck_assert_int_eq(m.triangle_count, 1);
    mesh_free(&m);
}
END_TEST

START_TEST(test_obj_skips_a_byte_order_mark)
{
    mesh m = {0};
    scene_error err;
    const char *path =
        write_file("bom.obj", "\xEF\xBB\xBF"
                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ck_assert_msg(mesh_load_obj(&m, path, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    ck_assert_int_eq(m.vertex_count, 3);
    ck_assert_int_eq(m.triangle_count, 1);
    mesh_free(&m);
}
END_TEST

START_TEST(test_a_mesh_must_be_a_regular_file)
{
    char fifo[192];
    snprintf(fifo, sizeof fifo, "%s", tmp_path("mesh-pipe"));
    ck_assert_int_eq(mkfifo(fifo, 0644), 0);
    alarm(30); /* a reader that waits for a writer fails instead of hanging */
    expect_scene_error("mesh file mesh-pipe", 1, 11, "not a regular file");
    expect_scene_error("mesh file /dev/zero", 1, 11, "not a regular file");
    alarm(0);
}
END_TEST

START_TEST(test_a_mesh_too_large_is_refused_before_it_is_read)
{
    char path[192], scene_path[192], out[192], errors[2048];
    snprintf(path, sizeof path, "%s", tmp_path("huge.obj"));
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, OBJ_MAX_BYTES, SEEK_SET),
                     0); /* sparse: 512 MiB + 1 */
    fputc('\n', f);
    fclose(f);
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("huge.scene", "mesh file huge.obj\n"));
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    const char *args[] = {scene_path, "-o", out, "--size", "8x6", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, ":1:11: error: cannot read mesh file") !=
                          NULL &&
                      strstr(errors, "more than 536870912 bytes") != NULL,
                  "stderr: %s", errors);
    /* Measured in work, not time: the file is neither read nor held (where
     * /proc/PID/io cannot be read, -1, only the peak memory is checked). */
    if (last_run_bytes_read >= 0) {
        /* 1 MiB: the scene, the program's shared libraries, none of the mesh */
        ck_assert_msg(last_run_bytes_read < (1L << 20), "%lld bytes read",
                      last_run_bytes_read);
    }
    /* The peak is the larger of the program's and the test's (tens of MiB
     * with AddressSanitizer); holding the mesh would take 512 MiB. */
    ck_assert_msg(last_run_peak_kib < (128L << 10), "peak of %ld KiB",
                  last_run_peak_kib);
}
END_TEST

START_TEST(test_a_mesh_named_twice_is_read_once)
{
    write_file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char scene_path[160];
    snprintf(scene_path, sizeof scene_path, "%s/twice.scene", tmpdir);
    const char *text =
        "mesh file tri.obj offset 0 0 5\n"
        "mesh file tri.obj offset 0 0 5 color 1 0 0\n" /* the same mesh */
        "mesh file tri.obj offset 0 0 6\n";            /* placed elsewhere */
    scene s;
    scene_error err;
    ck_assert_msg(parse_named(&s, text, strlen(text), scene_path, &err), "%s",
                  err.message);
    ck_assert_int_eq(s.object_count, 3);
    ck_assert_int_eq(s.mesh_count, 2);
    ck_assert_int_eq(s.objects[0].mesh, s.objects[1].mesh);
    ck_assert_int_ne(s.objects[0].mesh, s.objects[2].mesh);
    ck_assert(s.objects[1].color.x == 1 && s.objects[1].color.y == 0);
    ck_assert_int_eq(s.triangle_total, 2); /* the shared mesh counts once */
    scene_free(&s);
    /* Many meshes (the scene's index grows and is rebuilt), then an early one
     * again. */
    static char many[100 * 40];
    int n = 0;
    for (int k = 0; k <= 100; k++)
        n += snprintf(many + n, sizeof many - (size_t)n,
                      "mesh file tri.obj offset 0 0 %d\n", k < 100 ? k : 7);
    ck_assert_msg(parse_named(&s, many, (size_t)n, scene_path, &err), "%s",
                  err.message);
    ck_assert_int_eq(s.mesh_count, 100);
    ck_assert_int_eq(s.objects[100].mesh, s.objects[7].mesh);
    scene_free(&s);
}
END_TEST

/* Parses text as tmpdir/budget.scene with the scene's budgets lowered to
 * triangles and bytes; it must fail at line:col with part in the message. */
static void expect_over_budget(const char *text, long long triangles,
                               long long bytes, int line, int col,
                               const char *part)
{
    char scene_path[160];
    snprintf(scene_path, sizeof scene_path, "%s/budget.scene", tmpdir);
    scene s;
    scene_error err;
    scene_init(&s);
    s.triangle_budget = triangles, s.geometry_budget = bytes;
    ck_assert_msg(!scene_parse(&s, text, strlen(text), scene_path, &err),
                  "accepted: %s", text);
    expect_error_at(&err, scene_path, line, col, part, text);
    ck_assert_int_eq(err.kind, PARSE_OVER_BUDGET);
    ck_assert(s.triangle_total <= triangles && s.geometry_total <= bytes);
    scene_free(&s);
}

START_TEST(test_the_scene_budget_is_kept)
{
    /* A quad: 2 triangles, and 384 bytes of arrays as they grow (8 vertices
     * of 24 bytes, 8 triangles and 8 corners' normals of 12 bytes). */
    write_file("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    const char *three = "mesh file quad.obj\nmesh file quad.obj\nmesh file "
                        "quad.obj offset 0 0 1\n";
    expect_over_budget(three, 3, SCENE_MAX_GEOMETRY_BYTES, 3, 11,
                       "would pass the scene's budget of 3 triangles");
    expect_over_budget("mesh file quad.obj\n", SCENE_MAX_TRIANGLES, 200, 1, 11,
                       "at its line 5, triangles past the");
    /* Room for the mesh, not for its smooth normals beside it. */
    expect_over_budget(
        "mesh file quad.obj smooth\n", SCENE_MAX_TRIANGLES, 400, 1, 1,
        "smooth normals would pass the scene's budget of 400 bytes");
    scene s;
    scene_error err;
    char scene_path[160];
    snprintf(scene_path, sizeof scene_path, "%s/budget.scene", tmpdir);
    ck_assert(parse_named(&s, three, strlen(three), scene_path, &err));
    ck_assert_int_eq(s.triangle_total, 4);
    ck_assert_int_eq(s.geometry_total, 2 * 384);
    scene_free(&s);
}
END_TEST

START_TEST(test_running_out_of_memory_is_reported_as_such)
{
#if defined(TEST_ASAN)
    return; /* AddressSanitizer reserves terabytes of address space: no limit
               fits */
#endif
    /* 2 million vertices (16 MB of text, 48 MB of vec3) in 48 MiB of memory. */
    char path[192], scene_path[192], out[192], errors[2048];
    snprintf(path, sizeof path, "%s", tmp_path("big.obj"));
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    static char block[8 * 65536];
    for (size_t k = 0; k < sizeof block; k += 8)
        memcpy(block + k, "v 0 0 0\n", 8);
    for (int written = 0; written < 2000000; written += 65536)
        ck_assert_int_eq(fwrite(block, 1, sizeof block, f), sizeof block);
    fclose(f);
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("big.scene", "mesh file big.obj\n"));
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    const char *args[] = {scene_path, "-o", out, "--size", "8x6", NULL};
    ck_assert_int_eq(
        run_bin_limited(args, errors, sizeof errors,
                        (run_limits){.max_memory_bytes = 48L << 20}),
        1);
    /* At the scene line that asked for the mesh, and never as a mistake in it.
     */
    ck_assert_msg(strstr(errors, "big.scene:1:11: error: mesh file") != NULL &&
                      strstr(errors, "big.obj': out of memory") != NULL,
                  "stderr: %s", errors);
}
END_TEST

START_TEST(test_fuzz_collinear_triangle_is_not_hit)
{
    /* Found by fuzz/obj_fuzz: a ray aimed exactly at a zero-area triangle made
     * the watertight test report a hit whose normal was NaN. */
    mesh m = {0};
    scene_error err;
    ck_assert_msg(
        mesh_load_obj(&m, "tests/data/fuzz-obj-collinear-triangle.obj", &err),
        "%s", err.message);
    mesh_compute_bounds(&m);
    vec3 origin = {1.6, 0.6, -1}; /* the fuzz target's: in front of the box */
    for (double x = 0; x <= 8; x += 0.5) {
        ray r = {origin, vec3_normalize(vec3_sub((vec3){x, 0, 0}, origin))};
        hit h;
        long long tests = 0;
        ck_assert(!mesh_intersect(&m, r, 0, INFINITY, &h, &tests));
        triangle_hit th;
        for (int k = 0; k < N_METHODS; k++)
            ck_assert_msg(!methods[k].test(m.vertices[0], m.vertices[1],
                                           m.vertices[2], r, 0, INFINITY, &th),
                          "%s hits at x = %g", methods[k].name, x);
    }
    mesh_free(&m);
}
END_TEST

START_TEST(test_the_method_table_names_each_method)
{
    ck_assert_int_eq(TRIANGLE_METHOD_COUNT, N_METHODS);
    for (int m = 0; m < N_METHODS; m++) {
        const triangle_method_entry *e = &TRIANGLE_METHODS[m];
        char name[48];
        snprintf(name, sizeof name, "%s%s", e->name,
                 strcmp(e->precision, "float") == 0 ? " float" : "");
        ck_assert_msg(e->hit == methods[m].test &&
                          strcmp(name, methods[m].name) == 0,
                      "entry %d is %s", m, name);
    }
}
END_TEST

/* A byte order mark at the start of a line other than the first (two
 * files pasted into one) would make the line an unknown statement, which
 * the reader skips: it is reported where it is, in a small file and, read
 * by the program, in one large enough for later chapters to read in
 * parts. */
START_TEST(test_a_byte_order_mark_inside_an_obj_file_is_reported)
{
    expect_obj_error("v 0 0 5\n\xEF\xBB\xBFv 1 0 5\nv 0 1 5\nf 1 2 3\n", 2, 1,
                     "byte order mark");
    enum { VERTICES = 30000, MARK = 20000 }; /* about 600 KB */
    static char text[VERTICES * 24 + 64];
    size_t n = 0;
    for (int k = 1; k <= VERTICES; k++)
        n += (size_t)snprintf(text + n, sizeof text - n, "%sv %d 0 5.25\n",
                              k == MARK ? "\xEF\xBB\xBF" : "", k);
    n += (size_t)snprintf(text + n, sizeof text - n, "f 1 2 %d\n", VERTICES);
    write_bytes("large.obj", text, n);
    const char *scene_path =
        write_file("large.scene", "mesh file large.obj\n");
    char scene_copy[192], out[192], errors[2048], says[64];
    snprintf(scene_copy, sizeof scene_copy, "%s", scene_path);
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    snprintf(says, sizeof says, "large.obj:%d:1: error: a byte order mark",
             MARK);
    const char *args[] = {scene_copy, "-o", out, "--size", "8x6", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, says) != NULL, "stderr: %s", errors);
    ck_assert(!file_exists(out));
}
END_TEST

Suite *ch04_triangles_suite(void)
{
    Suite *s = suite_create("ch04 triangles");
    TCase *formulas = tcase_create("formulas");
    tcase_add_loop_test(formulas,
                        test_barycentric_coordinates_rebuild_the_hit_point, 0,
                        METHODS_OF_EXERCISES);
    tcase_add_test(formulas, test_winding_decides_the_normal);
    tcase_add_test(formulas, test_the_method_table_names_each_method);
    tcase_add_test(formulas,
                   test_smooth_normals_are_unit_and_blend_the_vertices);
    suite_add_tcase(s, formulas);

    TCase *edges = tcase_create("edge cases");
    tcase_add_loop_test(edges, test_hits_on_an_edge_and_a_vertex, 0,
                        METHODS_OF_EXERCISES);
    tcase_add_loop_test(edges, test_ray_parallel_to_the_plane_misses, 0,
                        METHODS_OF_EXERCISES);
    tcase_add_loop_test(edges, test_degenerate_triangle_is_never_hit, 0,
                        METHODS_OF_EXERCISES);
    tcase_add_loop_test(edges, test_t_outside_the_interval_is_rejected, 0,
                        METHODS_OF_EXERCISES);
    tcase_add_test(edges, test_watertight_leaks_no_ray_where_others_do);
    tcase_add_test(edges, test_bounding_box_never_culls_a_grazing_ray);
    tcase_add_test(edges, test_fuzz_collinear_triangle_is_not_hit);
    suite_add_tcase(s, edges);

    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(bad, 120);
    tcase_add_test(bad, test_obj_reads_every_face_form);
    tcase_add_test(bad, test_obj_rejects_bad_indices);
    tcase_add_test(bad, test_obj_rejects_short_faces_and_bad_numbers);
    tcase_add_test(bad, test_obj_reports_a_missing_file);
    tcase_add_slow_test(bad, test_obj_rejects_more_vertices_than_the_limit);
    tcase_add_test(bad, test_triangle_and_mesh_statements);
    tcase_add_test(bad, test_triangle_and_mesh_statements_reject_bad_input);
    tcase_add_test(bad, test_cli_reports_obj_errors_and_writes_nothing);
    tcase_add_test(bad, test_obj_corners_end_after_their_last_index);
    tcase_add_test(bad, test_obj_skips_a_byte_order_mark);
    tcase_add_test(bad, test_a_mesh_must_be_a_regular_file);
    tcase_add_test_in_a_process(
        bad, test_a_mesh_too_large_is_refused_before_it_is_read);
    tcase_add_test(bad, test_a_mesh_named_twice_is_read_once);
    tcase_add_test(bad, test_the_scene_budget_is_kept);
    tcase_add_test(bad, test_running_out_of_memory_is_reported_as_such);
    tcase_add_test(bad, test_a_byte_order_mark_inside_an_obj_file_is_reported);
    suite_add_tcase(s, bad);
    return s;
}
