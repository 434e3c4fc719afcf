/* ch08_kdtree.c: kd-trees, their walks and the tree over the objects
 * (chapter 08).
 *
 * The reference for every search through a tree is brute force, the test
 * of every triangle (chapter 04's mesh_nearest without a tree): a tree must
 * return a hit at exactly the same distance, on the same triangle or on
 * another one hit at that same distance. The naive walks that the chapter
 * warns against are written out here, so that each robustness test first
 * shows the naive walk failing on its input. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rng.h"
#include "mesh.h"
#include "obj.h"
#include "scene.h"
#include "memory.h"
#include "search.h"
#include "trees.h"
#include "test_util.h"

/* ------------------------------------------------------------ helpers */

static rng_state rng;

static void seed(uint64_t s) { rng = (rng_state){s}; }

/* Uniform in [0, 1), from a fixed seed: the same rays on every run. */
static double uniform01(void)
{
    return rng_uniform01(&rng);
}

static mesh load(const char *path)
{
    mesh m = {0};
    parse_error err;
    ck_assert_msg(mesh_load_obj(&m, path, &err), "%s: %s", path, err.message);
    mesh_compute_bounds(&m);
    return m;
}

static void build(mesh *m, kdtree_method method)
{
    kdtree_params p = kdtree_default_params();
    p.method = method;
    p.min_items = 1; /* a tree, however few the triangles */
    ck_assert(mesh_build_tree(m, &p));
}

/* m without its tree: brute force. */
static mesh brute(const mesh *m)
{
    mesh b = *m;
    b.tree = (kdtree){0};
    b.leaf_corners = NULL;
    return b;
}

typedef enum { WALK_ITERATIVE, WALK_RECURSIVE } walk_kind;

/* The distance of the nearest hit (infinity: none). */
static double nearest_t(const mesh *m, ray r, walk_kind walk, int *triangle)
{
    mesh_ray mr = mesh_ray_of(r);
    render_stats stats = {0};
    triangle_hit th;
    int k = walk == WALK_RECURSIVE
                ? mesh_nearest_recursive(m, &mr, 0, INFINITY, &th, &stats)
                : mesh_nearest(m, &mr, 0, INFINITY, &th, &stats);
    if (triangle)
        *triangle = k;
    return k >= 0 ? th.t : INFINITY;
}

/* The nearest hit of each ray by brute force, every triangle tried. */
typedef struct {
    double *t;
    int *triangle;
} answers;

static answers brute_answers(const mesh *m, const ray *rays, int n)
{
    mesh b = brute(m);
    answers a = {malloc((size_t)n * sizeof *a.t),
                 malloc((size_t)n * sizeof *a.triangle)};
    for (int k = 0; k < n; k++)
        a.t[k] = nearest_t(&b, rays[k], WALK_ITERATIVE, &a.triangle[k]);
    return a;
}

static void free_answers(answers *a)
{
    free(a->t), free(a->triangle);
}

/* How many of the rays get a different nearest hit through the tree of m
 * than the brute-force answers: another t, or another triangle at the same
 * t (the tie rule gives a tie to the lower index, in every search). */
static int differ_from(const mesh *m, const ray *rays, int n, walk_kind walk,
                       const answers *truth)
{
    int differ = 0;
    for (int k = 0; k < n; k++) {
        int tri_tree;
        double t_tree = nearest_t(m, rays[k], walk, &tri_tree);
        if (!(t_tree == truth->t[k]) || tri_tree != truth->triangle[k])
            differ++;
    }
    return differ;
}

/* The same, with the brute-force answers found here. */
static int disagreements(const mesh *m, const ray *rays, int n, walk_kind walk)
{
    answers truth = brute_answers(m, rays, n);
    int differ = differ_from(m, rays, n, walk, &truth);
    free_answers(&truth);
    return differ;
}

/* Random rays from a sphere around m's box towards points inside it. */
static int random_rays(const mesh *m, ray *rays, int n)
{
    vec3 c = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    vec3 e = vec3_sub(m->bounds.hi, m->bounds.lo);
    double radius = vec3_length(e) + 1e-9;
    for (int k = 0; k < n; k++) {
        vec3 o = vec3_add(c, vec3_scale(rng_unit_vector(&rng, 1e-3), radius));
        vec3 aim = {m->bounds.lo.x + e.x * uniform01(),
                    m->bounds.lo.y + e.y * uniform01(),
                    m->bounds.lo.z + e.z * uniform01()};
        rays[k] = (ray){o, vec3_normalize(vec3_sub(aim, o))};
    }
    return n;
}

/* Rays along the axes (a direction with two zero components: 1/d has two
 * infinities), from random points around the box. */
static int axis_rays(const mesh *m, ray *rays, int n)
{
    vec3 e = vec3_sub(m->bounds.hi, m->bounds.lo);
    for (int k = 0; k < n; k++) {
        int axis = k % 3;
        double sign = (k / 3) % 2 ? 1 : -1;
        vec3 o = {m->bounds.lo.x + e.x * uniform01(),
                  m->bounds.lo.y + e.y * uniform01(),
                  m->bounds.lo.z + e.z * uniform01()};
        vec3_set_axis(&o, axis, sign > 0 ? vec3_axis(m->bounds.lo, axis) - 1
                                         : vec3_axis(m->bounds.hi, axis) + 1);
        vec3 d = {0, 0, 0};
        vec3_set_axis(&d, axis, sign);
        rays[k] = (ray){o, d};
    }
    return n;
}

/* Rays aimed exactly at vertices and at points of edges of the mesh. */
static int edge_rays(const mesh *m, ray *rays, int n)
{
    vec3 c = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    double radius = vec3_length(vec3_sub(m->bounds.hi, m->bounds.lo));
    for (int k = 0; k < n; k++) {
        const int *v = m->triangles[(int)(uniform01() * m->triangle_count)].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]];
        vec3 target = k % 2 ? a : vec3_lerp(a, b, (double)(k % 7 + 1) / 8);
        vec3 o = vec3_add(c, vec3_scale(rng_unit_vector(&rng, 1e-3), radius));
        rays[k] = (ray){o, vec3_normalize(vec3_sub(target, o))};
    }
    return n;
}

/* Rays that start exactly on the split planes of m's tree, inside the
 * mesh's box, in random directions. */
static int plane_rays(const mesh *m, ray *rays, int n)
{
    vec3 e = vec3_sub(m->bounds.hi, m->bounds.lo);
    int made = 0;
    for (int k = 0; made < n && m->tree.node_count > 0; k++) {
        const kdtree_node *node = &m->tree.nodes[k % m->tree.node_count];
        int axis = (int)(node->bits & 3);
        if (axis == 3)
            continue;
        vec3 o = {m->bounds.lo.x + e.x * uniform01(),
                  m->bounds.lo.y + e.y * uniform01(),
                  m->bounds.lo.z + e.z * uniform01()};
        vec3_set_axis(&o, axis, node->split);
        rays[made++] = (ray){o, rng_unit_vector(&rng, 1e-3)};
    }
    return made;
}

/* Rays that graze triangles: aimed at a point inside one, along its plane
 * but for a tilt of 1e-4 to 1e-12. */
static int grazing_rays(const mesh *m, ray *rays, int n)
{
    for (int k = 0; k < n; k++) {
        const int *v = m->triangles[(int)(uniform01() * m->triangle_count)].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]],
             c = m->vertices[v[2]];
        vec3 p = vec3_add(vec3_scale(a, 0.4),
                          vec3_add(vec3_scale(b, 0.35), vec3_scale(c, 0.25)));
        vec3 along = vec3_sub(b, a),
             normal = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
        if (vec3_length(along) == 0 || vec3_length(normal) == 0) {
            rays[k] = (ray){vec3_add(p, (vec3){0, 0, 1}), {0, 0, -1}};
            continue;
        }
        double tilt = pow(10, -4 - 8 * uniform01());
        vec3 d = vec3_normalize(vec3_add(
            vec3_normalize(along), vec3_scale(vec3_normalize(normal), tilt)));
        rays[k] = (ray){vec3_sub(p, vec3_scale(d, 2 * vec3_length(along))), d};
    }
    return n;
}

