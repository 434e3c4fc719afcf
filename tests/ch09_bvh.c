/* ch09_bvh.c: chapter 9's bounding volume hierarchy: the same answers as
 * brute force and as chapter 8's kd-tree, bit for bit, at every width;
 * vector and scalar node tests that agree; the same tree on any number of
 * threads; float boxes that hold their items; and its choice in a scene
 * file and on the command line. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "memory.h"
#include "mesh.h"
#include "obj.h"
#include "rng.h"
#include "scene_file.h"
#include "test_util.h"

_Static_assert(sizeof(bvh_node) == 32, "a binary node is 32 bytes");
_Static_assert(sizeof(bvh_node4) == 128, "a 4-wide node, two lines");
_Static_assert(sizeof(bvh_node8) == 256, "an 8-wide node, four lines");

/* From tests/ch08_kdtree.c: its adversarial rays (random, along the axes,
 * at vertices and edges, from the kd-tree's split planes, grazing), count
 * of each kind, and its meshes made from arrays. */
int ch08_adversarial_rays(const mesh *m, ray *rays, int count,
                          uint64_t seed_value);
mesh ch08_make_mesh(const vec3 *points, int n_points, const int (*tris)[3],
                    int n_tris);
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size);

static const rng_state RNG_START = {0xB7Bu};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

static mesh load(const char *path)
{
    mesh m = {0};
    parse_error err;
    ck_assert_msg(mesh_load_obj(&m, path, &err), "%s: %s", path, err.message);
    mesh_compute_bounds(&m);
    return m;
}

/* m sharing its arrays, with no tree: for brute force. */
static mesh bare(const mesh *m)
{
    mesh b = *m;
    b.tree = (kdtree){0}, b.leaf_corners = NULL;
    b.bvh = (bvh){0}, b.bvh_packets = NULL;
    return b;
}

static mesh with_kdtree(const mesh *m)
{
    mesh k = bare(m);
    kdtree_params p = kdtree_default_params();
    p.min_items = 1;
    ck_assert(mesh_build_tree(&k, &p));
    return k;
}

static mesh with_bvh(const mesh *m, int width, int threads)
{
    mesh b = bare(m);
    bvh_params p = {.width = width, .threads = threads, .min_items = 1};
    ck_assert(mesh_build_bvh(&b, &p));
    ck_assert(b.bvh.node_count > 0);
    return b;
}

/* The nearest hit's triangle and t (-1, infinity: none). */
static int nearest(const mesh *m, ray r, double *t)
{
    mesh_ray mr = mesh_ray_of(r);
    render_stats stats = {0};
    triangle_hit th;
    int k = mesh_nearest(m, &mr, 0, INFINITY, &th, &stats);
    *t = k >= 0 ? th.t : INFINITY;
    return k;
}

/* Every width's BVH of m against brute force and the kd-tree on the
 * adversarial rays: the same triangle and the same t, bit for bit; and
 * the same answer to a shadow ray over a random segment. */
static void expect_agreement(const mesh *m, int count, const char *what)
{
    mesh kd = with_kdtree(m), brute = bare(m);
    ray *rays = malloc(5 * (size_t)count * sizeof *rays);
    int n = ch08_adversarial_rays(&kd, rays, count, 0xB0B);
    /* brute force's answers, found once for all three widths */
    double *t_f = malloc((size_t)n * sizeof *t_f);
    int *i_f = malloc((size_t)n * sizeof *i_f), kd_differ = 0;
    for (int k = 0; k < n; k++) {
        double t_k;
        i_f[k] = nearest(&brute, rays[k], &t_f[k]);
        int i_k = nearest(&kd, rays[k], &t_k);
        kd_differ += i_k != i_f[k] || memcmp(&t_k, &t_f[k], sizeof t_k) != 0;
    }
    ck_assert_msg(kd_differ == 0, "%s: the kd-tree differs on %d of %d rays",
                  what, kd_differ, n);
    /* 2, 4 and 8 wide, and 8 again with the walk kept from AVX2 */
    for (int run = 0; run < 4; run++) {
        int width = run < 3 ? 2 << run : 8;
        const char *how = run < 3 ? "" : ", without AVX2";
        bvh_allow_avx2(run < 3);
        mesh b = with_bvh(m, width, 0);
        int differ = 0, shadows = 0;
        for (int k = 0; k < n; k++) {
            double t_b;
            int i_b = nearest(&b, rays[k], &t_b);
            differ += i_b != i_f[k] || memcmp(&t_b, &t_f[k], sizeof t_b) != 0;
            mesh_ray mr = mesh_ray_of(rays[k]);
            render_stats stats = {0};
            double t_max = 5 * rng_uniform01(&rng) * vec3_length(
                               vec3_sub(m->bounds.hi, m->bounds.lo));
            shadows += mesh_occluded(&b, &mr, 1e-9, t_max, &stats) !=
                       mesh_occluded(&brute, &mr, 1e-9, t_max, &stats);
        }
        bvh_allow_avx2(true);
        ck_assert_msg(differ == 0, "%s, %d wide%s: %d of %d rays differ",
                      what, width, how, differ, n);
        ck_assert_msg(shadows == 0, "%s, %d wide%s: %d of %d shadow rays "
                      "differ", what, width, how, shadows, n);
        mesh_free_tree(&b);
    }
    mesh_free_tree(&kd);
    free(rays), free(t_f), free(i_f);
}

