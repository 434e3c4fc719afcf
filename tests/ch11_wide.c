/* ch11_wide.c: chapter 11's wide nodes: the same answers as brute force
 * and as chapter 8's kd-tree, bit for bit, at widths 4 and 8 (with AVX2
 * or AVX-512VL chosen at run time, and without); the vector pushes as the
 * plain one; vector and scalar node tests that
 * agree, and a fused test that never loses a box; octant orders and
 * pushes; wide nodes and their leaves' packets that hold their items;
 * the wide BVH's bytes. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "memory.h"
#include "mesh.h"
#include "rng.h"
#include "scene_file.h"
#include "test_util.h"

_Static_assert(sizeof(bvh_node8) == 256, "an 8-wide node, four lines");

/* From tests/ch09_bvh.c. */
mesh ch09_load(const char *path);
mesh ch09_bare(const mesh *m);
mesh ch09_with_bvh(const mesh *m, const bvh_params *p);
void ch09_expect_agreement(const mesh *m, int count, const char *what,
                           const bvh_params *p);
mesh ch09_plane_mesh(int n, vec3 offset, double size);
mesh ch09_fan_mesh(int n, vec3 centre);
void ch09_expect_edges_and_faces(const bvh_params *p);
void ch10_expect_packets_hold_each_triangle(
    const mesh *m, const mesh *b, int refs,
    uint32_t (*leaf_of)(const bvh *, int, int, uint32_t *));
box *ch09_random_boxes(rng_state *r, int count, vec3 centre, double spread,
                       double size);
bool ch09_holds(const float f[6], const box *b);

static const rng_state RNG_START = {0xB7Bu};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

/* m's BVH 4 wide (its walk AVX2's at most), 8 wide (AVX-512VL's where
 * the processor has it), and 8 again with the walk kept from AVX2,
 * against brute force and the kd-tree. */
static void expect_agreement(const mesh *m, int count, const char *what)
{
    for (int run = 0; run < 3; run++) {
        bvh_allow_avx2(run < 2);
        bvh_allow_avx512(run != 0);
        ch09_expect_agreement(m, count, what,
                              &(bvh_params){.width = run == 0 ? 4 : 8});
        bvh_allow_avx2(true);
        bvh_allow_avx512(true);
    }
}

START_TEST(test_wide_bvh_agrees_with_brute_force_and_kdtree_on_the_teapot)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    expect_agreement(&m, 400, "teapot");
    mesh_free(&m);
}
END_TEST

START_TEST(test_wide_bvh_agrees_with_brute_force_and_kdtree_on_the_bunny)
{
    mesh m = ch09_load("meshes/bunny.obj");
    expect_agreement(&m, 30, "bunny"); /* brute force: 1 ms a ray */
    mesh_free(&m);
}
END_TEST

START_TEST(test_wide_bvh_agrees_on_coincident_triangles_near_and_far)
{
    const vec3 at[3] = {{0, 0, 0}, {1e6, -1e6, 1e6}, {3e-3, 0, 0}};
    const double size[3] = {1, 10, 1e-5};
    for (int k = 0; k < 3; k++) {
        mesh m = ch09_plane_mesh(12, at[k], size[k]);
        expect_agreement(&m, 300, "coincident planes");
        mesh_free(&m);
    }
}
END_TEST

START_TEST(test_wide_bvh_agrees_on_fans_through_one_vertex)
{
    mesh m = ch09_fan_mesh(300, (vec3){0.25, -0.5, 4});
    expect_agreement(&m, 300, "fan");
    mesh_free(&m);
    m = ch09_fan_mesh(64, (vec3){2e6, 1e6, -3e6});
    expect_agreement(&m, 300, "far fan");
    mesh_free(&m);
}
END_TEST

START_TEST(test_wide_rays_along_edges_and_faces_find_their_hits)
{
    ch09_expect_edges_and_faces(&(bvh_params){.width = 4});
    ch09_expect_edges_and_faces(&(bvh_params){.width = 8});
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
            n->face[2 * a][c] = x < y ? x : y;
            n->face[2 * a + 1][c] = x < y ? y : x;
            if (c >= lanes) /* unused: empty */
                n->face[2 * a][c] = INFINITY, n->face[2 * a + 1][c] = -INFINITY;
        }
        n->child[c] = (uint32_t)c;
    }
}