/* All the kinds of rays above, count of each. */
static int adversarial_rays(const mesh *m, ray *rays, int count)
{
    int n = random_rays(m, rays, count);
    n += axis_rays(m, rays + n, count);
    n += edge_rays(m, rays + n, count);
    n += plane_rays(m, rays + n, count);
    n += grazing_rays(m, rays + n, count);
    return n;
}

/* Not static: chapter 9's suite tests its BVH on the same rays, from the
 * seed given, and on meshes made the same way. */
int ch08_adversarial_rays(const mesh *m, ray *rays, int count,
                          uint64_t seed_value);
int ch08_adversarial_rays(const mesh *m, ray *rays, int count,
                          uint64_t seed_value)
{
    seed(seed_value);
    return adversarial_rays(m, rays, count);
}

/* Builds m by each method and checks both walks against brute force. */
static void expect_agreement(mesh *m, int count, const char *what)
{
    static const kdtree_method methods[3] = {KDTREE_SAH, KDTREE_SAH_SORTING,
                                             KDTREE_MEDIAN};
    ray *rays = malloc(5 * (size_t)count * sizeof *rays);
    for (int k = 0; k < 3; k++) {
        build(m, methods[k]);
        ck_assert_msg(m->tree.node_count > 0, "%s: no tree", what);
        seed(0x5EED0000u + (uint64_t)k);
        int n = adversarial_rays(m, rays, count);
        answers truth = brute_answers(m, rays, n); /* once for both walks */
        for (int walk = 0; walk < 2; walk++) {
            int differ = differ_from(m, rays, n, (walk_kind)walk, &truth);
            ck_assert_msg(
                differ == 0,
                "%s, build %d, walk %d: %d of %d rays differ from brute force",
                what, k, walk, differ, n);
        }
        free_answers(&truth);
    }
    free(rays);
}

/* A mesh from arrays of points and triangles (copied). */
static mesh make_mesh(const vec3 *points, int n_points, const int (*tris)[3],
                      int n_tris)
{
    mesh m = {0};
    m.vertices = malloc(((size_t)n_points + 1) * sizeof *m.vertices);
    m.triangles = malloc(((size_t)n_tris + 1) * sizeof *m.triangles);
    memcpy(m.vertices, points, (size_t)n_points * sizeof *points);
    for (int k = 0; k < n_tris; k++)
        m.triangles[k] = (mesh_triangle){{tris[k][0], tris[k][1], tris[k][2]}};
    m.vertex_count = m.vertex_capacity = n_points;
    m.triangle_count = m.triangle_capacity = n_tris;
    mesh_compute_bounds(&m);
    return m;
}

/* A grid of 2 n^2 triangles in the plane z = 0, over [-1, 1]^2: every
 * coordinate a float, every triangle in one plane. */
static mesh plane_mesh(int n)
{
    vec3 *p = malloc((size_t)(n + 1) * (n + 1) * sizeof *p);
    int (*t)[3] = malloc(2 * (size_t)n * n * sizeof *t);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            p[j * (n + 1) + i] = (vec3){-1 + 2.0 * i / n, -1 + 2.0 * j / n, 0};
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            int *t0 = t[2 * (j * n + i)], *t1 = t[2 * (j * n + i) + 1];
            t0[0] = a, t0[1] = b, t0[2] = d, t1[0] = a, t1[1] = d, t1[2] = c;
        }
    mesh m = make_mesh(p, (n + 1) * (n + 1), (const int(*)[3])t, 2 * n * n);
    free(p), free(t);
    return m;
}

mesh ch08_make_mesh(const vec3 *points, int n_points, const int (*tris)[3],
                   int n_tris);
mesh ch08_make_mesh(const vec3 *points, int n_points, const int (*tris)[3],
                   int n_tris)
{
    return make_mesh(points, n_points, tris, n_tris);
}

/* ------------------------------------------------------------ agreement */

START_TEST(test_tree_agrees_with_brute_force_on_the_teapot)
{
    mesh m = load("meshes/teapot-8.obj");
    expect_agreement(&m, 600, "teapot");
    mesh_free(&m);
}
END_TEST

START_TEST(test_tree_agrees_with_brute_force_on_the_bunny)
{
    mesh m = load("meshes/bunny.obj");
    expect_agreement(&m, 40, "bunny"); /* brute force costs 1 ms a ray here */
    mesh_free(&m);
}
END_TEST

START_TEST(test_tree_agrees_with_brute_force_on_a_plane)
{
    mesh m = plane_mesh(24);
    expect_agreement(&m, 400, "plane");
    mesh_free(&m);
}
END_TEST

/* One huge triangle and 2,000 tiny ones scattered over it, on both sides. */
START_TEST(test_tree_agrees_with_brute_force_on_huge_and_tiny_triangles)
{
    enum { TINY = 2000 };
    vec3 *p = malloc((3 + 3 * TINY) * sizeof *p);
    int (*t)[3] = malloc((1 + TINY) * sizeof *t);
    p[0] = (vec3){-1e4, -1e4, 0}, p[1] = (vec3){1e4, -1e4, 1},
    p[2] = (vec3){0, 1e4, -1};
    t[0][0] = 0, t[0][1] = 1, t[0][2] = 2;
    seed(42);
    for (int k = 0; k < TINY; k++) {
        vec3 c = {200 * uniform01() - 100, 200 * uniform01() - 100,
                  4 * uniform01() - 2};
        for (int i = 0; i < 3; i++)
            p[3 + 3 * k + i] =
                vec3_add(c, vec3_scale(rng_unit_vector(&rng, 1e-3), 1e-3));
        t[1 + k][0] = 3 + 3 * k, t[1 + k][1] = 4 + 3 * k,
              t[1 + k][2] = 5 + 3 * k;
    }
    mesh m = make_mesh(p, 3 + 3 * TINY, (const int(*)[3])t, 1 + TINY);
    free(p), free(t);
    expect_agreement(&m, 400, "huge and tiny");
    /* and rays aimed at the tiny ones, which are the hard part */
    ray rays[400];
    for (int k = 0; k < 400; k++) {
        vec3 target = m.vertices[3 + (k * 7) % (3 * TINY)];
        vec3 o = vec3_add(target, vec3_scale(rng_unit_vector(&rng, 1e-3), 50));
        rays[k] = (ray){o, vec3_normalize(vec3_sub(target, o))};
    }
    ck_assert_int_eq(disagreements(&m, rays, 400, WALK_ITERATIVE), 0);
    mesh_free(&m);
}
END_TEST

/* Rays lying in split planes of m's tree (the direction's component on
 * the plane's axis exactly 0, of either sign), from outside the box, aimed
 * at points of the plane inside it and at points of the mesh's edges that
 * lie in the plane: both children of such a node share one interval. */
