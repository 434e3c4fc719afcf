/* ch09_bvh.c: chapter 9's bounding volume hierarchy: the same answers as
 * brute force and as chapter 8's kd-tree, bit for bit; the binned
 * surface area heuristic's split; float boxes that hold their items; the
 * walk's order; and its choice in a scene file and on the command line.
 * Its helpers (ch09_...) serve the suites of chapters 10 to 12, which
 * walk wider trees built on more threads. */
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

/* From tests/ch08_kdtree.c: its adversarial rays (random, along the axes,
 * at vertices and edges, from the kd-tree's split planes, grazing), count
 * of each kind, and its meshes made from arrays. */
int ch08_adversarial_rays(const mesh *m, ray *rays, int count,
                          uint64_t seed_value);
mesh ch08_make_mesh(const vec3 *points, int n_points, const int (*tris)[3],
                    int n_tris);
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size);

/* Shared with the suites of chapters 10 to 12. */
mesh ch09_load(const char *path);
mesh ch09_bare(const mesh *m);
mesh ch09_with_bvh(const mesh *m, const bvh_params *p);
void ch09_expect_agreement(const mesh *m, int count, const char *what,
                           const bvh_params *p);
mesh ch09_plane_mesh(int n, vec3 offset, double size);
mesh ch09_fan_mesh(int n, vec3 centre);
void ch09_expect_edges_and_faces(const bvh_params *p);
box *ch09_random_boxes(rng_state *r, int count, vec3 centre, double spread,
                       double size);
bool ch09_holds(const float f[6], const box *b);

static const rng_state RNG_START = {0xB7Bu};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

mesh ch09_load(const char *path)
{
    mesh m = {0};
    parse_error err;
    ck_assert_msg(mesh_load_obj(&m, path, &err), "%s: %s", path, err.message);
    mesh_compute_bounds(&m);
    return m;
}

/* m sharing its arrays, with no tree: for brute force. */
mesh ch09_bare(const mesh *m)
{
    mesh b = *m;
    b.tree = (kdtree){0}, b.leaf_corners = NULL;
    b.bvh = (bvh){0};
    return b;
}

static mesh with_kdtree(const mesh *m)
{
    mesh k = ch09_bare(m);
    kdtree_params p = kdtree_default_params();
    p.min_items = 1;
    ck_assert(mesh_build_tree(&k, &p));
    return k;
}

/* m's BVH by p, from a single item on. */
mesh ch09_with_bvh(const mesh *m, const bvh_params *p)
{
    mesh b = ch09_bare(m);
    bvh_params q = *p;
    q.min_items = 1;
    ck_assert(mesh_build_bvh(&b, &q));
    ck_assert(b.bvh.node_count > 0);
    return b;
}

static const bvh_params BINARY = {.width = 2};

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

/* What brute force answers on the adversarial rays, which the kd-tree
 * was found to answer alike: the same for any BVH of the mesh, so kept
 * for the next call on the same mesh and count (chapter 11 asks for
 * three BVHs of one mesh, and the bunny's costs seconds). */
typedef struct {
    uint64_t key; /* of the mesh's bytes and the count; 0: none */
    int n;
    ray *rays;
    int *nearest;    /* the triangle, or -1 */
    double *t;       /* its t, or infinity */
    double *t_max;   /* the shadow ray's segment */
    bool *occluded;  /* brute force's answer to it */
} agreement_reference;

static uint64_t hash_bytes(uint64_t h, const void *bytes, size_t size)
{
    const unsigned char *b = bytes;
    for (size_t k = 0; k < size; k++)
        h = (h ^ b[k]) * 0x100000001B3u; /* FNV-1a */
    return h;
}

static uint64_t reference_key(const mesh *m, int count)
{
    uint64_t h = 0xCBF29CE484222325u;
    h = hash_bytes(h, &count, sizeof count);
    h = hash_bytes(h, &m->triangle_count, sizeof m->triangle_count);
    h = hash_bytes(h, m->vertices,
                   (size_t)m->vertex_count * sizeof *m->vertices);
    h = hash_bytes(h, m->triangles,
                   (size_t)m->triangle_count * sizeof *m->triangles);
    return h | 1;
}