/* A ray at the node: from one of its faces, along an axis, or random. */
static ray random_ray(const bvh_node8 *n, int k)
{
    ray r = {{random_coordinate(), random_coordinate(), random_coordinate()},
             {random_coordinate(), random_coordinate(), random_coordinate()}};
    if (k % 3 == 0) /* on a face's plane and parallel to it: 0 * inf */
        r.origin.x = n->face[k % 2 ? 0 : 1][k % 8], r.dir.x = 0;
    if (k % 5 == 0) /* from a corner, along an edge */
        r.origin = (vec3){n->face[0][k % 8], n->face[2][k % 8],
                          n->face[5][k % 8]},
        r.dir = (vec3){k % 2 ? 1 : -0.0, 0, 0};
    return r;
}

/* Lane c of the fused test (AVX2 with FMA), alone: fmaf's one rounding
 * a face, the numbers of v. Where the ray enters into *enter; does it
 * meet the box? (Neither bound can become a NaN: a NaN never wins.) */
static bool fused_lane(const bvh_node8 *n, int c, const bvh_ray8 *v,
                       float t_max, float *enter)
{
    float lo = v->t_min, hi = t_max;
    for (int a = 0; a < 3; a++) {
        const char *node = (const char *)n;
        float f0 = ((const float *)(node + v->rows[2 * a]))[c];
        float f1 = ((const float *)(node + v->rows[2 * a + 1]))[c];
        float e = fmaf(f0, v->inv[a][0], v->zero_near[a][0]);
        float x = fmaf(f1, v->inv_far[a][0], v->zero_far[a][0]);
        if (e > lo)
            lo = e;
        if (x < hi)
            hi = x;
    }
    *enter = lo;
    return lo <= hi; /* the exits widened by inv_far */
}

/* Does the ray r meet lane c's box in [0, t_max], in double with 1 / d
 * exact to double's rounding, by a margin (2^-40, relative) far above
 * that rounding and far below float's? *t0: where it enters. */
static bool clearly_meets(const bvh_node8 *n, int c, ray r, double t_max,
                          double *t0)
{
    double lo = 0, hi = t_max;
    for (int a = 0; a < 3; a++) {
        double o = vec3_axis(r.origin, a), d = vec3_axis(r.dir, a);
        double f0 = n->face[2 * a][c], f1 = n->face[2 * a + 1][c];
        if (!(f0 <= f1))
            return false; /* an unused lane */
        if (d == 0) {
            if (o < f0 || o > f1)
                return false;
            continue;
        }
        double e = (f0 - o) / d, x = (f1 - o) / d;
        lo = fmax(lo, fmin(e, x)), hi = fmin(hi, fmax(e, x));
    }
    *t0 = lo;
    return lo * (1 + 0x1p-40) + 0x1p-1000 < hi;
}