static int rays_in_split_planes(const mesh *m, ray *rays, int n)
{
    vec3 c = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    vec3 e = vec3_sub(m->bounds.hi, m->bounds.lo);
    double radius = vec3_length(e) + 1;
    int made = 0;
    for (int k = 0; made < n && k < 64 * n; k++) {
        const kdtree_node *node = &m->tree.nodes[k % m->tree.node_count];
        int axis = (int)(node->bits & 3);
        if (axis == 3)
            continue;
        vec3 target = {m->bounds.lo.x + e.x * uniform01(),
                       m->bounds.lo.y + e.y * uniform01(),
                       m->bounds.lo.z + e.z * uniform01()};
        for (int i = 0; i < m->triangle_count && k % 2; i++) {
            const int *v = m->triangles[(i + k) % m->triangle_count].v;
            vec3 a = m->vertices[v[0]], b = m->vertices[v[1]];
            if (vec3_axis(a, axis) == node->split &&
                vec3_axis(b, axis) == node->split) { /* an edge in it */
                target = vec3_lerp(a, b, uniform01());
                break;
            }
        }
        vec3_set_axis(&target, axis, node->split);
        vec3 o = vec3_add(c, vec3_scale(rng_unit_vector(&rng, 1e-3), radius));
        vec3_set_axis(&o, axis, node->split);
        vec3 d = vec3_normalize(vec3_sub(target, o));
        vec3_set_axis(&d, axis, made % 4 < 2 ? 0.0 : -0.0); /* 1/d: +-inf */
        rays[made++] = (ray){o, d};
    }
    return made;
}

/* Both walks against brute force on rays in the split planes of m's tree,
 * built by each method. */
static void expect_agreement_in_split_planes(mesh *m, int count,
                                             const char *what)
{
    static const kdtree_method methods[2] = {KDTREE_SAH, KDTREE_MEDIAN};
    ray *rays = malloc((size_t)count * sizeof *rays);
    for (int k = 0; k < 2; k++) {
        build(m, methods[k]);
        seed(0x91A0E000u + (uint64_t)k);
        int n = rays_in_split_planes(m, rays, count);
        ck_assert_int_eq(n, count);
        answers truth = brute_answers(m, rays, n);
        for (int walk = 0; walk < 2; walk++)
            ck_assert_msg(differ_from(m, rays, n, (walk_kind)walk, &truth) ==
                              0,
                          "%s, build %d, walk %d: %d of %d rays in split "
                          "planes differ from brute force",
                          what, k, walk,
                          differ_from(m, rays, n, (walk_kind)walk, &truth),
                          n);
        free_answers(&truth);
    }
    free(rays);
}

START_TEST(test_tree_agrees_with_brute_force_on_rays_in_split_planes)
{
    mesh teapot = load("meshes/teapot-8.obj"); /* its seam lies in x = 0 */
    expect_agreement_in_split_planes(&teapot, 2000, "teapot");
    mesh_free(&teapot);
    mesh grid = plane_mesh(16); /* edges in the planes x = c and y = c */
    expect_agreement_in_split_planes(&grid, 2000, "grid");
    mesh_free(&grid);
}
END_TEST

START_TEST(test_sweep_and_sorting_builds_make_the_same_tree)
{
    mesh a = load("meshes/teapot-8.obj"), b = load("meshes/teapot-8.obj");
    build(&a, KDTREE_SAH);
    build(&b, KDTREE_SAH_SORTING);
    ck_assert_int_eq(a.tree.node_count, b.tree.node_count);
    ck_assert_int_eq(a.tree.item_count, b.tree.item_count);
    for (int k = 0; k < a.tree.node_count; k++) {
        const kdtree_node *x = &a.tree.nodes[k], *y = &b.tree.nodes[k];
        ck_assert_uint_eq(x->bits, y->bits);
        if ((x->bits & 3) != 3)
            ck_assert_msg(x->split == y->split, "node %d splits at %a and %a",
                          k, x->split, y->split);
        else
            ck_assert_uint_eq(x->first, y->first);
    }
    ck_assert(memcmp(a.tree.items, b.tree.items,
                     (size_t)a.tree.item_count * sizeof(int)) == 0);
    mesh_free(&a), mesh_free(&b);
}
END_TEST

START_TEST(test_trees_over_zero_one_and_two_triangles)
{
    const vec3 p[6] = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5},
                       {3, 0, 6}, {4, 0, 6}, {3, 1, 6}};
    const int t[2][3] = {{0, 1, 2}, {3, 4, 5}};
    for (int n = 0; n <= 2; n++) {
        mesh m = make_mesh(p, 6, t, n);
        build(&m, KDTREE_SAH);
        ck_assert_int_eq(m.tree.node_count > 0,
                         n > 0); /* nothing to hold: no tree */
        ray rays[200];
        seed(7);
        for (int k = 0; k < 200; k++) {
            vec3 aim = {-1 + 6 * uniform01(), -1 + 3 * uniform01(), 5.5};
            rays[k] = (ray){{1.5, 0.5, 0},
                            vec3_normalize(vec3_sub(aim, (vec3){1.5, 0.5, 0}))};
        }
        ck_assert_int_eq(disagreements(&m, rays, 200, WALK_ITERATIVE), 0);
        if (n == 2) { /* two triangles apart: a leaf each, the walk tests one */
            kdtree_params p = kdtree_default_params();
            p.min_items = 1, p.traversal_cost = 1; /* splitting is cheap */
            ck_assert(mesh_build_tree(&m, &p));
            ck_assert_int_eq(m.tree.item_count, 2);
            mesh_ray mr = mesh_ray_of((ray){{0.25, 0.25, 0}, {0, 0, 1}});
            render_stats stats = {0};
            triangle_hit th;
            ck_assert_int_eq(mesh_nearest(&m, &mr, 0, INFINITY, &th, &stats),
                             0);
            ck_assert_int_eq(stats.triangle_tests, 1);
        }
        mesh_free(&m);
    }
}
END_TEST

/* ------------------------------------------------------------ where naive
 * walks fail */

/* The naive habits the chapter warns against, one flag each. */
typedef struct {
    bool origin_side;   /* the near side is the origin's: o < split */
    bool nan_is_a_miss; /* t_split = NaN (0 * inf): the plane is not crossed */
    bool strict_cells;  /* a cell whose interval is one point is empty, and
                           the root is clipped without rounding's margin */
    bool
        leaf_interval; /* a leaf tests its triangles on its own open interval */
} naive;

/* The textbook walk (pbrt's, with the flags' habits), with no thickness. */
static double naive_nearest(const mesh *m, ray r, naive nv)
{
    mesh_ray mr = mesh_ray_of(r);
    watertight_ray shear = watertight_ray_of(r);
    double t0 = 0, t1 = INFINITY, best = INFINITY;
    const double o[3] = {r.origin.x, r.origin.y, r.origin.z};
    const double inv[3] = {mr.inv_dir.x, mr.inv_dir.y, mr.inv_dir.z};
    for (int k = 0; k < 3; k++) { /* the slab test */
        double a = (vec3_axis(m->bounds.lo, k) - o[k]) * inv[k];
        double b = (vec3_axis(m->bounds.hi, k) - o[k]) * inv[k];
        double lo = fmin(a, b),
               hi = fmax(a, b) * (nv.strict_cells ? 1 : 1 + 1e-15);
        t0 = lo > t0 ? lo : t0, t1 = hi < t1 ? hi : t1;
    }
    struct {
        int node;
        double t0, t1;
    } stack[KDTREE_MAX_DEPTH];
    int top = 0, node = 0;
    for (;;) {
        bool skip = nv.strict_cells ? !(t0 < t1) : !(t0 <= t1);
        const kdtree_node *n = &m->tree.nodes[node];
        int axis = (int)(n->bits & 3);
        if (!skip && axis == 3) {
            triangle_hit th;
            int first = (int)n->first, count = (int)(n->bits >> 2);
            double lo = nv.leaf_interval ? t0 : 0,
                   hi = nv.leaf_interval ? fmin(t1, best) : best;
            if (triangle_nearest_corners(&shear, m->leaf_corners + first,
                                         count, lo, hi, &th) >= 0)
                best = th.t;
        } else if (!skip) {
            double t_split = (n->split - o[axis]) * inv[axis];
            bool below_first =
                o[axis] < n->split ||
                (!nv.origin_side && o[axis] == n->split && inv[axis] < 0);
            int near = below_first ? node + 1 : (int)(n->bits >> 2);
            int far = below_first ? (int)(n->bits >> 2) : node + 1;
            if (t_split != t_split && !nv.nan_is_a_miss) {
                stack[top].node = far, stack[top].t0 = t0, stack[top++].t1 = t1;
                node = near;
            } else if (t_split > t1 || t_split <= 0 || t_split != t_split) {
                node = near;
            } else if (t_split < t0) {
                node = far;
            } else {
                stack[top].node = far, stack[top].t0 = t_split,
                stack[top++].t1 = t1;
                node = near, t1 = t_split;
            }
            continue;
        }
        if (top == 0 || stack[top - 1].t0 > best)
            return best;
        top--, node = stack[top].node, t0 = stack[top].t0, t1 = stack[top].t1;
    }
}