/* A grid of 2 n^2 triangles over [-1, 1]^2 in the plane z = 0, moved by
 * offset and scaled by size, with a copy of every triangle (coincident:
 * a tie at every hit, to the lower index). */
static mesh plane_mesh(int n, vec3 offset, double size)
{
    vec3 *p = malloc((size_t)(n + 1) * (n + 1) * sizeof *p);
    int (*t)[3] = malloc(4 * (size_t)n * n * sizeof *t), m = 0;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            p[j * (n + 1) + i] = vec3_add(
                offset, vec3_scale((vec3){-1 + 2.0 * i / n,
                                          -1 + 2.0 * j / n, 0}, size));
    for (int copy = 0; copy < 2; copy++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                t[m][0] = a, t[m][1] = b, t[m++][2] = d;
                t[m][0] = a, t[m][1] = d, t[m++][2] = c;
            }
    mesh out = ch08_make_mesh(p, (n + 1) * (n + 1), (const int(*)[3])t, m);
    free(p), free(t);
    return out;
}

/* A fan of n triangles around one vertex at centre, in the plane z. */
static mesh fan_mesh(int n, vec3 centre)
{
    vec3 *p = malloc((size_t)(n + 1) * sizeof *p);
    int (*t)[3] = malloc((size_t)n * sizeof *t);
    p[0] = centre;
    for (int k = 0; k < n; k++) {
        double a = 2 * M_PI * k / n;
        p[1 + k] = vec3_add(centre, (vec3){cos(a), sin(a), 0});
        t[k][0] = 0, t[k][1] = 1 + k, t[k][2] = 1 + (k + 1) % n;
    }
    mesh out = ch08_make_mesh(p, n + 1, (const int(*)[3])t, n);
    free(p), free(t);
    return out;
}

/* ------------------------------------------------------------ agreement */

START_TEST(test_bvh_agrees_with_brute_force_and_kdtree_on_the_teapot)
{
    mesh m = load("meshes/teapot-8.obj");
    expect_agreement(&m, 400, "teapot");
    mesh_free(&m);
}
END_TEST

START_TEST(test_bvh_agrees_with_brute_force_and_kdtree_on_the_bunny)
{
    mesh m = load("meshes/bunny.obj");
    expect_agreement(&m, 30, "bunny"); /* brute force: 1 ms a ray */
    mesh_free(&m);
}
END_TEST

START_TEST(test_bvh_agrees_on_coincident_triangles_near_and_far)
{
    const vec3 at[3] = {{0, 0, 0}, {1e6, -1e6, 1e6}, {3e-3, 0, 0}};
    const double size[3] = {1, 10, 1e-5};
    for (int k = 0; k < 3; k++) {
        mesh m = plane_mesh(12, at[k], size[k]);
        expect_agreement(&m, 300, "coincident planes");
        mesh_free(&m);
    }
}
END_TEST

START_TEST(test_bvh_agrees_on_fans_through_one_vertex)
{
    mesh m = fan_mesh(300, (vec3){0.25, -0.5, 4});
    expect_agreement(&m, 300, "fan");
    mesh_free(&m);
    m = fan_mesh(64, (vec3){2e6, 1e6, -3e6});
    expect_agreement(&m, 300, "far fan");
    mesh_free(&m);
}
END_TEST

/* Rays along the edges of a grid's triangles, and through its vertices,
 * exactly in the plane of its boxes' faces. */