START_TEST(test_vector_and_scalar_node_tests_agree)
{
    bvh_node8 n8;
    int hits = 0;
    for (int k = 0; k < 20000; k++) {
        random_node(&n8, 1 + k % 8);
        float box[6 * 8]; /* the same boxes, faces as bvh_node's */
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 8; c++)
                box[a * 8 + c] = n8.face[2 * a][c],
                box[(a + 3) * 8 + c] = n8.face[2 * a + 1][c];
        ray r = random_ray(&n8, k);
        bvh_ray br, rows;
        if (!bvh_ray_of(r.origin, ray_inverse_dir(r), 0, INFINITY, &br))
            continue;
        rows = br;
        bvh_walk_rows(&rows);
        float t_max = k % 4 ? INFINITY : (float)rng_uniform01(&rng);
        float v8[8], s8[8], b8[8];
        unsigned m8 = bvh_node8_test(&n8, &rows, t_max, v8);
        if (bvh_walks_with_avx2()) { /* AVX2's fused test as well */
            float a8[8], f8[8];
            bvh_ray8 v = bvh_ray8_of(&rows);
            bvh_ray8_fused(&v, &rows);
            unsigned fused = bvh_node8_test_avx2(&n8, &rows, t_max, a8);
            float m_near[8];
            int32_t met[8]; /* the same lanes, as a push reads them */
            ck_assert_uint_eq(bvh_node8_lanes_avx2(&n8, &v, t_max, m_near, met),
                              fused);
            for (int c = 0; c < 8; c++)
                ck_assert_int_eq(met[c], (fused >> c & 1) ? -1 : 0);
            unsigned alone = 0;
            for (int c = 0; c < 8; c++)
                if (fused_lane(&n8, c, &v, t_max, &f8[c]))
                    alone |= 1u << c;
            ck_assert_uint_eq(fused, alone);
            ck_assert(memcmp(a8, f8, sizeof a8) == 0);
            for (int c = 0; c < 8; c++) { /* it never loses a box */
                double t0;
                if (!clearly_meets(&n8, c, r, t_max, &t0))
                    continue;
                ck_assert_msg(fused >> c & 1, "ray %d misses lane %d", k, c);
                ck_assert(a8[c] <= t0 * (1 + 0x1p-21) + 0x1p-140);
            }
        }
        ck_assert_uint_eq(m8, bvh_lanes_test_scalar(&n8.face[0][0], 8, 8,
                                                    &rows, t_max, s8));
        ck_assert_uint_eq(m8, bvh_lanes_test_scalar(box, 8, 8, &br, t_max,
                                                    b8));
        ck_assert(memcmp(v8, s8, sizeof v8) == 0);
        ck_assert(memcmp(v8, b8, sizeof v8) == 0);
        hits += __builtin_popcount(m8);
    }
    ck_assert_int_gt(hits, 1000); /* the rays meet boxes, not only miss */
}
END_TEST

/* Each octant's order is the eight lanes, the used ones farthest first
 * along its diagonal. */
/* A point of lane c's box just inside one of its corners: inside each
 * slab by 2^-30 of the slab's width. */
static vec3 just_inside_a_corner(const bvh_node8 *n, int c, int corner)
{
    double p[3];
    for (int a = 0; a < 3; a++) {
        double lo = n->face[2 * a][c], hi = n->face[2 * a + 1][c];
        double in = (hi - lo) * 0x1p-30;
        p[a] = corner >> a & 1 ? hi - in : lo + in;
    }
    return (vec3){p[0], p[1], p[2]};
}

/* A ray aimed just inside a box's corner meets it clearly in double,
 * while its entry and exit differ by less than float's rounding: the
 * exits' widening alone keeps such a box. */
START_TEST(test_the_fused_test_keeps_a_box_met_just_inside_a_corner)
{
    if (!bvh_walks_with_avx2())
        return; /* no fused test to check */
    bvh_node8 n8;
    int tried = 0;
    for (int k = 0; k < 20000; k++) {
        random_node(&n8, 8);
        int c = k % 8;
        vec3 o = {random_coordinate(), random_coordinate(),
                  random_coordinate()};
        ray r = {o, vec3_sub(just_inside_a_corner(&n8, c, k / 8 % 8), o)};
        double t0;
        bvh_ray br;
        if (!clearly_meets(&n8, c, r, INFINITY, &t0) ||
            !bvh_ray_of(r.origin, ray_inverse_dir(r), 0, INFINITY, &br))
            continue;
        bvh_walk_rows(&br);
        float t_near[8];
        unsigned m = bvh_node8_test_avx2(&n8, &br, INFINITY, t_near);
        ck_assert_msg(m >> c & 1, "ray %d misses lane %d at corner %d", k, c,
                      k / 8 % 8);
        tried++;
    }
    ck_assert_int_gt(tried, 15000); /* most rays met their box clearly */
}
END_TEST