static void reference_free(agreement_reference *r)
{
    free(r->rays), free(r->nearest), free(r->t), free(r->t_max);
    free(r->occluded);
    *r = (agreement_reference){0};
}

/* Brute force's answers on m's adversarial rays (made from its kd-tree,
 * which must give the same), made again unless m and count are those of
 * the last call. */
static const agreement_reference *reference_of(const mesh *m, int count,
                                               const char *what)
{
    static agreement_reference r;
    uint64_t key = reference_key(m, count);
    if (r.key == key)
        return &r;
    reference_free(&r);
    mesh kd = with_kdtree(m), brute = ch09_bare(m);
    size_t most = 5 * (size_t)count;
    r.rays = malloc(most * sizeof *r.rays);
    r.nearest = malloc(most * sizeof *r.nearest);
    r.t = malloc(most * sizeof *r.t);
    r.t_max = malloc(most * sizeof *r.t_max);
    r.occluded = malloc(most * sizeof *r.occluded);
    ck_assert(r.rays && r.nearest && r.t && r.t_max && r.occluded);
    r.n = ch08_adversarial_rays(&kd, r.rays, count, 0xB0B);
    int kd_differ = 0;
    rng_state draws = {0xB7Bu};
    for (int k = 0; k < r.n; k++) {
        double t_k;
        r.nearest[k] = nearest(&brute, r.rays[k], &r.t[k]);
        int i_k = nearest(&kd, r.rays[k], &t_k);
        kd_differ += i_k != r.nearest[k] ||
                     memcmp(&t_k, &r.t[k], sizeof t_k) != 0;
        mesh_ray mr = mesh_ray_of(r.rays[k]);
        render_stats stats = {0};
        r.t_max[k] = 5 * rng_uniform01(&draws) * vec3_length(
                         vec3_sub(m->bounds.hi, m->bounds.lo));
        r.occluded[k] = mesh_occluded(&brute, &mr, 1e-9, r.t_max[k], &stats);
    }
    mesh_free_tree(&kd);
    ck_assert_msg(kd_differ == 0, "%s: the kd-tree differs on %d of %d rays",
                  what, kd_differ, r.n);
    r.key = key; /* only once the kd-tree agreed */
    return &r;
}

/* m's BVH by p against brute force and the kd-tree on the adversarial
 * rays: the same triangle and the same t, bit for bit; and the same
 * answer to a shadow ray over a random segment. */
void ch09_expect_agreement(const mesh *m, int count, const char *what,
                           const bvh_params *p)
{
    const agreement_reference *r = reference_of(m, count, what);
    mesh b = ch09_with_bvh(m, p);
    int differ = 0, shadows = 0;
    for (int k = 0; k < r->n; k++) {
        double t_b;
        int i_b = nearest(&b, r->rays[k], &t_b);
        differ += i_b != r->nearest[k] ||
                  memcmp(&t_b, &r->t[k], sizeof t_b) != 0;
        mesh_ray mr = mesh_ray_of(r->rays[k]);
        render_stats stats = {0};
        shadows += mesh_occluded(&b, &mr, 1e-9, r->t_max[k], &stats) !=
                   r->occluded[k];
    }
    ck_assert_msg(differ == 0, "%s, %d wide: %d of %d rays differ", what,
                  b.bvh.width, differ, r->n);
    ck_assert_msg(shadows == 0, "%s, %d wide: %d of %d shadow rays differ",
                  what, b.bvh.width, shadows, r->n);
    mesh_free_tree(&b);
}

/* A grid of 2 n^2 triangles over [-1, 1]^2 in the plane z = 0, moved by
 * offset and scaled by size, with a copy of every triangle (coincident:
 * a tie at every hit, to the lower index). */
mesh ch09_plane_mesh(int n, vec3 offset, double size)
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
mesh ch09_fan_mesh(int n, vec3 centre)
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
    mesh m = ch09_load("meshes/teapot-8.obj");
    ch09_expect_agreement(&m, 400, "teapot", &BINARY);
    mesh_free(&m);
}
END_TEST

START_TEST(test_bvh_agrees_with_brute_force_and_kdtree_on_the_bunny)
{
    mesh m = ch09_load("meshes/bunny.obj");
    ch09_expect_agreement(&m, 30, "bunny", &BINARY); /* brute: 1 ms a ray */
    mesh_free(&m);
}
END_TEST