/* By hand: a tree whose root cuts x at 0, triangle 0 of m below, triangle
 * 1 above. */
static void hand_tree(mesh *m)
{
    m->tree.nodes = malloc(3 * sizeof *m->tree.nodes);
    m->tree.nodes[0] = (kdtree_node){.split = 0, .bits = 2u << 2 | 0};
    m->tree.nodes[1] = (kdtree_node){.first = 0, .bits = 1u << 2 | 3};
    m->tree.nodes[2] = (kdtree_node){.first = 1, .bits = 1u << 2 | 3};
    m->tree.node_count = m->tree.node_capacity = 3;
    m->tree.items = malloc(2 * sizeof *m->tree.items);
    m->tree.items[0] = 0, m->tree.items[1] = 1;
    m->tree.item_count = m->tree.item_capacity = 2;
    m->tree.bounds = m->bounds;
    m->tree.thickness = KDTREE_THICKNESS * 8; /* the largest coordinate is 6 */
    m->leaf_corners = malloc(2 * sizeof *m->leaf_corners);
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++)
            m->leaf_corners[k].p[c] = m->vertices[m->triangles[k].v[c]];
}

/* Two triangles in the plane x + z = 5 sharing the edge from (0, -1, 5)
 * to (0, 1, 5), which lies in the root's plane x = 0: triangle 0 on the
 * side x <= 0, triangle 1 on x >= 0. */
static mesh hinge(void)
{
    const vec3 p[4] = {{0, -1, 5}, {0, 1, 5}, {-1, 0, 6}, {1, 0, 4}};
    const int t[2][3] = {{0, 1, 2}, {1, 0, 3}};
    mesh m = make_mesh(p, 4, t, 2);
    hand_tree(&m);
    return m;
}

START_TEST(test_a_ray_from_a_split_plane_goes_where_it_points)
{
    mesh m = hinge();
    /* from the plane x = 0, going to -x: into the cell below */
    ray r = {{0, 0.25, 5.5}, vec3_normalize((vec3){-0.5, 0, 0.1})};
    mesh b = brute(&m);
    double t = nearest_t(&b, r, WALK_ITERATIVE, NULL);
    ck_assert(isfinite(t));
    ck_assert(naive_nearest(&m, r, (naive){.origin_side = true}) !=
              t); /* naive: misses */
    ck_assert(naive_nearest(&m, r, (naive){0}) == t);
    ck_assert(nearest_t(&m, r, WALK_ITERATIVE, NULL) == t);
    ck_assert(nearest_t(&m, r, WALK_RECURSIVE, NULL) == t);
    mesh_free(&m);
}
END_TEST

START_TEST(test_a_ray_in_a_split_plane_sees_both_sides)
{
    mesh m = hinge();
    /* in the plane x = 0 (d.x = 0, so 1/d.x = inf and t_split = 0 * inf),
     * aimed at the shared edge: both triangles touch it; the ray starts
     * on the plane, so the naive near side is the one above */
    ray r = {{0, 0.25, 9}, {0, 0, -1}};
    ck_assert(isinf(mesh_ray_of(r).inv_dir.x));
    mesh b = brute(&m);
    double t = nearest_t(&b, r, WALK_ITERATIVE, NULL);
    ck_assert(t == 4); /* at (0, 0.25, 5), on the shared edge */
    /* with only triangle 0 (below) in the tree: the naive walk goes above
     * and misses */
    mesh below = hinge();
    below.leaf_corners[1] =
        (triangle_corners){{{9, 9, 9}, {9, 9, 9}, {9, 9, 9}}};
    ck_assert(isinf(naive_nearest(&below, r, (naive){.nan_is_a_miss = true})));
    ck_assert(nearest_t(&below, r, WALK_ITERATIVE, NULL) == t);
    ck_assert(nearest_t(&below, r, WALK_RECURSIVE, NULL) == t);
    mesh_free(&m), mesh_free(&below);
}
END_TEST

START_TEST(test_a_hit_on_a_split_plane_is_not_lost_between_two_leaves)
{
    mesh m = hinge();
    /* along +x through (0, 0.25, 5), a point of the shared edge: the hit is
     * at t = 1 exactly, and the plane is crossed at t = 1 exactly */
    ray r = {{-1, 0.25, 5}, {1, 0, 0}};
    mesh b = brute(&m);
    double t = nearest_t(&b, r, WALK_ITERATIVE, NULL);
    ck_assert(t == 1);
    ck_assert(isinf(
        naive_nearest(&m, r, (naive){.leaf_interval = true}))); /* leaks */
    ck_assert(naive_nearest(&m, r, (naive){0}) == 1);
    ck_assert(nearest_t(&m, r, WALK_ITERATIVE, NULL) == 1);
    ck_assert(nearest_t(&m, r, WALK_RECURSIVE, NULL) == 1);
    mesh_free(&m);
}
END_TEST