START_TEST(test_rays_along_edges_and_faces_find_their_hits)
{
    mesh m = plane_mesh(8, (vec3){0, 0, 0}, 1), brute = bare(&m);
    for (int width = 2; width <= 8; width *= 2) {
        mesh b = with_bvh(&m, width, 1);
        for (int k = 0; k <= 8; k++) {
            double y = -1 + 2.0 * k / 8;
            ray rays[4] = {{{-3, y, 0}, {1, 0, 0}}, /* along an edge */
                           {{y, -3, 0}, {0, 1, 0}},
                           {{-3, y, 1e-300}, {1, 0, -1e-300}},
                           {{y, y, 2}, {0, 0, -1}}}; /* at a vertex */
            for (int r = 0; r < 4; r++) {
                double t_b, t_f;
                int i_b = nearest(&b, rays[r], &t_b);
                int i_f = nearest(&brute, rays[r], &t_f);
                ck_assert_msg(i_b == i_f && memcmp(&t_b, &t_f, sizeof t_b) ==
                                  0, "width %d, ray %d at %g: %d at %g, "
                              "brute force %d at %g", width, r, y, i_b, t_b,
                              i_f, t_f);
            }
        }
        mesh_free_tree(&b);
    }
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ nodes */

/* A random float in [-1, 1] times a random power of two, or a face. */
static float random_coordinate(void)
{
    return (float)((2 * rng_uniform01(&rng) - 1) *
                   pow(2, (int)(rng_uniform01(&rng) * 40) - 20));
}

static void random_node(bvh_node8 *n, int lanes)
{
    for (int c = 0; c < 8; c++) {
        for (int a = 0; a < 3; a++) {
            float x = random_coordinate(), y = random_coordinate();
            n->box[a][c] = x < y ? x : y, n->box[a + 3][c] = x < y ? y : x;
            if (c >= lanes) /* unused: empty */
                n->box[a][c] = INFINITY, n->box[a + 3][c] = -INFINITY;
        }
        n->child[c] = c < lanes ? (uint32_t)c : BVH_NO_CHILD, n->count[c] = 0;
    }
}

/* A ray at the node: from one of its faces, along an axis, or random. */
static ray random_ray(const bvh_node8 *n, int k)
{
    ray r = {{random_coordinate(), random_coordinate(), random_coordinate()},
             {random_coordinate(), random_coordinate(), random_coordinate()}};
    if (k % 3 == 0) /* on a face's plane and parallel to it: 0 * inf */
        r.origin.x = n->box[k % 2 ? 0 : 3][k % 8], r.dir.x = 0;
    if (k % 5 == 0) /* from a corner, along an edge */
        r.origin = (vec3){n->box[0][k % 8], n->box[1][k % 8], n->box[5][k % 8]},
        r.dir = (vec3){k % 2 ? 1 : -0.0, 0, 0};
    return r;
}

START_TEST(test_vector_and_scalar_node_tests_agree)
{
    bvh_node8 n8;
    bvh_node4 n4;
    int hits = 0;
    for (int k = 0; k < 20000; k++) {
        random_node(&n8, 1 + k % 8);
        for (int f = 0; f < 6; f++)
            memcpy(n4.box[f], n8.box[f], sizeof n4.box[f]);
        ray r = random_ray(&n8, k);
        bvh_ray br;
        if (!bvh_ray_of(r.origin, ray_inverse_dir(r), 0, INFINITY, &br))
            continue;
        float t_max = k % 4 ? INFINITY : (float)rng_uniform01(&rng);
        float v8[8], s8[8], v4[4], s4[4];
        unsigned m8 = bvh_node8_test_vector(&n8, &br, t_max, v8);
        if (bvh_walks_with_avx2()) { /* AVX2's eight lanes as well */
            float a8[8];
            ck_assert_uint_eq(bvh_node8_test_avx2(&n8, &br, t_max, a8), m8);
            ck_assert(memcmp(a8, v8, sizeof a8) == 0);
        }
        unsigned m4 = bvh_node4_test_vector(&n4, &br, t_max, v4);
        ck_assert_uint_eq(m8, bvh_lanes_test_scalar(&n8.box[0][0], 8, 8, &br,
                                                    t_max, s8));
        ck_assert_uint_eq(m4, bvh_lanes_test_scalar(&n4.box[0][0], 4, 4, &br,
                                                    t_max, s4));
        ck_assert(memcmp(v8, s8, sizeof v8) == 0);
        ck_assert(memcmp(v4, s4, sizeof v4) == 0);
        hits += __builtin_popcount(m8);
    }
    ck_assert_int_gt(hits, 1000); /* the rays meet boxes, not only miss */
}
END_TEST

/* A ray that runs in the plane of a box's face meets the box. */
START_TEST(test_a_ray_in_a_face_plane_meets_the_box)
{
    float box[6] = {0, 0, 0, 1, 1, 1}, t_near;
    const ray rays[] = {{{-1, 0.5, 0}, {1, 0, 0}},    /* in the face z = 0 */
                        {{-1, 0, 1}, {1, 0, 0}},      /* along an edge */
                        {{0.5, 0.5, 1}, {0, 0, -1}},  /* from the top face */
                        {{1, 1, 1}, {-1, -1, -1}}};   /* from a corner */
    for (size_t k = 0; k < sizeof rays / sizeof *rays; k++) {
        bvh_ray br;
        ck_assert(bvh_ray_of(rays[k].origin, ray_inverse_dir(rays[k]), 0,
                             INFINITY, &br));
        ck_assert_msg(bvh_lanes_test_scalar(box, 1, 1, &br, INFINITY,
                                            &t_near) == 1, "ray %zu", k);
    }
}
END_TEST

/* A node's children as the walk takes them: the nearest in hand, the
 * others on the stack farthest at the bottom; for any hit, in the order
 * of their lanes; none, nothing pushed. */
START_TEST(test_the_walk_takes_the_nearest_child_and_stacks_the_rest)
{
    const uint32_t child[4] = {10, 11, 12, 13}, count[4] = {0, 1, 0, 2};
    const float t_near[4] = {3, 1, 4, 2};
    static bvh_walk w; /* its stack is large: not on the test's stack */
    bvh_todo next;
    w.pending = 0, w.sorted = true;
    ck_assert(!bvh_take(&w, 0, child, count, t_near, &next));
    ck_assert_int_eq(w.pending, 0);
    ck_assert(bvh_take(&w, 1u << 2, child, count, t_near, &next));
    ck_assert_int_eq(w.pending, 0); /* one child: straight to it */
    ck_assert_uint_eq(next.child, 12);
    ck_assert(bvh_take(&w, 0xf, child, count, t_near, &next));
    ck_assert_uint_eq(next.child, 11);
    ck_assert_uint_eq(next.count, 1);
    ck_assert(next.t_near == 1);
    ck_assert_int_eq(w.pending, 3);
    const uint32_t sorted[3] = {12, 10, 13}; /* t_near 4, 3, 2 */
    for (int k = 0; k < 3; k++)
        ck_assert_uint_eq(w.stack[k].child, sorted[k]);
    w.pending = 0, w.sorted = false;
    ck_assert(bvh_take(&w, 0xf, child, count, t_near, &next));
    ck_assert_uint_eq(next.child, 10);
    for (int k = 0; k < 3; k++)
        ck_assert_uint_eq(w.stack[k].child, child[k + 1]);
}
END_TEST

/* ------------------------------------------------------------ the build */

/* count random boxes around centre, sizes up to size (some zero). */
static box *random_boxes(int count, vec3 centre, double spread, double size)
{
    box *b = malloc((size_t)count * sizeof *b);
    for (int k = 0; k < count; k++) {
        vec3 c = vec3_add(centre, vec3_scale(rng_unit_vector(&rng, 1e-3),
                                             spread * rng_uniform01(&rng)));
        vec3 e = vec3_scale((vec3){rng_uniform01(&rng), rng_uniform01(&rng),
                                   rng_uniform01(&rng)},
                            k % 7 ? size : 0);
        b[k] = (box){vec3_sub(c, e), vec3_add(c, e)};
    }
    return b;
}

/* Does the float box f hold the double box b? */
static bool holds(const float f[6], const box *b)
{
    for (int a = 0; a < 3; a++)
        if (!(f[a] <= vec3_axis(b->lo, a) && vec3_axis(b->hi, a) <= f[a + 3]))
            return false;
    return true;
}

/* Every leaf of t's binary nodes holds its items, every node its
 * children: the items below it. */
static void expect_boxes_hold(const bvh *t, const box *bounds)
{
    for (int k = 0; k < t->node_count; k++) {
        const bvh_node *n = &t->nodes[k];
        for (int i = 0; i < n->count; i++)
            ck_assert_msg(holds(n->box, &bounds[t->items[n->index + i]]),
                          "node %d, item %d", k, t->items[n->index + i]);
        for (int c = 0; n->count == 0 && c < 2; c++) {
            const float *kid = t->nodes[c ? n->index : (uint32_t)k + 1].box;
            box b = {{kid[0], kid[1], kid[2]}, {kid[3], kid[4], kid[5]}};
            ck_assert(holds(n->box, &b));
        }
    }
}

START_TEST(test_float_boxes_hold_their_items)
{
    const vec3 centres[3] = {{0.1, 0.2, 0.3}, {1e6, -1e6, 3e6}, {7, 7, 7}};
    const double spread[3] = {1, 1, 1e-12}, size[3] = {0.1, 1e-9, 1e-15};
    for (int k = 0; k < 3; k++) {
        box *b = random_boxes(5000, centres[k], spread[k], size[k]);
        bvh t;
        ck_assert(bvh_build(&t, 5000, b, &(bvh_params){.width = 2}));
        ck_assert_int_eq(t.item_count, 5000);
        expect_boxes_hold(&t, b);
        bvh_free(&t);
        free(b);
    }
}
END_TEST

/* The wide nodes' lanes hold the items of their leaves. */
START_TEST(test_wide_nodes_hold_their_leaves_items)
{
    box *b = random_boxes(3000, (vec3){1e6, 2, -3}, 10, 0.5);
    for (int width = 4; width <= 8; width *= 2) {
        bvh t;
        ck_assert(bvh_build(&t, 3000, b, &(bvh_params){.width = width}));
        int items = 0;
        for (int k = 0; k < t.node_count; k++)
            for (int c = 0; c < width; c++) {
                const float *box = width == 4 ? &t.nodes4[k].box[0][0]
                                              : &t.nodes8[k].box[0][0];
                uint32_t first = width == 4 ? t.nodes4[k].child[c]
                                            : t.nodes8[k].child[c];
                uint32_t n = width == 4 ? t.nodes4[k].count[c]
                                        : t.nodes8[k].count[c];
                for (uint32_t i = 0; i < n; i++, items++) {
                    float f[6];
                    for (int face = 0; face < 6; face++)
                        f[face] = box[face * width + c];
                    ck_assert(holds(f, &b[t.items[first + i]]));
                }
            }
        ck_assert_int_eq(items, 3000); /* every item in exactly one leaf */
        bvh_free(&t);
    }
    free(b);
}
END_TEST

static size_t node_bytes(const bvh *t)
{
    size_t size = t->width == 2 ? sizeof(bvh_node)
                  : t->width == 4 ? sizeof(bvh_node4) : sizeof(bvh_node8);
    return (size_t)t->node_count * size;
}

static const void *node_array(const bvh *t)
{
    return t->width == 2 ? (const void *)t->nodes
           : t->width == 4 ? (const void *)t->nodes4 : (const void *)t->nodes8;
}

START_TEST(test_thread_counts_build_the_same_tree)
{
    mesh m = load("meshes/bunny.obj");
    for (int width = 2; width <= 8; width *= 2) {
        mesh one = with_bvh(&m, width, 1);
        const int threads[] = {2, 3, 8, 0};
        for (int k = 0; k < 4; k++) {
            mesh many = with_bvh(&m, width, threads[k]);
            ck_assert_int_eq(many.bvh.node_count, one.bvh.node_count);
            ck_assert_msg(memcmp(node_array(&many.bvh), node_array(&one.bvh),
                                 node_bytes(&one.bvh)) == 0,
                          "width %d, %d threads: other nodes", width,
                          threads[k]);
            ck_assert(memcmp(many.bvh.items, one.bvh.items,
                             (size_t)m.triangle_count * sizeof(int)) == 0);
            ck_assert_int_eq(many.bvh_packet_count, one.bvh_packet_count);
            ck_assert(memcmp(many.bvh_packets, one.bvh_packets,
                             (size_t)one.bvh_packet_count *
                                 sizeof(triangle_packet)) == 0);
            mesh_free_tree(&many);
        }
        mesh_free_tree(&one);
    }
    mesh_free(&m);
}
END_TEST

/* Boxes enough for the top's passes to be shared (several times
 * BVH_SHARED_ITEMS), on a coarse grid so that many centers coincide, some
 * at the origin with either sign of zero: the slices' boxes, bins and
 * partitions make the tree that one thread makes, to the bit. */
START_TEST(test_thread_counts_build_the_same_tree_over_many_items)
{
    int n = 5 * BVH_SHARED_ITEMS + 17;
    box *b = malloc((size_t)n * sizeof *b);
    ck_assert_ptr_nonnull(b);
    for (int k = 0; k < n; k++) {
        vec3 c = {(double)(rng_next(&rng) % 64) - 32,
                  (double)(rng_next(&rng) % 8),
                  rng_uniform(&rng, -1, 1)};
        c = k % 7 == 0 ? (vec3){k % 2 ? -0.0 : 0.0, k % 3 ? -0.0 : 0.0,
                                k % 5 ? -0.0 : 0.0}
                       : c;
        b[k] = (box){c, vec3_add(c, (vec3){0.5, k % 11 ? 0.25 : 0, 0})};
    }
    for (int width = 2; width <= 8; width *= 2) {
        bvh one, many;
        ck_assert(bvh_build(&one, n, b,
                            &(bvh_params){.width = width, .threads = 1}));
        const int threads[] = {2, 3, 5};
        for (int k = 0; k < 3; k++) {
            ck_assert(bvh_build(&many, n, b,
                                &(bvh_params){.width = width,
                                              .threads = threads[k]}));
            ck_assert_int_eq(many.node_count, one.node_count);
            ck_assert_msg(memcmp(node_array(&many), node_array(&one),
                                 node_bytes(&one)) == 0,
                          "width %d, %d threads: other nodes", width,
                          threads[k]);
            ck_assert(memcmp(many.items, one.items,
                             (size_t)n * sizeof(int)) == 0);
            bvh_free(&many);
        }
        bvh_free(&one);
    }
    free(b);
}
END_TEST

START_TEST(test_a_build_starts_no_more_threads_than_tasks)
{
    /* eight triangles are one task: the calling thread alone, whatever
     * the count asked for; the bunny's tasks share out over the threads */
    mesh small = fan_mesh(8, (vec3){0.25, -0.5, 4});
    for (int width = 2; width <= 8; width *= 2) {
        mesh b = with_bvh(&small, width, 256);
        ck_assert_msg(b.bvh.build_threads == 1,
                      "8 triangles, %d wide: %d threads", width,
                      b.bvh.build_threads);
        mesh_free_tree(&b);
    }
    mesh_free(&small);
    mesh bunny = load("meshes/bunny.obj");
    mesh b = with_bvh(&bunny, 4, 3);
    ck_assert_int_eq(b.bvh.build_threads, 3);
    mesh_free_tree(&b);
    mesh_free(&bunny);
}
END_TEST

/* The leaf of reference c of node k of t (count 0: none): its first
 * packet and its triangles. */
static uint32_t leaf_of(const bvh *t, int k, int c, uint32_t *count)
{
    if (t->width == 2)
        return *count = t->nodes[k].count, t->nodes[k].index;
    if (t->width == 4)
        return *count = t->nodes4[k].count[c], t->nodes4[k].child[c];
    return *count = t->nodes8[k].count[c], t->nodes8[k].child[c];
}

START_TEST(test_every_leaf_s_packets_hold_its_triangles)
{
    mesh m = load("meshes/teapot-8.obj");
    for (int width = 2; width <= 8; width *= 2) {
        mesh b = with_bvh(&m, width, 1);
        int *seen = memory_alloc((size_t)m.triangle_count, sizeof *seen);
        ck_assert_ptr_nonnull(seen);
        memset(seen, 0, (size_t)m.triangle_count * sizeof *seen);
        int packets = 0, refs = width == 2 ? 1 : width;
        for (int k = 0; k < b.bvh.node_count; k++)
            for (int c = 0; c < refs; c++) {
                uint32_t count, first = leaf_of(&b.bvh, k, c, &count);
                int n = (int)(count + PACKET_W - 1) / PACKET_W;
                for (int lane = 0; lane < n * PACKET_W; lane++) {
                    const triangle_packet *q = &b.bvh_packets[first +
                                                lane / PACKET_W];
                    int i = q->triangle[lane % PACKET_W];
                    ck_assert_int_eq(i >= 0, lane < (int)count);
                    if (i < 0)
                        continue;
                    seen[i]++;
                    vec3 v = m.vertices[m.triangles[i].v[2]];
                    ck_assert(q->corner[2][1][lane % PACKET_W] == (float)v.y);
                }
                packets += n;
            }
        for (int i = 0; i < m.triangle_count; i++)
            ck_assert_int_eq(seen[i], 1); /* each in exactly one lane */
        ck_assert_int_eq(packets, b.bvh_packet_count);
        free(seen);
        mesh_free_tree(&b);
    }
    mesh_free(&m);
}
END_TEST

START_TEST(test_the_bvh_of_a_mesh_stays_within_its_bytes)
{
    const char *paths[] = {"meshes/bunny.obj", "meshes/teapot-8.obj"};
    for (int k = 0; k < 2; k++) {
        mesh m = load(paths[k]);
        mesh b = bare(&m);
        ck_assert(mesh_build_bvh(&b, &(bvh_params){0}));
        double bytes = (double)mesh_tree_bytes(&b) / m.triangle_count;
        ck_assert_msg(bytes <= MESH_BVH_MAX_BYTES_PER_TRIANGLE,
                      "%s: %.1f bytes a triangle", paths[k], bytes);
        mesh_free_tree(&b);
        mesh_free(&m);
    }
}
END_TEST

START_TEST(test_running_out_of_memory_in_a_build_leaves_no_tree)
{
    mesh m = load("meshes/teapot-8.obj");
    int failed = 0;
    for (long n = 0; n < 12; n++) {
        mesh b = bare(&m);
        memory_fail_after(n);
        bool ok = mesh_build_bvh(&b, &(bvh_params){.width = 4 << (n % 2)});
        memory_fail_after(-1);
        failed += !ok;
        ck_assert(ok || (b.bvh.node_count == 0 && b.bvh_packets == NULL));
        mesh_free_tree(&b);
    }
    ck_assert_int_gt(failed, 3);
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ choosing it */

START_TEST(test_the_accelerator_statement_chooses_the_tree)
{
    link_meshes();
    /* the default; each statement; a heat map of kd-tree nodes; and
     * --accelerator (set before the file is read) over the statement */
    const char *texts[7] = {
        "mesh file meshes/teapot-8.obj\n",
        "accelerator kdtree\nmesh file meshes/teapot-8.obj\n",
        "accelerator bvh\nmesh file meshes/teapot-8.obj\n",
        "kdtree heatmap 9\nmesh file meshes/teapot-8.obj\n",
        "accelerator kdtree\nmesh file meshes/teapot-8.obj\n",
        "accelerator bvh-float\nmesh file meshes/teapot-8.obj\n",
        "accelerator bvh-float\nmesh file meshes/teapot-8.obj\n"};
    const bool wants_bvh[7] = {
        MESH_DEFAULT_ACCELERATOR == MESH_ACCELERATOR_BVH, false, true, false,
        true, true, true};
    const bool in_float[7] = {false, false, false, false, false, true, false};
    for (int k = 0; k < 7; k++) {
        scene s;
        scene_error err;
        char *path = (char *)write_file("choose.scene", texts[k]);
        scene_init(&s);
        if (k == 4 || k == 6)
            s.accelerator_option = MESH_ACCELERATOR_BVH;
        ck_assert_msg(scene_load(&s, path, &err), "%s", err.message);
        bool bvh = wants_bvh[k];
        ck_assert_int_eq(s.meshes[0].bvh.node_count > 0, bvh);
        ck_assert_int_eq(s.meshes[0].tree.node_count > 0, !bvh);
        ck_assert_int_eq(s.meshes[0].bvh_in_float, in_float[k]);
        scene_free(&s);
    }
}
END_TEST

/* The teapot's scene with a BVH, within a geometry budget of bytes; the
 * geometry counted. */
static bool parse_bvh_within(long long bytes, scene_error *err,
                             long long *total)
{
    scene s;
    const char *text = "accelerator bvh\nmesh file meshes/teapot-8.obj\n";
    scene_init(&s);
    s.geometry_budget = bytes;
    bool ok = scene_parse(&s, text, strlen(text), "budget.scene", err);
    *total = s.geometry_total;
    scene_free(&s);
    return ok;
}

START_TEST(test_the_bvh_counts_against_the_geometry_budget)
{
    scene_error err; /* meshes/ from the current folder, as chapter 8's */
    long long with_bvh, total;
    ck_assert_msg(parse_bvh_within(SCENE_MAX_GEOMETRY_BYTES, &err, &with_bvh),
                  "%s", err.message);
    ck_assert(!parse_bvh_within(with_bvh - 1, &err, &total));
    expect_error_at(&err, "budget.scene", 2, 1,
                    "the BVH of mesh file 'meshes/teapot-8.obj' would pass "
                    "the scene's budget of", "a BVH over the budget");
    ck_assert_int_eq(err.kind, PARSE_OVER_BUDGET);
}
END_TEST

START_TEST(test_bad_accelerator_statements_are_located)
{
    expect_parse_error("accelerator octree\n", 1, 13, "accelerator (kdtree");
    expect_parse_error("accelerator\n", 1, 12, "accelerator (kdtree");
    expect_parse_error("accelerator bvh 4\n", 1, 17, "end of line");
    expect_parse_error("accelerator bvh\n\naccelerator kdtree\n", 3, 1,
                       "first is on line 1");
    expect_parse_error("accelerator BVH\n", 1, 13, "accelerator (kdtree");
    expect_parse_error("accelerator bvh-double\n", 1, 13,
                       "accelerator (kdtree, bvh, bvh-float)");
}
END_TEST

START_TEST(test_bad_accelerator_options_are_usage_errors)
{
    const char *bad[] = {"octree", "", "BVH", "bvh4", "bvh-floats"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        char errors[1024];
        const char *out = tmp_path("never.png");
        const char *args[] = {"--accelerator", bad[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "--accelerator expects kdtree, bvh or "
                                     "bvh-float"),
                      "%s", errors);
        ck_assert(!file_exists(out));
    }
    char errors[1024];
    const char *args[] = {"--accelerator", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_ptr_nonnull(strstr(errors, "needs a value"));
}
END_TEST

START_TEST(test_a_kd_tree_heat_map_over_bvhs_is_refused)
{
    /* the heat map counts kd-tree nodes: over BVHs it would be black */
    expect_parse_error("kdtree heatmap 60\naccelerator bvh\nimage 8 6\n", 2,
                       1, "heat map draws kd-tree nodes");
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s, "kdtree heatmap 60\naccelerator kdtree\n",
                             &err), "%s", err.message);
    scene_free(&s);
    char errors[1024], out[200], scene[200]; /* tmp_path's buffer is reused */
    snprintf(scene, sizeof scene, "%s",
             write_file("heat.scene", "kdtree heatmap 60\n"));
    snprintf(out, sizeof out, "%s", tmp_path("never.png"));
    const char *args[] = {scene, "--accelerator", "bvh", "-o", out, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "--accelerator bvh gives the meshes BVHs"),
                  "%s", errors);
    ck_assert(!file_exists(out));
    args[2] = "bvh-float";
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "--accelerator bvh-float gives the meshes"),
                  "%s", errors);
    ck_assert(!file_exists(out));
    expect_parse_error("kdtree heatmap 60\naccelerator bvh-float\n", 2, 1,
                       "heat map draws kd-tree nodes");
}
END_TEST