START_TEST(test_bvh_agrees_on_coincident_triangles_near_and_far)
{
    const vec3 at[3] = {{0, 0, 0}, {1e6, -1e6, 1e6}, {3e-3, 0, 0}};
    const double size[3] = {1, 10, 1e-5};
    for (int k = 0; k < 3; k++) {
        mesh m = ch09_plane_mesh(12, at[k], size[k]);
        ch09_expect_agreement(&m, 300, "coincident planes", &BINARY);
        mesh_free(&m);
    }
}
END_TEST

START_TEST(test_bvh_agrees_on_fans_through_one_vertex)
{
    mesh m = ch09_fan_mesh(300, (vec3){0.25, -0.5, 4});
    ch09_expect_agreement(&m, 300, "fan", &BINARY);
    mesh_free(&m);
    m = ch09_fan_mesh(64, (vec3){2e6, 1e6, -3e6});
    ch09_expect_agreement(&m, 300, "far fan", &BINARY);
    mesh_free(&m);
}
END_TEST

/* Rays along the edges of a grid's triangles, and through its vertices,
 * exactly in the plane of its boxes' faces, through p's BVH. */
void ch09_expect_edges_and_faces(const bvh_params *p)
{
    mesh m = ch09_plane_mesh(8, (vec3){0, 0, 0}, 1), brute = ch09_bare(&m);
    mesh b = ch09_with_bvh(&m, p);
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
            ck_assert_msg(i_b == i_f && memcmp(&t_b, &t_f, sizeof t_b) == 0,
                          "width %d, ray %d at %g: %d at %g, brute force %d "
                          "at %g", b.bvh.width, r, y, i_b, t_b, i_f, t_f);
        }
    }
    mesh_free_tree(&b);
    mesh_free(&m);
}

START_TEST(test_rays_along_edges_and_faces_find_their_hits)
{
    ch09_expect_edges_and_faces(&BINARY);
}
END_TEST

/* ------------------------------------------------------------ nodes */

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

/* count random boxes around centre, drawn from r, sizes up to size
 * (some zero). */
box *ch09_random_boxes(rng_state *r, int count, vec3 centre, double spread,
                       double size)
{
    box *b = malloc((size_t)count * sizeof *b);
    for (int k = 0; k < count; k++) {
        vec3 c = vec3_add(centre, vec3_scale(rng_unit_vector(r, 1e-3),
                                             spread * rng_uniform01(r)));
        vec3 e = vec3_scale((vec3){rng_uniform01(r), rng_uniform01(r),
                                   rng_uniform01(r)},
                            k % 7 ? size : 0);
        b[k] = (box){vec3_sub(c, e), vec3_add(c, e)};
    }
    return b;
}

/* Does the float box f hold the double box b? */
bool ch09_holds(const float f[6], const box *b)
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
            ck_assert_msg(
                ch09_holds(n->box, &bounds[t->items[n->index + i]]),
                "node %d, item %d", k, t->items[n->index + i]);
        for (int c = 0; n->count == 0 && c < 2; c++) {
            const float *kid = t->nodes[c ? n->index : (uint32_t)k + 1].box;
            box b = {{kid[0], kid[1], kid[2]}, {kid[3], kid[4], kid[5]}};
            ck_assert(ch09_holds(n->box, &b));
        }
    }
}

START_TEST(test_float_boxes_hold_their_items)
{
    const vec3 centres[3] = {{0.1, 0.2, 0.3}, {1e6, -1e6, 3e6}, {7, 7, 7}};
    const double spread[3] = {1, 1, 1e-12}, size[3] = {0.1, 1e-9, 1e-15};
    for (int k = 0; k < 3; k++) {
        box *b = ch09_random_boxes(&rng, 5000, centres[k], spread[k], size[k]);
        bvh t;
        ck_assert(bvh_build(&t, 5000, b, &(bvh_params){.width = 2}));
        ck_assert_int_eq(t.item_count, 5000);
        expect_boxes_hold(&t, b);
        bvh_free(&t);
        free(b);
    }
}
END_TEST

/* The root of a tree over items in two clusters far apart splits them:
 * every item of one cluster on one side. */