START_TEST(test_a_flat_cell_is_not_skipped)
{
    mesh m = plane_mesh(8); /* its root cell is flat: z from 0 to 0 */
    build(&m, KDTREE_SAH);
    ck_assert(m.tree.bounds.lo.z == 0 && m.tree.bounds.hi.z == 0);
    int naive_misses = 0;
    seed(11);
    for (int k = 0; k < 200; k++) {
        vec3 target = {1.8 * uniform01() - 0.9, 1.8 * uniform01() - 0.9, 0};
        vec3 o = {target.x, target.y, k % 2 ? 3 : -3}; /* straight down or up */
        ray r = {o, {0, 0, k % 2 ? -1 : 1}};
        mesh b = brute(&m);
        double t = nearest_t(&b, r, WALK_ITERATIVE, NULL);
        ck_assert_msg(fabs(t - 3) <= 3 * 4 * DBL_EPSILON, /* a few roundings */
                      "t = %a", t);
        naive_misses +=
            isinf(naive_nearest(&m, r, (naive){.strict_cells = true}));
        ck_assert(nearest_t(&m, r, WALK_ITERATIVE, NULL) == t);
        ck_assert(nearest_t(&m, r, WALK_RECURSIVE, NULL) == t);
    }
    ck_assert_int_eq(naive_misses, 200); /* the naive walk sees none */
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ degenerate input
 */

/* Depth, references and nodes stay within their limits. */
static void expect_bounded(const mesh *m, const char *what)
{
    long long n = m->triangle_count;
    int max_depth = (int)(8 + 1.3 * log2((double)n));
    ck_assert_msg(m->tree.depth <= max_depth, "%s: depth %d", what,
                  m->tree.depth);
    ck_assert_msg(m->tree.item_count <= KDTREE_REFERENCES_PER_ITEM * n + 64,
                  "%s: %d references for %lld triangles", what,
                  m->tree.item_count, n);
    ck_assert_msg(m->tree.node_count <=
                      2 * (KDTREE_REFERENCES_PER_ITEM * n + 64) + 1,
                  "%s: %d nodes", what, m->tree.node_count);
}

START_TEST(test_degenerate_input_keeps_depth_and_memory_bounded)
{
    enum { N = 3000 };
    vec3 *p = malloc((N + 2) * sizeof *p);
    int (*t)[3] = malloc(N * sizeof *t);
    for (int shape = 0; shape < 3; shape++) {
        const char *what = shape == 0   ? "identical"
                           : shape == 1 ? "one plane"
                                        : "one vertex";
        seed(99);
        for (int k = 0; k < N; k++) {
            double a = 2 * M_PI * k / N, b = 2 * M_PI * (k + 1) / N;
            if (shape == 0) /* all the same triangle */
                p[k] = k < 3 ? (vec3){k == 1, k == 2, 5} : (vec3){0, 0, 5},
                t[k][0] = 0, t[k][1] = 1, t[k][2] = 2;
            else if (shape == 1) /* overlapping triangles in z = 5 */
                p[k] = (vec3){2 * uniform01() - 1, 2 * uniform01() - 1, 5},
                t[k][0] = k, t[k][1] = (k * 7 + 1) % N,
                t[k][2] = (k * 13 + 2) % N;
            else /* a fan: every triangle has the vertex 0 */
                p[0] = (vec3){0, 0, 5},
                p[1 + k] = (vec3){cos(a), sin(a), 5 + 0.1 * sin(7 * b)},
                t[k][0] = 0, t[k][1] = 1 + k, t[k][2] = 1 + (k + 1) % N;
        }
        mesh m = make_mesh(p, N + 1, (const int(*)[3])t, N);
        for (int method = 0; method < 3; method++) {
            build(&m, (kdtree_method)method);
            expect_bounded(&m, what);
            ray rays[300];
            seed(5);
            int n = random_rays(&m, rays, 100) + axis_rays(&m, rays + 100, 100);
            n += edge_rays(&m, rays + n, 100);
            ck_assert_msg(disagreements(&m, rays, n, WALK_ITERATIVE) == 0, "%s",
                          what);
        }
        mesh_free(&m);
    }
    free(p), free(t);
}
END_TEST

START_TEST(test_a_ray_through_a_shared_vertex_tests_every_triangle)
{
    /* Correction (sheet 6.6): O(log n) is not a bound. Every one of the N
     * triangles of a fan contains its centre, so a ray through the centre
     * must test them all, through any tree. */
    enum { N = 512 };
    vec3 p[N + 1];
    int t[N][3];
    p[0] = (vec3){0, 0, 5};
    for (int k = 0; k < N; k++) {
        double a = 2 * M_PI * k / N;
        p[1 + k] = (vec3){cos(a), sin(a), 5};
        t[k][0] = 0, t[k][1] = 1 + k, t[k][2] = 1 + (k + 1) % N;
    }
    mesh m = make_mesh(p, N + 1, (const int(*)[3])t, N);
    build(&m, KDTREE_SAH);
    mesh_ray mr = mesh_ray_of((ray){{0, 0, 0}, {0, 0, 1}});
    render_stats stats = {0};
    triangle_hit th;
    ck_assert(mesh_nearest(&m, &mr, 0, INFINITY, &th, &stats) >= 0);
    ck_assert_int_ge(stats.triangle_tests, N);
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ any hit, objects
 */

START_TEST(test_any_hit_agrees_with_the_closest_hit)
{
    mesh meshes[2] = {load("meshes/teapot-8.obj"), plane_mesh(16)};
    for (int k = 0; k < 2; k++) {
        build(&meshes[k], KDTREE_SAH);
        ray rays[2500];
        seed(123);
        int n = adversarial_rays(&meshes[k], rays, 500);
        for (int i = 0; i < n; i++) {
            mesh_ray mr = mesh_ray_of(rays[i]);
            render_stats stats = {0};
            triangle_hit th;
            double t_max = 10 * uniform01(); /* a shadow ray's segment */
            bool closest =
                mesh_nearest(&meshes[k], &mr, 1e-9, t_max, &th, &stats) >= 0;
            ck_assert_int_eq(
                mesh_occluded(&meshes[k], &mr, 1e-9, t_max, &stats), closest);
            mesh b = brute(&meshes[k]);
            ck_assert_int_eq(mesh_occluded(&b, &mr, 1e-9, t_max, &stats),
                             closest);
        }
        mesh_free(&meshes[k]);
    }
}
END_TEST

/* Rays from the eye over the view: the scene with its objects' tree gives
 * the same closest hits, and the same answers to shadow rays, as the same
 * scene searched as a list. Frees with. */
static void expect_tree_agrees_with_list(scene *with)
{
    scene without = *with;
    without.object_tree = (kdtree){0};
    for (int k = 0; k < 5000; k++) {
        ray r = {
            {0, 0, 0},
            vec3_normalize((vec3){uniform01() - 0.5, uniform01() - 0.5, 1})};
        hit a, b;
        render_stats stats = {0};
        bool ha = scene_intersect(with, r, 0, INFINITY, &a, &stats);
        bool hb = scene_intersect(&without, r, 0, INFINITY, &b, &stats);
        ck_assert_int_eq(ha, hb);
        ck_assert(!ha || a.t == b.t);
        double t_max = 12 * uniform01();
        ck_assert_int_eq(scene_occluded(with, r, 0, t_max, &stats),
                         scene_occluded(&without, r, 0, t_max, &stats));
    }
    scene_free(with);
}

START_TEST(test_the_objects_tree_agrees_with_the_list)
{
    scene with;
    scene_init(&with);
    seed(2024);
    for (int k = 0; k < 300; k++) {
        object o = {.kind = k % 3 ? SHAPE_SPHERE : SHAPE_TRIANGLE,
                    .color = {1, 1, 1}};
        vec3 c = {8 * uniform01() - 4, 8 * uniform01() - 4,
                  4 + 8 * uniform01()};
        if (o.kind == SHAPE_SPHERE)
            o.sphere = (sphere){c, 0.05 + 0.4 * uniform01()};
        else
            for (int i = 0; i < 3; i++)
                o.corners[i] =
                    vec3_add(c, vec3_scale(rng_unit_vector(&rng, 1e-3), 0.5));
        ck_assert(scene_add_object(&with, o));
    }
    ck_assert(scene_build_trees(&with, NULL));
    ck_assert(with.object_tree.node_count > 0);
    expect_tree_agrees_with_list(&with);
}
END_TEST

START_TEST(test_the_objects_tree_agrees_with_the_list_for_placed_objects)
{
    /* Ellipsoids and triangles placed by rotations, non-uniform scales and
     * moves: their world boxes go into the tree. Closest hits and shadow
     * rays must be what the plain list of objects gives. */
    static char text[64 * 160];
    size_t used = 0;
    seed(77);
    for (int k = 0; k < 60; k++) {
        double x = 8 * uniform01() - 4, y = 8 * uniform01() - 4,
               z = 4 + 8 * uniform01();
        const char *shape = k % 2 ? "sphere radius 0.3"
                                  : "triangle a -0.4 0 0 b 0.4 0 0 c 0 0.5 0";
        used += (size_t)snprintf(
            text + used, sizeof text - used,
            "%s transform scale %.3f 1 %.3f rotate y %.1f rotate x %.1f "
            "translate %.3f %.3f %.3f\n",
            shape, 0.5 + uniform01(), 0.5 + 2 * uniform01(), 360 * uniform01(),
            360 * uniform01(), x, y, z);
    }
    scene with;
    scene_error err;
    scene_init(&with);
    ck_assert_msg(scene_parse(&with, text, used, "placed.scene", &err),
                  "%d:%d %s", err.line, err.col, err.message);
    ck_assert(scene_build_trees(&with, NULL));
    ck_assert(with.object_tree.node_count > 0);
    expect_tree_agrees_with_list(&with);
}
END_TEST

/* A triangle whose coordinates are near 1e9 in its own space, rotated and
 * moved back by a translation that cancels them, so that it lies near the
 * world's origin, 1.5 wide; and 30 small spheres far away, so that the
 * scene has an objects' tree. The sums of M p lose about 1e-7 to
 * cancellation: the world box must still hold the triangle. */
static void placed_far_triangle_scene(scene *s, long double corners[3][2])
{
    const long double a = 0.8L, b = 0.6L;
    const double X = 312345678.25, Y = 712345678.5, side = 1.5;
    const double object[3][2] = {{X, Y}, {X + side, Y}, {X, Y + side}};
    long double tx = -(a * X + b * Y), ty = -(-b * X + a * Y);
    for (int k = 0; k < 3; k++) {
        corners[k][0] = a * object[k][0] + b * object[k][1] + tx;
        corners[k][1] = -b * object[k][0] + a * object[k][1] + ty;
    }
    static char text[8192];
    size_t used = (size_t)snprintf(
        text, sizeof text,
        "triangle a %.17g %.17g 0 b %.17g %.17g 0 c %.17g %.17g 0 "
        "transform matrix 0.8 0.6 0 %.17Lg -0.6 0.8 0 %.17Lg 0 0 1 5\n",
        object[0][0], object[0][1], object[1][0], object[1][1], object[2][0],
        object[2][1], tx, ty);
    for (int k = 0; k < 30; k++)
        used += (size_t)snprintf(text + used, sizeof text - used,
                                 "sphere center %d 20 30 radius 0.1\n", k - 15);
    scene_error err;
    ck_assert_msg(parse_named(s, text, used, "far.scene", &err), "%d:%d %s",
                  err.line, err.col, err.message);
    ck_assert(s->object_tree.node_count > 0);
}

START_TEST(test_a_ray_grazing_a_far_moved_object_finds_it_in_the_tree)
{
    scene with;
    long double w[3][2];
    placed_far_triangle_scene(&with, w);
    scene without = with;
    without.object_tree = (kdtree){0};
    seed(31);
    int hits = 0;
    for (int n = 0; n < 30000; n++) {
        /* a point within 2e-7 of a corner, where the triangle touches its box
         */
        const long double *c = w[n % 3];
        long double x = c[0] + 4e-7L * (uniform01() - 0.5),
                    y = c[1] + 4e-7L * (uniform01() - 0.5);
        ray r = {{0, 0, 0}, vec3_normalize((vec3){(double)x, (double)y, 5})};
        hit a, b;
        render_stats stats = {0};
        bool in_list = scene_intersect(&without, r, 0, INFINITY, &b, &stats);
        ck_assert_msg(scene_intersect(&with, r, 0, INFINITY, &a, &stats) ==
                          in_list,
                      "ray %d: the list %s the triangle, the tree does not", n,
                      in_list ? "hits" : "misses");
        hits += in_list;
    }
    ck_assert_int_gt(hits, 3000); /* the rays graze it: many hit, many miss */
    ck_assert_int_lt(hits, 27000);
    scene_free(&with);
}
END_TEST

/* ------------------------------------------------------------ shadow rays */

/* An OBJ grid of 2 n^2 triangles over [-1, 1]^2 in the plane z = 0. */
static void write_grid_obj(const char *name, int n)
{
    static char text[1 << 14];
    size_t used = 0;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            used +=
                (size_t)snprintf(text + used, sizeof text - used, "v %g %g 0\n",
                                 -1 + 2.0 * i / n, -1 + 2.0 * j / n);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
            used +=
                (size_t)snprintf(text + used, sizeof text - used,
                                 "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
        }
    write_file(name, text);
}

/* count instances of the grid, one behind the other along +z from z = 5:
 * a shadow ray along +z through all of them is blocked by the first it
 * tests, which is asked for any hit, and no other is taken into its own
 * space. */
static void expect_shadow_ray_stops_at_its_first_occluder(int count)
{
    write_grid_obj("grid.obj", 4);
    static char text[64 * 64];
    size_t used = 0;
    for (int k = 0; k < count; k++)
        used += (size_t)snprintf(
            text + used, sizeof text - used,
            "mesh file grid.obj transform translate 0 0 %d\n", 5 + k);
    char path[192];
    snprintf(path, sizeof path, "%s", tmp_path("instances.scene"));
    scene s;
    scene_error err;
    ck_assert_msg(parse_named(&s, text, used, path, &err), "%s", err.message);
    ck_assert_int_eq(s.object_count, count);
    ck_assert_int_eq(s.object_tree.node_count > 0,
                     count >= SCENE_TREE_MIN_OBJECTS);
    render_stats stats = {0};
    ray r = {{0.1, 0.2, 0}, {0, 0, 1}};
    ck_assert(scene_occluded(&s, r, 0, 100, &stats));
    ck_assert_int_eq(stats.object_space_rays, 1);
    ck_assert_int_eq(stats.mesh_occlusion_tests, 1);
    if (count < SCENE_TREE_MIN_OBJECTS) /* a list: every other one is skipped */
        ck_assert_int_eq(stats.shadow_objects_skipped, count - 1);
    scene_free(&s);
}

START_TEST(test_a_shadow_ray_through_instances_stops_at_its_first_occluder)
{
    expect_shadow_ray_stops_at_its_first_occluder(5);  /* a list of objects */
    expect_shadow_ray_stops_at_its_first_occluder(40); /* the objects' tree */
}
END_TEST

/* ------------------------------------------------------------ command line */

static char *read_all(const char *path, size_t *length)
{
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    char *data = malloc(1 << 20);
    *length = fread(data, 1, 1 << 20, f);
    fclose(f);
    return data;
}

/* The program of the chapter before this one: $CHAPTER_BIN with its
 * chapter number lowered by one (bin/ch08 -> bin/ch07). */
static const char *previous_bin(void)
{
    static char path[256];
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert_ptr_nonnull(bin);
    snprintf(path, sizeof path, "%s", bin);
    char *number = strrchr(path, 'h'); /* ...chNN */
    ck_assert(number != NULL && strlen(number) == 3);
    unsigned n = (unsigned)atoi(number + 1) - 1;
    snprintf(number + 1, 3, "%02u", n % 100); /* two digits, as chNN has */
    return path;
}

#define TIE_W 48
#define TIE_H 36
#define TIE_FANS 63 /* cones, each with its apex on a pixel's ray */
#define TIE_SIDES 16

/* Cones whose apexes lie exactly on pixel rays (4 times the ray's unit
 * direction: a power of two, so exact), their triangles listed in a
 * shuffled order. corners[f][k] is triangle k of fan f's three corners. */
static void tie_fans(vec3 corners[TIE_FANS][TIE_SIDES][3])
{
    scene s;
    scene_init(&s);
    s.cam.width = TIE_W, s.cam.height = TIE_H;
    int f = 0;
    for (int j = 2; j < TIE_H && f < TIE_FANS; j += 5)
        for (int i = 2; i < TIE_W && f < TIE_FANS; i += 5, f++) {
            vec3 apex = vec3_scale(camera_ray(&s.cam, i, j).dir, 4);
            vec3 rim[TIE_SIDES];
            for (int k = 0; k < TIE_SIDES; k++) {
                double a = 2 * M_PI * (k + 0.3 * (f % 3)) / TIE_SIDES;
                rim[k] =
                    vec3_add(apex, (vec3){0.2 * cos(a), 0.2 * sin(a), 0.25});
            }
            for (int k = 0; k < TIE_SIDES; k++) {
                corners[f][k][0] = apex;
                corners[f][k][1] = rim[k];
                corners[f][k][2] = rim[(k + 1) % TIE_SIDES];
            }
        }
    ck_assert_int_eq(f, TIE_FANS);
    scene_free(&s);
}

/* The order in which the files list the triangles: shuffled. */
static void tie_order(int order[TIE_FANS * TIE_SIDES])
{
    int n = TIE_FANS * TIE_SIDES;
    for (int k = 0; k < n; k++)
        order[k] = k;
    seed(8);
    for (int k = n - 1; k > 0; k--) {
        int j = (int)(uniform01() * (k + 1)), swap = order[k];
        order[k] = order[j], order[j] = swap;
    }
}

/* What bin renders of scene_path. */
static char *render_bytes(const char *bin, const char *scene_path,
                          size_t *length)
{
    char errors[4096];
    const char *args[] = {scene_path, "-o", tmp_path("tie.png"), NULL};
    const char *saved = getenv("CHAPTER_BIN");
    char chapter[256];
    snprintf(chapter, sizeof chapter, "%s", saved);
    setenv("CHAPTER_BIN", bin, 1);
    int status = run_bin(args, errors, sizeof errors);
    setenv("CHAPTER_BIN", chapter, 1);
    ck_assert_msg(status == 0, "%s: %s", bin, errors);
    return read_all(tmp_path("tie.png"), length);
}

/* Chapter 7's program (brute force) and chapter 8's (the trees) draw
 * scene_path byte for byte alike. */
static void expect_same_bytes(const char *scene_path)
{
    size_t n7, n8;
    char *seven = render_bytes(previous_bin(), scene_path, &n7);
    char *eight = render_bytes(getenv("CHAPTER_BIN"), scene_path, &n8);
    ck_assert_msg(n7 == n8 && memcmp(seven, eight, n7) == 0,
                  "%s: ch07 and ch08 differ", scene_path);
    free(seven), free(eight);
}

/* The tie scenes: into obj (obj_size bytes) the fans as one OBJ mesh, which
 * chapter 8 gives a tree, its vertices shared; into lone (lone_size bytes)
 * a scene of them as lone triangles, objects that chapter 8 puts in the
 * objects' tree, each of its own colour. Not static: chapter 9's suite
 * draws the same scenes on several threads. */
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size);
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size)
{
    static vec3 c[TIE_FANS][TIE_SIDES][3];
    static int order[TIE_FANS * TIE_SIDES];
    tie_fans(c);
    tie_order(order);
    size_t vo = 0, lo = (size_t)snprintf(lone, lone_size, "image %d %d\n",
                                         TIE_W, TIE_H);
    for (int f = 0; f < TIE_FANS; f++) {
        const vec3 *p = c[f][0];
        vo += (size_t)snprintf(obj + vo, obj_size - vo, "v %.17g %.17g %.17g\n",
                               p[0].x, p[0].y, p[0].z);
        for (int k = 0; k < TIE_SIDES; k++)
            vo += (size_t)snprintf(obj + vo, obj_size - vo,
                                   "v %.17g %.17g %.17g\n", c[f][k][1].x,
                                   c[f][k][1].y, c[f][k][1].z);
    }
    for (int n = 0; n < TIE_FANS * TIE_SIDES; n++) {
        int f = order[n] / TIE_SIDES, k = order[n] % TIE_SIDES;
        int apex = f * (TIE_SIDES + 1) + 1;
        vo += (size_t)snprintf(obj + vo, obj_size - vo, "f %d %d %d\n", apex,
                               apex + 1 + k, apex + 1 + (k + 1) % TIE_SIDES);
        const vec3 *p = c[f][k];
        lo +=
            (size_t)snprintf(lone + lo, lone_size - lo,
                             "triangle a %.17g %.17g %.17g b %.17g %.17g %.17g "
                             "c %.17g %.17g %.17g color %.2f %.2f %.2f\n",
                             p[0].x, p[0].y, p[0].z, p[1].x, p[1].y, p[1].z,
                             p[2].x, p[2].y, p[2].z, 0.2 + 0.8 * uniform01(),
                             0.2 + 0.8 * uniform01(), 0.2 + 0.8 * uniform01());
    }
}