START_TEST(test_the_octant_orders_list_the_lanes_farthest_first)
{
    box *b = ch09_random_boxes(&rng, 2000, (vec3){3, -2, 1}, 10, 0.5);
    bvh t;
    ck_assert(bvh_build(&t, 2000, b, &(bvh_params){.width = 8}));
    for (int k = 0; k < t.node_count; k++) {
        const bvh_node8 *n = &t.nodes8[k];
        for (unsigned o = 0; o < 8; o++) {
            unsigned seen = 0;
            double last = INFINITY;
            for (int j = 0; j < 8; j++) {
                unsigned c = n->order[j] >> 3 * o & 7;
                seen |= 1u << c;
                if (n->face[0][c] > n->face[1][c])
                    continue; /* unused */
                double far = 0;
                for (int a = 0; a < 3; a++) {
                    double centre = (double)n->face[2 * a][c] +
                                    n->face[2 * a + 1][c];
                    far += (o >> a & 1) ? -centre : centre;
                }
                ck_assert_msg(far <= last, "node %d, octant %u: place %d "
                              "is farther than the place before it", k, o, j);
                last = far;
            }
            ck_assert_msg(seen == 0xff, "node %d, octant %u: the order "
                          "holds lanes %#x, not each of the eight", k, o, seen);
        }
    }
    bvh_free(&t);
    free(b);
}
END_TEST

/* A push keeps exactly the lanes hit, in the octant's order, each with
 * its entry; the nearest ends on top. */
/* The AVX2 and AVX-512VL pushes of n's children in mask, for octant o,
 * where the processor has them: the same top and the same stack as the
 * plain push's (stack, entry, top), and the child on top as nearest. */
static void expect_vector_pushes_alike(const bvh_node8 *n, unsigned mask,
                                       unsigned o, const uint32_t *stack,
                                       const float *entry, int top)
{
    const float t_near[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    for (int isa = 0; isa < 2; isa++) {
        if (!(isa == 0 ? bvh_walks_with_avx2() : bvh_walks_with_avx512()))
            continue;
        uint32_t s[16];
        float e[16];
        uint32_t nearest;
        int32_t met[8]; /* the lanes of mask, as the node test gives them */
        for (int c = 0; c < 8; c++)
            met[c] = mask >> c & 1 ? -1 : 0;
        int got = isa == 0 ? bvh_push8_avx2(s, e, 0, n, met, t_near, 3 * o,
                                            &nearest)
                           : bvh_push8_avx512(s, e, 0, n, met, t_near, 3 * o,
                                              &nearest);
        const char *name = isa == 0 ? "AVX2" : "AVX-512";
        uint32_t on_top = top > 0 ? stack[top - 1] : nearest; /* or none */
        ck_assert_msg(nearest == on_top,
                      "%s push of mask %#x: nearest %#x, not the top %#x",
                      name, mask, nearest, on_top);
        ck_assert_msg(got == top, "%s push of mask %#x: top %d, not %d",
                      name, mask, got, top);
        ck_assert_msg(memcmp(s, stack, (size_t)top * sizeof *s) == 0 &&
                          memcmp(e, entry, (size_t)top * sizeof *e) == 0,
                      "%s push of mask %#x: another stack", name, mask);
    }
}

START_TEST(test_a_push_keeps_the_children_hit_in_the_octant_s_order)
{
    box *b = ch09_random_boxes(&rng, 2000, (vec3){3, -2, 1}, 10, 0.5);
    bvh t;
    ck_assert(bvh_build(&t, 2000, b, &(bvh_params){.width = 8}));
    for (int k = 0; k < t.node_count; k++) {
        const bvh_node8 *n = &t.nodes8[k];
        for (unsigned o = 0; o < 8; o++) {
            unsigned mask = (unsigned)(k * 37 + o * 11) & 0xff;
            uint32_t stack[9];
            float entry[9], t_near[8] = {0, 1, 2, 3, 4, 5, 6, 7};
            int top = bvh_push8(stack, entry, 0, n, mask, t_near, 3 * o);
            ck_assert_msg(top == __builtin_popcount(mask), "mask %#x pushed "
                          "%d children", mask, top);
            for (int j = 0, at = 0; j < 8; j++) {
                unsigned c = n->order[j] >> 3 * o & 7;
                if (!(mask >> c & 1))
                    continue;
                ck_assert_uint_eq(stack[at], n->child[c]);
                ck_assert(entry[at++] == (float)c);
            }
            expect_vector_pushes_alike(n, mask, o, stack, entry, top);
        }
    }
    bvh_free(&t);
    free(b);
}
END_TEST

/* The wide nodes' lanes hold the items of their leaves. */
START_TEST(test_wide_nodes_hold_their_leaves_items)
{
    box *b = ch09_random_boxes(&rng, 3000, (vec3){1e6, 2, -3}, 10, 0.5);
    for (int width = 4; width <= 8; width *= 2) {
        bvh t;
        ck_assert(bvh_build(&t, 3000, b, &(bvh_params){.width = width}));
        int items = 0;
        for (int k = 0; k < t.node_count; k++)
            for (int c = 0; c < 8; c++) {
                const bvh_node8 *node = &t.nodes8[k];
                uint32_t word = node->child[c];
                uint32_t first = word & BVH_FIRST_MASK;
                uint32_t n = word & BVH_LEAF ? word >> BVH_COUNT_SHIFT & 15 : 0;
                ck_assert(c < width || node->face[0][c] > node->face[1][c]);
                for (uint32_t i = 0; i < n; i++, items++) {
                    float f[6];
                    for (int a = 0; a < 3; a++)
                        f[a] = node->face[2 * a][c],
                        f[a + 3] = node->face[2 * a + 1][c];
                    ck_assert(ch09_holds(f, &b[t.items[first + i]]));
                }
            }
        ck_assert_int_eq(items, 3000); /* every item in exactly one leaf */
        bvh_free(&t);
    }
    free(b);
}
END_TEST

/* bvh_bound_after(t) lies at or above t (1 + BVH_SLACK), computed
 * exactly in double (a float's 24 bits times 21), and is the least float
 * there or the float after it: never below, never two floats more; a
 * NaN (no bound) only where no float lies above or the step crosses 0. */
static void expect_bound_after(float t)
{
    double exact = (double)t * (1 + BVH_SLACK);
    float b = bvh_bound_after(t), least = bvh_float_up(exact);
    if (least == INFINITY) /* no float above: no bound */
        ck_assert_msg(isnan(b), "t %a: %a", (double)t, (double)b);
    else
        ck_assert_msg(b == least || b == nextafterf(least, INFINITY),
                      "t %a: %a, least %a", (double)t, (double)b,
                      (double)least);
}

START_TEST(test_the_float_path_s_bound_after_a_hit_lies_just_above_it)
{
    const float edges[] = {0.0f, 0x1p-149f, 0x1p-126f, 1.0f, 0x1.fffffep-1f,
                           3.0f, FLT_MAX, -1.0f, -0x1p-149f};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++)
        expect_bound_after(edges[i]);
    for (int k = 0; k < 100000; k++) /* from tiny to huge, either sign */
        expect_bound_after((float)ldexp(rng_uniform(&rng, -0.25, 0.75),
                                        (int)rng_uniform(&rng, -125, 125)));
    ck_assert(isnan(bvh_bound_after(INFINITY))); /* no float above */
    ck_assert(isnan(bvh_bound_after(-0.0f)));     /* nor a step over 0 */
    ck_assert(isnan(bvh_bound_after(NAN)));
}
END_TEST