START_TEST(test_the_root_splits_two_clusters_apart)
{
    int n = 400;
    box *b = ch09_random_boxes(&rng, n, (vec3){0, 0, 0}, 1, 0.1);
    for (int k = n / 2; k < n; k++) /* the second half, 100 units away */
        b[k].lo.x += 100, b[k].hi.x += 100;
    bvh t;
    ck_assert(bvh_build(&t, n, b, &(bvh_params){.width = 2}));
    const bvh_node *root = &t.nodes[0], *low = &t.nodes[1];
    ck_assert_int_eq(root->count, 0);
    ck_assert_int_eq(root->axis, 0);
    /* the first child's items: the subtree right after the root */
    int first_child_items = 0, side = -1;
    for (int k = 1; k < (int)root->index; k++)
        for (int i = 0; i < t.nodes[k].count; i++) {
            int cluster = t.items[t.nodes[k].index + i] >= n / 2;
            side = side < 0 ? cluster : side;
            ck_assert_msg(cluster == side, "item %d on the wrong side",
                          t.items[t.nodes[k].index + i]);
            first_child_items++;
        }
    ck_assert_int_eq(first_child_items, n / 2);
    ck_assert(low->box[3] < 50); /* the low side's box ends in its cluster */
    bvh_free(&t);
    free(b);
}
END_TEST

/* The surface area heuristic's cost of the split of items [0, n) at bin
 * boundary k, computed here from the formula: centres binned along axis
 * from lo, bins a unit of scale. */
static double sah_cost(const box *b, int n, int axis, double lo,
                       double scale, int bins, int k, double area)
{
    box sides[2] = {{{INFINITY, INFINITY, INFINITY},
                     {-INFINITY, -INFINITY, -INFINITY}},
                    {{INFINITY, INFINITY, INFINITY},
                     {-INFINITY, -INFINITY, -INFINITY}}};
    int count[2] = {0, 0};
    for (int i = 0; i < n; i++) {
        double c = (vec3_axis(b[i].lo, axis) + vec3_axis(b[i].hi, axis)) / 2;
        int bin = (int)((c - lo) * scale);
        bin = bin < 0 ? 0 : bin >= bins ? bins - 1 : bin;
        int s = bin >= k;
        sides[s].lo = vec3_min(sides[s].lo, b[i].lo);
        sides[s].hi = vec3_max(sides[s].hi, b[i].hi);
        count[s]++;
    }
    if (count[0] == 0 || count[1] == 0)
        return INFINITY;
    return 1 + (box_area(&sides[0]) * count[0] +
                box_area(&sides[1]) * count[1]) / area;
}

/* The root's two children hold the items on either side of the cheapest
 * boundary between the bins, by the cost computed here. */
START_TEST(test_the_split_is_the_cheapest_plane_of_the_bins)
{
    for (int run = 0; run < 8; run++) {
        int n = 300 + 97 * run, bins = 4 + 4 * run;
        box *b = ch09_random_boxes(&rng, n, (vec3){run, -2, 3}, 1 + run,
                                   0.2);
        for (int k = 0; k < n; k += 3) /* stretched along x: its axis */
            b[k].lo.x *= 3, b[k].hi.x *= 3;
        /* the centres' box, and the items' */
        box centres = {{INFINITY, INFINITY, INFINITY},
                       {-INFINITY, -INFINITY, -INFINITY}}, all = centres;
        for (int i = 0; i < n; i++) {
            vec3 c = vec3_scale(vec3_add(b[i].lo, b[i].hi), 0.5);
            centres.lo = vec3_min(centres.lo, c);
            centres.hi = vec3_max(centres.hi, c);
            all.lo = vec3_min(all.lo, b[i].lo);
            all.hi = vec3_max(all.hi, b[i].hi);
        }
        vec3 size = vec3_sub(centres.hi, centres.lo);
        int axis = size.y > size.x ? 1 : 0;
        axis = size.z > vec3_axis(size, axis) ? 2 : axis;
        double lo = vec3_axis(centres.lo, axis);
        double scale = bins / vec3_axis(size, axis);
        int best = -1;
        double least = INFINITY;
        for (int k = 1; k < bins; k++) {
            double c = sah_cost(b, n, axis, lo, scale, bins, k,
                                box_area(&all));
            if (c < least)
                least = c, best = k;
        }
        ck_assert_int_gt(best, 0);
        bvh t;
        ck_assert(bvh_build(&t, n, b,
                            &(bvh_params){.width = 2, .bins = bins}));
        ck_assert_int_eq(t.nodes[0].count, 0);
        ck_assert_int_eq(t.nodes[0].axis, axis);
        /* every item of the first child's subtree is below the boundary */
        int below = 0;
        for (int k = 1; k < (int)t.nodes[0].index; k++)
            for (int i = 0; i < t.nodes[k].count; i++) {
                const box *it = &b[t.items[t.nodes[k].index + i]];
                double c = (vec3_axis(it->lo, axis) +
                            vec3_axis(it->hi, axis)) / 2;
                int bin = (int)((c - lo) * scale);
                bin = bin < 0 ? 0 : bin >= bins ? bins - 1 : bin;
                ck_assert_msg(bin < best, "run %d: an item of bin %d left "
                              "of the boundary %d", run, bin, best);
                below++;
            }
        int expected = 0;
        for (int i = 0; i < n; i++) {
            double c = (vec3_axis(b[i].lo, axis) +
                        vec3_axis(b[i].hi, axis)) / 2;
            int bin = (int)((c - lo) * scale);
            bin = bin < 0 ? 0 : bin >= bins ? bins - 1 : bin;
            expected += bin < best;
        }
        ck_assert_int_eq(below, expected);
        bvh_free(&t);
        free(b);
    }
}
END_TEST