START_TEST(test_chapters_7_and_8_draw_ties_alike)
{
    static char obj[1 << 18], lone[1 << 19];
    tie_scene_texts(obj, sizeof obj, lone, sizeof lone);
    write_file("fans.obj", obj);
    char mesh_text[128];
    snprintf(mesh_text, sizeof mesh_text,
             "image %d %d\nmesh file fans.obj color 0.9 0.7 0.4\n", TIE_W,
             TIE_H);
    char mesh_path[192], lone_path[192];
    snprintf(mesh_path, sizeof mesh_path, "%s",
             write_file("mesh.scene", mesh_text));
    snprintf(lone_path, sizeof lone_path, "%s", write_file("lone.scene", lone));
    expect_same_bytes(mesh_path);
    expect_same_bytes(lone_path);
}
END_TEST

START_TEST(test_stats_hint_an_over_fine_mesh)
{
    link_meshes();
    char scene_path[192], errors[4096];
    snprintf(
        scene_path, sizeof scene_path, "%s",
        write_file("bunny.scene",
                   "mesh file meshes/bunny.obj scale 12 offset 0 -1.4 6\n"));
    const char *sizes[2] = {"16x12", "320x240"};
    for (int k = 0; k < 2; k++) {
        const char *args[] = {scene_path, "--size", sizes[k],
                              "--stats",  "-o",     tmp_path("b.png"),
                              NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
        /* at 16 x 12 the box covers at most 192 pixels: 362 triangles each */
        ck_assert_msg((strstr(errors, "hint: object 1") != NULL) == (k == 0),
                      "%s: %s", sizes[k], errors);
    }
}
END_TEST

/* ------------------------------------------------------------ the kdtree
 * statement */

START_TEST(test_kdtree_statement_sets_the_parameters)
{
    scene s;
    scene_error err;
    ck_assert(
        parse_text(&s,
                   "kdtree build median traversal_cost 3 intersection_cost 7 "
                   "empty_bonus 0.5 max_depth 12 heatmap 40\n",
                   &err));
    ck_assert_int_eq(s.tree_params.method, KDTREE_MEDIAN);
    ck_assert(s.tree_params.traversal_cost == 3 &&
              s.tree_params.intersection_cost == 7);
    ck_assert(s.tree_params.empty_bonus == 0.5 &&
              s.tree_params.max_depth == 12);
    ck_assert_int_eq(s.heatmap, 40);
    scene_free(&s);
    ck_assert(
        parse_text(&s, "kdtree build none\nkdtree build sorting\n", &err));
    ck_assert_int_eq(s.tree_params.method, KDTREE_SAH_SORTING);
    scene_free(&s);
}
END_TEST

START_TEST(test_kdtree_statement_rejects_bad_settings)
{
    expect_parse_error("kdtree build fast\n", 1, 14, "build method");
    expect_parse_error("kdtree build\n", 1, 13, "build method");
    expect_parse_error("kdtree traversal_cost 0\n", 1, 23, "traversal cost");
    expect_parse_error("kdtree intersection_cost -2\n", 1, 26,
                       "intersection cost");
    expect_parse_error("kdtree empty_bonus 1\n", 1, 20, "empty bonus");
    expect_parse_error("kdtree empty_bonus nan\n", 1, 20, "finite");
    expect_parse_error("kdtree max_depth 65\n", 1, 18, "maximum depth");
    expect_parse_error("kdtree max_depth 2.5\n", 1, 18, "whole number");
    expect_parse_error("kdtree heatmap 0\n", 1, 16, "number of nodes");
    expect_parse_error("kdtree depth 3\n", 1, 8, "kd-tree setting");
    expect_parse_error("kdtree\n", 1, 7, "kd-tree setting");
}
END_TEST

/* Parses text as the scene file budget.scene (its meshes relative to the
 * current folder) with the geometry budget set to bytes; the total after. */
static bool parse_within(const char *text, long long bytes, scene_error *err,
                         long long *total)
{
    scene s;
    scene_init(&s);
    s.geometry_budget = bytes;
    bool ok = scene_parse(&s, text, strlen(text), "budget.scene", err);
    *total = s.geometry_total;
    scene_free(&s);
    return ok;
}

START_TEST(test_the_trees_count_against_the_geometry_budget)
{
    scene_error err;
    long long mesh_only, with_tree, total;
#ifdef BVH_H /* from chapter 9 on: the meshes' kd-trees, asked for */
    const char *teapot = "accelerator kdtree\n"
                         "mesh file meshes/teapot-8.obj\n";
    const char *no_tree = "accelerator kdtree\nkdtree build none\n"
                          "mesh file meshes/teapot-8.obj\n";
#else
    const char *teapot = "image 8 6\nmesh file meshes/teapot-8.obj\n";
    const char *no_tree = "image 8 6\nkdtree build none\n"
                          "mesh file meshes/teapot-8.obj\n";
#endif
    ck_assert_msg(
        parse_within(no_tree, SCENE_MAX_GEOMETRY_BYTES, &err, &mesh_only), "%s",
        err.message);
    ck_assert_msg(
        parse_within(teapot, SCENE_MAX_GEOMETRY_BYTES, &err, &with_tree), "%s",
        err.message);
    ck_assert_msg(with_tree > mesh_only, "the tree took no bytes: %lld",
                  with_tree);
    /* Room for the mesh and 100 bytes: not for its tree, which the mesh
     * statement on line 2 asked for. */
    ck_assert(!parse_within(teapot, mesh_only + 100, &err, &total));
    expect_error_at(&err, "budget.scene", 2, 1,
                    "the kd-tree of mesh file 'meshes/teapot-8.obj' would pass "
                    "the scene's budget of", teapot);
    ck_assert_int_eq(err.kind, PARSE_OVER_BUDGET);
    ck_assert_int_le(total, mesh_only + 100);
    /* The objects' tree belongs to the whole file. */
    char spheres[2048] = "";
    for (int k = 0; k < 40; k++)
        snprintf(spheres + strlen(spheres), sizeof spheres - strlen(spheres),
                 "sphere center %d 0 9 radius 0.4\n", k - 20);
    ck_assert_msg(parse_within(spheres, SCENE_MAX_GEOMETRY_BYTES, &err, &total),
                  "%s", err.message);
    ck_assert_int_gt(total, 0);
    ck_assert(!parse_within(spheres, total - 1, &err, &total));
    expect_error_at(&err, "budget.scene", 0, 0,
                    "the objects' kd-tree would pass", spheres);
    ck_assert_int_eq(err.kind, PARSE_OVER_BUDGET);
}
END_TEST

START_TEST(test_running_out_of_memory_anywhere_in_a_load_is_reported)
{
    /* A cube of 12 triangles (a tree of its own), placed twice, and 30
     * spheres (a tree over the objects): the load fails at its first,
     * second, ... allocation in turn, and each failure must be reported as
     * running out of memory, at a place in the file, and leave nothing
     * behind (the sanitizer build checks for leaks). */
    write_file("cube.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                           "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                           "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\n"
                           "f 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n");
    char text[4096] = "material shiny specular 0.5\n"
                      "light area position 0 5 5 samples 4\n"
                      "mesh file cube.obj transform rotate y 30\n"
                      "mesh file cube.obj smooth transform translate 2 0 9\n";
    for (int k = 0; k < 30; k++)
        snprintf(text + strlen(text), sizeof text - strlen(text),
                 "sphere center %d 0 9 radius 0.4 material shiny\n", k - 15);
    char path[192];
    snprintf(path, sizeof path, "%s", write_file("oom.scene", text));
    int failures = 0;
    for (long n = 0;; n++) {
        scene s;
        scene_error err;
        scene_init(&s);
        memory_fail_after(n);
        bool ok = scene_load(&s, path, &err);
        memory_fail_after(-1);
        scene_free(&s);
        if (ok)
            break;
        failures++;
        ck_assert_msg(err.kind == PARSE_NO_MEMORY,
                      "allocation %ld: kind %d: %s:%d: %s", n, err.kind,
                      err.file, err.line, err.message);
        ck_assert_msg(strstr(err.message, "out of memory") != NULL,
                      "allocation %ld: %s", n, err.message);
        ck_assert_msg(n < 100000, "the load never succeeds");
    }
    ck_assert_int_gt(failures, 20); /* every array, the trees' nodes, ... */
}
END_TEST

Suite *ch08_kdtree_suite(void)
{
    Suite *s = suite_create("ch08 kdtree");
    TCase *agree = tcase_create("agreement with brute force");
    tcase_set_timeout(agree, 120);
    tcase_add_test(agree, test_trees_over_zero_one_and_two_triangles);
    tcase_add_test(agree, test_sweep_and_sorting_builds_make_the_same_tree);
    tcase_add_slow_test(agree, test_tree_agrees_with_brute_force_on_the_teapot);
    tcase_add_slow_test(agree, test_tree_agrees_with_brute_force_on_the_bunny);
    tcase_add_test(agree, test_tree_agrees_with_brute_force_on_a_plane);
    tcase_add_test(agree,
                   test_tree_agrees_with_brute_force_on_rays_in_split_planes);
    tcase_add_test(
        agree, test_tree_agrees_with_brute_force_on_huge_and_tiny_triangles);
    tcase_add_test(agree, test_any_hit_agrees_with_the_closest_hit);
    tcase_add_test(agree, test_the_objects_tree_agrees_with_the_list);
    tcase_add_test(
        agree, test_the_objects_tree_agrees_with_the_list_for_placed_objects);
    tcase_add_test(agree,
                   test_a_ray_grazing_a_far_moved_object_finds_it_in_the_tree);
    suite_add_tcase(s, agree);
    TCase *edges = tcase_create("edge cases");
    tcase_set_timeout(edges, 120);
    tcase_add_test(edges, test_a_ray_from_a_split_plane_goes_where_it_points);
    tcase_add_test(edges, test_a_ray_in_a_split_plane_sees_both_sides);
    tcase_add_test(edges,
                   test_a_hit_on_a_split_plane_is_not_lost_between_two_leaves);
    tcase_add_test(edges, test_a_flat_cell_is_not_skipped);
    tcase_add_slow_test(edges,
                        test_degenerate_input_keeps_depth_and_memory_bounded);
    tcase_add_test(edges,
                   test_a_ray_through_a_shared_vertex_tests_every_triangle);
    suite_add_tcase(s, edges);
    TCase *shadows = tcase_create("shadow rays");
    tcase_add_checked_fixture(shadows, make_tmpdir, remove_tmpdir);
    tcase_add_test(
        shadows,
        test_a_shadow_ray_through_instances_stops_at_its_first_occluder);
    suite_add_tcase(s, shadows);
    TCase *bad = tcase_create("bad input and the command line");
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(bad, 120);
    tcase_add_test(bad, test_chapters_7_and_8_draw_ties_alike);
    tcase_add_slow_test(bad, test_stats_hint_an_over_fine_mesh);
    tcase_add_test(bad, test_kdtree_statement_sets_the_parameters);
    tcase_add_test(bad, test_kdtree_statement_rejects_bad_settings);
    tcase_add_test(bad, test_the_trees_count_against_the_geometry_budget);
    tcase_add_test(bad,
                   test_running_out_of_memory_anywhere_in_a_load_is_reported);
    suite_add_tcase(s, bad);
    return s;
}