/* The surface area of the box around the used lanes of wide node n. */
static double wide_node_area(const bvh_node8 *n)
{
    float f[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY,
                  -INFINITY};
    for (int c = 0; c < 8; c++)
        for (int a = 0; a < 3; a++) {
            f[a] = fminf(f[a], n->face[2 * a][c]);
            f[a + 3] = fmaxf(f[a + 3], n->face[2 * a + 1][c]);
        }
    double x = f[3] - f[0], y = f[4] - f[1], z = f[5] - f[2];
    return x * y + y * z + z * x;
}

/* The sum of the areas of a wide tree's nodes but the root's (every
 * collapse has the root): what the collapse makes least. */
static double wide_tree_area(const bvh *t)
{
    double sum = 0;
    for (int k = 1; k < t->node_count; k++)
        sum += wide_node_area(&t->nodes8[k]);
    return sum;
}

static double binary_node_area(const bvh_node *n)
{
    double x = n->box[3] - n->box[0], y = n->box[4] - n->box[1],
           z = n->box[5] - n->box[2];
    return x * y + y * z + z * x;
}

/* The same sum for the greedy collapse of binary tree b (nodes[k]'s
 * children k + 1 and index) width wide: each wide node's interior child
 * with the largest box opened first, while there is room. */
static double greedy_tree_area(const bvh *b, int k, int width)
{
    const bvh_node *nodes = b->nodes;
    int kids[8] = {k + 1, (int)nodes[k].index}, n = 2;
    for (;;) {
        int widest = -1;
        for (int j = 0; j < n; j++)
            if (nodes[kids[j]].count == 0 &&
                (widest < 0 || binary_node_area(&nodes[kids[j]]) >
                                   binary_node_area(&nodes[kids[widest]])))
                widest = j;
        if (widest < 0 || n == width)
            break;
        int open = kids[widest];
        kids[widest] = open + 1, kids[n++] = (int)nodes[open].index;
    }
    double sum = 0;
    for (int j = 0; j < n; j++)
        if (nodes[kids[j]].count == 0)
            sum += binary_node_area(&nodes[kids[j]]) +
                   greedy_tree_area(b, kids[j], width);
    return sum;
}