START_TEST(test_running_out_of_memory_in_a_build_leaves_no_tree)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    int failed = 0;
    for (long n = 0; n < 12; n++) {
        mesh b = ch09_bare(&m);
        memory_fail_after(n);
        bool ok = mesh_build_bvh(&b, &BINARY);
        memory_fail_after(-1);
        failed += !ok;
        ck_assert(ok || b.bvh.node_count == 0);
        mesh_free_tree(&b);
    }
    ck_assert_int_gt(failed, 2);
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ choosing it */

START_TEST(test_the_accelerator_statement_chooses_the_tree)
{
    link_meshes();
    /* the default; each statement; a heat map of kd-tree nodes; and
     * --accelerator (set before the file is read) over the statement */
    const char *texts[5] = {
        "mesh file meshes/teapot-8.obj\n",
        "accelerator kdtree\nmesh file meshes/teapot-8.obj\n",
        "accelerator bvh\nmesh file meshes/teapot-8.obj\n",
        "kdtree heatmap 9\nmesh file meshes/teapot-8.obj\n",
        "accelerator kdtree\nmesh file meshes/teapot-8.obj\n"};
    const bool wants_bvh[5] = {
        MESH_DEFAULT_ACCELERATOR == MESH_ACCELERATOR_BVH, false, true, false,
        true};
    for (int k = 0; k < 5; k++) {
        scene s;
        scene_error err;
        char *path = (char *)write_file("choose.scene", texts[k]);
        scene_init(&s);
        if (k == 4)
            s.accelerator_option = MESH_ACCELERATOR_BVH;
        ck_assert_msg(scene_load(&s, path, &err), "%s", err.message);
        bool bvh = wants_bvh[k];
        ck_assert_int_eq(s.meshes[0].bvh.node_count > 0, bvh);
        ck_assert_int_eq(s.meshes[0].tree.node_count > 0, !bvh);
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
                       "accelerator (kdtree, bvh");
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
        ck_assert_msg(strstr(errors, "--accelerator expects kdtree"), "%s",
                      errors);
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
    expect_same_with_either(chapter_scene("ch09", "ch08-bunny.scene"),
                            "200x150");
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
    tcase_add_test(nodes, test_a_ray_in_a_face_plane_meets_the_box);
    tcase_add_test(nodes,
                   test_the_walk_takes_the_nearest_child_and_stacks_the_rest);
    tcase_add_test(nodes, test_the_root_splits_two_clusters_apart);
    tcase_add_test(nodes, test_the_split_is_the_cheapest_plane_of_the_bins);
    tcase_add_test(nodes, test_float_boxes_hold_their_items);
    tcase_add_test(nodes, test_running_out_of_memory_in_a_build_leaves_no_tree);
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