static char *read_whole(const char *path, size_t *length)
{
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    char *data = malloc(1 << 21);
    *length = fread(data, 1, 1 << 21, f);
    fclose(f);
    return data;
}

/* scene_path drawn with --accelerator kdtree and bvh, at --size size
 * (NULL: the scene's): the same bytes. */
static void expect_same_with_either(const char *scene_path, const char *size)
{
    size_t n[2];
    char *png[2], errors[4096];
    const char *names[2] = {"kdtree", "bvh"};
    for (int k = 0; k < 2; k++) {
        const char *args[] = {scene_path, "--accelerator", names[k], "--stats",
                              "-o", tmp_path("either.png"), size ? "--size"
                              : NULL, size, NULL};
        ck_assert_msg(run_bin(args, errors, sizeof errors) == 0, "%s", errors);
        ck_assert_int_eq(strstr(errors, "bvhs ") != NULL, k == 1);
        png[k] = read_whole(tmp_path("either.png"), &n[k]);
    }
    ck_assert_msg(n[0] == n[1] && memcmp(png[0], png[1], n[0]) == 0,
                  "%s: the BVH draws another picture", scene_path);
    free(png[0]), free(png[1]);
}

START_TEST(test_the_bunny_scene_is_the_same_with_either_tree)
{
    /* the committed tangle's scene, or (a handout has no src/) the
     * build's */
    const char *scene = "src/ch09/scenes/ch08-bunny.scene";
    if (!file_exists(scene))
        scene = "build/tangle/ch09/scenes/ch08-bunny.scene";
    expect_same_with_either(scene, "200x150");
}
END_TEST