/* The priced collapse's wide nodes cost no more than the greedy one's,
 * by the sum of their areas, and less on thousands of boxes. */
START_TEST(test_the_collapse_costs_no_more_than_opening_the_largest_box)
{
    box *b = ch09_random_boxes(&rng, 3000, (vec3){5, -2, 1}, 10, 0.5);
    bvh binary;
    ck_assert(bvh_build(&binary, 3000, b, &(bvh_params){.width = 2}));
    for (int width = 4; width <= 8; width *= 2) {
        bvh t;
        ck_assert(bvh_build(&t, 3000, b, &(bvh_params){.width = width}));
        double priced = wide_tree_area(&t);
        double greedy = greedy_tree_area(&binary, 0, width);
        ck_assert_msg(priced < greedy, "width %d: %g, greedy %g", width,
                      priced, greedy);
        bvh_free(&t);
    }
    bvh_free(&binary);
    free(b);
}
END_TEST

/* A set of nodes below a binary node, each leaf under exactly one of
 * them (a frontier): its size, and the areas of the wide nodes that its
 * interior members become, each at its least. */
typedef struct {
    int size;
    double cost;
} frontier;

enum { MOST_FRONTIERS = 8192 };

/* Every frontier of k's subtree of at most width members, listed one by
 * one into out: k itself first, then each of its children's with each
 * of the other's. How many. */
static int frontiers(const bvh_node *nodes, int k, int width, frontier *out)
{
    out[0] = (frontier){1, 0}; /* a leaf: itself alone */
    if (nodes[k].count != 0)
        return 1;
    frontier *l = malloc(2 * MOST_FRONTIERS * sizeof *l);
    ck_assert(l != NULL);
    frontier *r = l + MOST_FRONTIERS;
    int nl = frontiers(nodes, k + 1, width, l);
    int nr = frontiers(nodes, (int)nodes[k].index, width, r);
    int n = 1;
    double least = INFINITY; /* of the frontiers below k */
    for (int i = 0; i < nl; i++)
        for (int j = 0; j < nr; j++)
            if (l[i].size + r[j].size <= width) {
                ck_assert_int_lt(n, MOST_FRONTIERS);
                out[n++] = (frontier){l[i].size + r[j].size,
                                      l[i].cost + r[j].cost};
                least = fmin(least, l[i].cost + r[j].cost);
            }
    free(l);
    out[0].cost = binary_node_area(&nodes[k]) + least; /* a wide node */
    return n;
}

/* On small trees, the priced collapse's sum is the least of all. */
START_TEST(test_the_collapse_costs_the_least_of_every_collapse)
{
    frontier *f = malloc(MOST_FRONTIERS * sizeof *f);
    ck_assert(f != NULL);
    for (int trial = 0; trial < 20; trial++) {
        int count = 6 + trial / 2; /* up to 15 leaves: few frontiers */
        box *b = ch09_random_boxes(&rng, count, (vec3){1, 2, 3}, 4, 1);
        bvh_params p = {.width = 2, .max_leaf_items = 1};
        bvh binary;
        ck_assert(bvh_build(&binary, count, b, &p));
        for (p.width = 4; p.width <= 8; p.width *= 2) {
            bvh t;
            ck_assert(bvh_build(&t, count, b, &p));
            int n = frontiers(binary.nodes, 0, p.width, f);
            double least = INFINITY; /* not the root alone: below it */
            for (int i = 1; i < n; i++)
                least = fmin(least, f[i].cost);
            double priced = wide_tree_area(&t);
            ck_assert_msg(fabs(priced - least) <= 1e-5 * least,
                          "%d boxes, width %d: %.9g, least %.9g", count,
                          p.width, priced, least);
            bvh_free(&t);
        }
        bvh_free(&binary);
        free(b);
    }
    free(f);
}
END_TEST

/* A node's children that are nodes fill its first lanes, numbered one
 * after another from child[0]'s, as many as bvh_child_nodes says; every
 * node but the root is the child of one lane, below its parent. */
START_TEST(test_a_node_s_children_that_are_nodes_come_first_in_a_row)
{
    box *b = ch09_random_boxes(&rng, 3000, (vec3){-4, 2, 7}, 10, 0.5);
    for (int width = 4; width <= 8; width *= 2) {
        bvh t;
        ck_assert(bvh_build(&t, 3000, b, &(bvh_params){.width = width}));
        int *parents = calloc((size_t)t.node_count, sizeof *parents);
        ck_assert(parents != NULL);
        for (int k = 0; k < t.node_count; k++) {
            const bvh_node8 *n = &t.nodes8[k];
            int nodes = bvh_child_nodes(n);
            ck_assert_int_le(nodes, width);
            for (int c = 0; c < 8; c++) {
                uint32_t word = n->child[c];
                ck_assert_msg((c < nodes) == !(word & BVH_LEAF),
                              "node %d, lane %d: a node past the count, "
                              "or a leaf before it", k, c);
                if (c >= nodes)
                    continue;
                ck_assert_uint_eq(word, n->child[0] + (uint32_t)c);
                ck_assert((int)word > k && (int)word < t.node_count);
                parents[word]++;
            }
        }
        ck_assert_int_eq(parents[0], 0);
        for (int k = 1; k < t.node_count; k++)
            ck_assert_int_eq(parents[k], 1);
        free(parents);
        bvh_free(&t);
    }
    free(b);
}
END_TEST

/* The leaf of reference c of wide node k of t (count 0: none): its first
 * packet and its triangles. */
static uint32_t leaf_of(const bvh *t, int k, int c, uint32_t *count)
{
    uint32_t word = t->nodes8[k].child[c];
    *count = word & BVH_LEAF ? word >> BVH_COUNT_SHIFT & 15 : 0;
    return word & BVH_FIRST_MASK;
}

START_TEST(test_every_wide_leaf_s_packets_hold_its_triangles)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    for (int width = 4; width <= 8; width *= 2) {
        mesh b = ch09_with_bvh(&m, &(bvh_params){.width = width});
        ch10_expect_packets_hold_each_triangle(&m, &b, 8, leaf_of);
        mesh_free_tree(&b);
    }
    mesh_free(&m);
}
END_TEST

START_TEST(test_the_wide_bvh_of_a_mesh_stays_within_its_bytes)
{
    const char *paths[] = {"meshes/bunny.obj", "meshes/teapot-8.obj"};
    for (int k = 0; k < 2; k++) {
        mesh m = ch09_load(paths[k]);
        mesh b = ch09_bare(&m);
        ck_assert(mesh_build_bvh(&b, &(bvh_params){.width = 8}));
        double bytes = (double)mesh_tree_bytes(&b) / m.triangle_count;
        ck_assert_msg(bytes <= MESH_BVH_MAX_BYTES_PER_TRIANGLE,
                      "%s: %.1f bytes a triangle", paths[k], bytes);
        mesh_free_tree(&b);
        mesh_free(&m);
    }
}
END_TEST

/* A mesh's wide tree prices a node's box at half a packet's test (its
 * own traversal_cost 0.5 builds the same tree); priced alike, as the
 * binary tree's build prices them, its leaves are larger and fewer. */