START_TEST(test_ties_come_out_the_same_with_either_tree)
{
    static char obj[1 << 18], lone[1 << 19];
    tie_scene_texts(obj, sizeof obj, lone, sizeof lone);
    write_file("fans.obj", obj);
    char path[256]; /* tmp_path's buffer is reused */
    snprintf(path, sizeof path, "%s",
             write_file("fans.scene",
                        "image 48 36\nmesh file fans.obj color 0.9 0.7 0.4\n"));
    expect_same_with_either(path, NULL);
}
END_TEST

Suite *ch09_bvh_suite(void)
{
    Suite *s = suite_create("ch09 bvh");
    TCase *agree = tcase_create("agreement");
    tcase_add_checked_fixture(agree, reseed, NULL);
    tcase_set_timeout(agree, 120);
    tcase_add_test(agree,
                   test_bvh_agrees_with_brute_force_and_kdtree_on_the_teapot);
    tcase_add_slow_test(agree,
                   test_bvh_agrees_with_brute_force_and_kdtree_on_the_bunny);
    tcase_add_test(agree, test_bvh_agrees_on_coincident_triangles_near_and_far);
    tcase_add_test(agree, test_bvh_agrees_on_fans_through_one_vertex);
    tcase_add_test(agree, test_rays_along_edges_and_faces_find_their_hits);
    suite_add_tcase(s, agree);
    TCase *nodes = tcase_create("nodes and builds");
    tcase_add_checked_fixture(nodes, reseed, NULL);
    tcase_set_timeout(nodes, 120);
    tcase_add_test(nodes, test_vector_and_scalar_node_tests_agree);
    tcase_add_test(nodes, test_a_ray_in_a_face_plane_meets_the_box);
    tcase_add_test(nodes,
                   test_the_walk_takes_the_nearest_child_and_stacks_the_rest);
    tcase_add_test(nodes, test_float_boxes_hold_their_items);
    tcase_add_test(nodes, test_wide_nodes_hold_their_leaves_items);
    tcase_add_threaded_test(nodes, test_thread_counts_build_the_same_tree);
    tcase_add_test(nodes,
                   test_thread_counts_build_the_same_tree_over_many_items);
    tcase_add_test(nodes, test_a_build_starts_no_more_threads_than_tasks);
    tcase_add_test(nodes, test_running_out_of_memory_in_a_build_leaves_no_tree);
    tcase_add_test(nodes, test_every_leaf_s_packets_hold_its_triangles);
    tcase_add_test(nodes, test_the_bvh_of_a_mesh_stays_within_its_bytes);
    suite_add_tcase(s, nodes);
    TCase *choose = tcase_create("choosing it");
    tcase_add_checked_fixture(choose, reseed, NULL);
    tcase_add_checked_fixture(choose, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(choose, 120);
    tcase_add_test(choose, test_the_accelerator_statement_chooses_the_tree);
    tcase_add_test(choose, test_bad_accelerator_statements_are_located);
    tcase_add_test(choose, test_the_bvh_counts_against_the_geometry_budget);
    tcase_add_test(choose, test_bad_accelerator_options_are_usage_errors);
    tcase_add_test(choose, test_a_kd_tree_heat_map_over_bvhs_is_refused);
    tcase_add_test(choose, test_the_bunny_scene_is_the_same_with_either_tree);
    tcase_add_test(choose, test_ties_come_out_the_same_with_either_tree);
    suite_add_tcase(s, choose);
    return s;
}