START_TEST(test_a_mesh_s_wide_tree_prices_a_box_at_half_a_packet)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    mesh own = ch09_bare(&m), half = ch09_bare(&m), whole = ch09_bare(&m);
    ck_assert(mesh_build_bvh(&own, &(bvh_params){0}));
    ck_assert(mesh_build_bvh(&half, &(bvh_params){.traversal_cost = 0.5}));
    ck_assert(mesh_build_bvh(&whole, &(bvh_params){.traversal_cost = 1}));
    ck_assert_int_eq(own.bvh.width, 8);
    ck_assert_int_eq(own.bvh.node_count, half.bvh.node_count);
    ck_assert(memcmp(own.bvh.nodes8, half.bvh.nodes8,
                     (size_t)own.bvh.node_count * sizeof(bvh_node8)) == 0);
    ck_assert_int_gt(own.bvh.leaf_count, whole.bvh.leaf_count);
    mesh binary = ch09_bare(&m), binary_whole = ch09_bare(&m);
    ck_assert(mesh_build_bvh(&binary, &(bvh_params){.width = 2}));
    ck_assert(mesh_build_bvh(&binary_whole,
                             &(bvh_params){.width = 2, .traversal_cost = 1}));
    ck_assert_int_eq(binary.bvh.node_count, binary_whole.bvh.node_count);
    ck_assert(memcmp(binary.bvh.nodes, binary_whole.bvh.nodes,
                     (size_t)binary.bvh.node_count * sizeof(bvh_node)) == 0);
    mesh_free_tree(&own), mesh_free_tree(&half), mesh_free_tree(&whole);
    mesh_free_tree(&binary), mesh_free_tree(&binary_whole);
    mesh_free(&m);
}
END_TEST

START_TEST(test_running_out_of_memory_in_a_wide_build_leaves_no_tree)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    int failed = 0;
    for (long n = 0; n < 12; n++) {
        mesh b = ch09_bare(&m);
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

Suite *ch11_wide_suite(void)
{
    Suite *s = suite_create("ch11 wide");
    TCase *agree = tcase_create("agreement");
    tcase_add_checked_fixture(agree, reseed, NULL);
    tcase_set_timeout(agree, 120);
    tcase_add_test(
        agree, test_wide_bvh_agrees_with_brute_force_and_kdtree_on_the_teapot);
    tcase_add_slow_test(
        agree, test_wide_bvh_agrees_with_brute_force_and_kdtree_on_the_bunny);
    tcase_add_test(agree,
                   test_wide_bvh_agrees_on_coincident_triangles_near_and_far);
    tcase_add_test(agree, test_wide_bvh_agrees_on_fans_through_one_vertex);
    tcase_add_test(agree, test_wide_rays_along_edges_and_faces_find_their_hits);
    suite_add_tcase(s, agree);
    TCase *nodes = tcase_create("nodes and packets");
    tcase_add_checked_fixture(nodes, reseed, NULL);
    tcase_set_timeout(nodes, 120);
    tcase_add_test(nodes, test_vector_and_scalar_node_tests_agree);
    tcase_add_test(nodes,
                   test_the_fused_test_keeps_a_box_met_just_inside_a_corner);
    tcase_add_test(nodes, test_the_octant_orders_list_the_lanes_farthest_first);
    tcase_add_test(nodes,
                   test_a_push_keeps_the_children_hit_in_the_octant_s_order);
    tcase_add_test(nodes, test_wide_nodes_hold_their_leaves_items);
    tcase_add_test(
        nodes, test_the_float_path_s_bound_after_a_hit_lies_just_above_it);
    tcase_add_test(
        nodes, test_the_collapse_costs_no_more_than_opening_the_largest_box);
    tcase_add_test(nodes, test_the_collapse_costs_the_least_of_every_collapse);
    tcase_add_test(nodes,
                   test_a_node_s_children_that_are_nodes_come_first_in_a_row);
    tcase_add_test(nodes, test_every_wide_leaf_s_packets_hold_its_triangles);
    tcase_add_test(nodes, test_the_wide_bvh_of_a_mesh_stays_within_its_bytes);
    tcase_add_test(nodes,
                   test_a_mesh_s_wide_tree_prices_a_box_at_half_a_packet);
    tcase_add_test(nodes,
                   test_running_out_of_memory_in_a_wide_build_leaves_no_tree);
    suite_add_tcase(s, nodes);
    return s;
}
