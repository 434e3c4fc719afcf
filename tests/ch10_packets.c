/* ch10_packets.c: chapter 10's leaf tests (chapter 10).
 *
 * The tightened leaf tests must be chapter 4's watertight test to the last
 * bit: the same winner, t and barycentric coordinates, whatever the
 * triangles and the rays, so every comparison here is exact (==, memcmp),
 * against a loop over triangle_hit_prepared, chapter 4's reference, that
 * keeps the tie rule in its own words. The packets of triangles in float
 * must give exactly the answers of the double leaf test: their filter may
 * keep too much, never too little. */
#include <check.h>
#include "shard.h"
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "memory.h"
#include "rng.h"
#include "triangle.h"
#include "triangle_packet.h"

/* ------------------------------------------------------------ references */

/* The nearest of a leaf's triangles by chapter 4's test, one by one: the
 * lowest (t, item) in (t_min, t_max], t_max itself only below best. */
static int reference_nearest(const watertight_ray *w,
                             const triangle_corners *c, const int *items,
                             int count, double t_min, double t_max, int best,
                             triangle_hit *out)
{
    int nearest = -1;
    for (int k = 0; k < count; k++) {
        triangle_hit th;
        const vec3 *p = c[k].p;
        if (!triangle_hit_prepared(w, p[0], p[1], p[2], t_min, INFINITY, &th))
            continue;
        if (th.t < t_max || (th.t == t_max && items[k] < best))
            *out = th, t_max = th.t, best = items[k], nearest = k;
    }
    return nearest;
}

static bool reference_any(const watertight_ray *w, const triangle_corners *c,
                          int count, double t_min, double t_max)
{
    triangle_hit th;
    for (int k = 0; k < count; k++)
        if (triangle_hit_prepared(w, c[k].p[0], c[k].p[1], c[k].p[2], t_min,
                                  t_max, &th))
            return true;
    return false;
}

/* How many of the rays' leaf answers differ from the reference's. */
typedef struct {
    int rays, hits, differences;
} leaf_tally;

static void compare_leaf(leaf_tally *tally, ray r,
                         const triangle_corners *c, const int *items,
                         int count, double t_max, int best)
{
    watertight_ray w = watertight_ray_of(r);
    triangle_hit mine = {0}, theirs = {0};
    int k = triangle_nearest_of_leaf(&w, c, items, count, 0, t_max, best,
                                     &mine);
    int j = reference_nearest(&w, c, items, count, 0, t_max, best, &theirs);
    bool any = triangle_any_corners(&w, c, count, 0, t_max);
    tally->rays++;
    tally->hits += j >= 0;
    tally->differences += k != j || any != reference_any(&w, c, count, 0,
                                                         t_max);
    if (k == j && k >= 0)
        tally->differences += memcmp(&mine, &theirs, sizeof mine) != 0;
}

/* ------------------------------------------------------------ leaves */

/* A leaf of eight triangles: a fan of six around a point, which share
 * edges, and two loose ones, all within size of centre; items shuffled. */
static void random_leaf(rng_state *g, vec3 centre, double size,
                        triangle_corners c[8], int items[8])
{
    vec3 hub = vec3_add(centre, vec3_scale(rng_unit_vector(g, 0.1), size));
    vec3 rim[6];
    for (int k = 0; k < 6; k++)
        rim[k] = vec3_add(hub, vec3_scale(rng_unit_vector(g, 0.1), size));
    for (int k = 0; k < 6; k++)
        c[k] = (triangle_corners){{hub, rim[k], rim[(k + 1) % 6]}};
    for (int k = 6; k < 8; k++)
        for (int i = 0; i < 3; i++)
            c[k].p[i] = vec3_add(centre,
                                 vec3_scale(rng_unit_vector(g, 0.1), size));
    for (int k = 0; k < 8; k++)
        items[k] = (int)(rng_next(g) >> 40) % 1000;
}

/* A point of triangle c: inside, on an edge (as near as double rounds)
 * or a corner, by the kind k mod 3. */
static vec3 aim_at(rng_state *g, const triangle_corners *c, int kind)
{
    int i = (int)(rng_next(g) >> 40) % 3;
    vec3 a = c->p[i], b = c->p[(i + 1) % 3], e = c->p[(i + 2) % 3];
    double s = rng_uniform01(g), t = rng_uniform01(g) * (1 - s);
    if (kind % 3 == 2)
        return a;
    if (kind % 3 == 1)
        t = 0;
    return vec3_add(a, vec3_add(vec3_scale(vec3_sub(b, a), s),
                                vec3_scale(vec3_sub(e, a), t)));
}

START_TEST(test_tightened_leaf_is_chapter_4s_test_on_random_rays)
{
    rng_state g = {9};
    const double scales[4][2] = {{1e-3, 1}, {1, 1}, {1, 1e5}, {30, 1e6}};
    leaf_tally tally = {0};
    for (int n = 0; n < 40000; n++) {
        const double *sc = scales[n % 4];
        vec3 centre = vec3_scale(rng_unit_vector(&g, 0.1), sc[1]);
        triangle_corners c[8];
        int items[8];
        random_leaf(&g, centre, sc[0], c, items);
        for (int k = 0; k < 8; k++) {
            vec3 target = aim_at(&g, &c[k], k);
            vec3 origin = vec3_add(
                target, vec3_scale(rng_unit_vector(&g, 0.1), 4 * sc[0]));
            ray r = {origin, vec3_normalize(vec3_sub(target, origin))};
            compare_leaf(&tally, r, c, items, 8, INFINITY, -1);
            compare_leaf(&tally, r, c, items, 8, 4 * sc[0], items[k]);
        }
    }
    ck_assert_int_eq(tally.differences, 0);
    ck_assert_msg(tally.hits > tally.rays / 2, "%d hits of %d rays",
                  tally.hits, tally.rays);
}
END_TEST

/* Chapter 4's octahedron (tests/ch04_triangles.c): corners off the axes,
 * rays aimed at points of its edges and at its vertices. */
static triangle_corners octa[8];

static void make_octahedron(void)
{
    const vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                          {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    vec3 v[6];
    for (int k = 0; k < 6; k++) /* turned by an awkward angle, moved */
        v[k] = (vec3){0.3 + axes[k].x * cos(0.7) - axes[k].y * sin(0.7),
                      -0.2 + axes[k].x * sin(0.7) + axes[k].y * cos(0.7),
                      5 + axes[k].z};
    for (int f = 0; f < 8; f++)
        for (int i = 0; i < 3; i++)
            octa[f].p[i] = v[faces[f][i]];
}

/* The ray from outside to the point s/16 of the way along edge e of face
 * f, tilted by o (chapter 4's leak test's rays). */
static ray edge_ray(int f, int e, int s, int o)
{
    vec3 a = octa[f].p[e], b = octa[f].p[(e + 1) % 3];
    vec3 target = vec3_add(a, vec3_scale(vec3_sub(b, a), s / 16.0));
    vec3 out = vec3_normalize(vec3_sub(target, (vec3){0.3, -0.2, 5}));
    double angle = o * 0.5236 + 0.1;
    vec3 tilt = {0.25 * cos(angle), 0.25 * sin(angle),
                 0.25 * cos(3 * angle)};
    vec3 origin = vec3_add(target, vec3_scale(vec3_add(out, tilt), 3));
    return (ray){origin, vec3_normalize(vec3_sub(target, origin))};
}

START_TEST(test_tightened_leaf_leaks_no_edge_aimed_ray)
{
    make_octahedron();
    const int items[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    leaf_tally tally = {0};
    int leaks = 0;
    for (int f = 0; f < 8; f++)
        for (int e = 0; e < 3; e++)
            for (int s = 0; s <= 16; s++)
                for (int o = 0; o < 12; o++) {
                    ray r = edge_ray(f, e, s, o);
                    watertight_ray w = watertight_ray_of(r);
                    triangle_hit th;
                    leaks += triangle_nearest_of_leaf(&w, octa, items, 8, 0,
                                                      INFINITY, -1, &th) < 0;
                    leaks += !triangle_any_corners(&w, octa, 8, 0, INFINITY);
                    compare_leaf(&tally, r, octa, items, 8, INFINITY, -1);
                }
    ck_assert_int_eq(leaks, 0);
    ck_assert_int_eq(tally.differences, 0);
    ck_assert_int_eq(tally.hits, tally.rays);
}
END_TEST

START_TEST(test_tightened_leaf_keeps_the_tie_rule)
{
    /* One triangle three times, items 7, 3, 5: every copy is hit at the
     * same t, and the lowest item wins, here and against a best so far. */
    triangle_corners one = {{{-1, -1, 2}, {2, -1, 2}, {-1, 2, 2}}};
    triangle_corners c[3] = {one, one, one};
    const int items[3] = {7, 3, 5};
    watertight_ray w = watertight_ray_of((ray){{0.1, 0.2, 0}, {0, 0, 1}});
    triangle_hit th;
    ck_assert_int_eq(
        triangle_nearest_of_leaf(&w, c, items, 3, 0, INFINITY, -1, &th), 1);
    ck_assert(th.t == 2);
    ck_assert_int_eq(triangle_nearest_of_leaf(&w, c, items, 3, 0, 2, 4, &th),
                     1); /* a tie with item 4 found before: 3 wins */
    ck_assert_int_eq(triangle_nearest_of_leaf(&w, c, items, 3, 0, 2, 2, &th),
                     -1); /* a tie with item 2: 2 keeps it */
    ck_assert_int_eq(triangle_nearest_of_leaf(&w, c, items, 3, 0, 2, -1, &th),
                     -1); /* nothing found yet: t_max itself is out */
}
END_TEST

START_TEST(test_tightened_leaf_never_hits_a_degenerate_triangle)
{
    /* Chapter 4's fuzz case (tests/data/fuzz-obj-collinear-triangle.obj):
     * rays aimed exactly at a triangle of three points on a line. */
    triangle_corners c[2] = {{{{8, 0, 0}, {1, 0, 0}, {0, 0, 0}}},
                             {{{1, 0, 0}, {1, 0, 0}, {0, 0, 0}}}};
    const int items[2] = {0, 1};
    vec3 origin = {1.6, 0.6, -1};
    leaf_tally tally = {0};
    for (double x = 0; x <= 8; x += 0.5) {
        ray r = {origin, vec3_normalize(vec3_sub((vec3){x, 0, 0}, origin))};
        watertight_ray w = watertight_ray_of(r);
        triangle_hit th;
        ck_assert_msg(triangle_nearest_of_leaf(&w, c, items, 2, 0, INFINITY,
                                               -1, &th) < 0,
                      "a hit at x = %g", x);
        ck_assert(!triangle_any_corners(&w, c, 2, 0, INFINITY));
        compare_leaf(&tally, r, c, items, 2, INFINITY, -1);
    }
    ck_assert_int_eq(tally.differences, 0);
}
END_TEST

/* ------------------------------------------------------------ packets */

/* A few triangles, as a mesh holds them, and their packets. */
enum { MAX_TRIANGLES = 32 };
typedef struct {
    vec3 vertices[3 * MAX_TRIANGLES];
    mesh_triangle triangles[MAX_TRIANGLES];
    triangle_corners corners[MAX_TRIANGLES];
    triangle_corners leaf[MAX_TRIANGLES]; /* corners in the items' order */
    int items[MAX_TRIANGLES], count, packet_count;
    triangle_packet *packets;
    bool in_lanes; /* every corner a float: decided on the packets' */
} little_mesh;

/* Triangle c as the mesh's triangle number count. */
static void add_triangle(little_mesh *m, triangle_corners c)
{
    int k = m->count++;
    ck_assert_int_le(m->count, MAX_TRIANGLES);
    for (int i = 0; i < 3; i++)
        m->vertices[3 * k + i] = c.p[i];
    m->triangles[k] = (mesh_triangle){{3 * k, 3 * k + 1, 3 * k + 2}};
    m->corners[k] = c;
    m->items[k] = k;
}

/* Packs the triangles items[0..count) (the order a leaf may hold), and
 * copies their corners in that order, as chapter 8's leaves do. */
static void pack(little_mesh *m)
{
    for (int k = 0; k < m->count; k++)
        m->leaf[k] = m->corners[m->items[k]];
    free(m->packets);
    int n = triangle_packets_needed(m->count);
    m->packets = memory_alloc_aligned(_Alignof(triangle_packet), (size_t)n,
                                      sizeof(triangle_packet));
    ck_assert_ptr_nonnull(m->packets);
    m->packet_count = triangle_packets_fill(m->packets, m->vertices,
                                            m->triangles, m->items, m->count);
    ck_assert_int_eq(m->packet_count, n);
}

/* The packets' nearest and any hit, decided on the mesh's corners, or
 * (in_lanes) on the packets' own. */
static int packets_nearest(const little_mesh *m, const packet_ray *pr,
                           double t_max, int best, triangle_hit *th,
                           long long *decided)
{
    const vec3 *v = m->in_lanes ? NULL : m->vertices;
    return triangle_packets_nearest_in_mesh(pr, m->packets, m->packet_count,
                                            v, m->triangles, 0, t_max, best,
                                            th, decided);
}

static bool packets_any(const little_mesh *m, const packet_ray *pr,
                        double t_max, long long *decided)
{
    const vec3 *v = m->in_lanes ? NULL : m->vertices;
    return triangle_packets_any_in_mesh(pr, m->packets, m->packet_count, v,
                                        m->triangles, 0, t_max, decided);
}

typedef struct {
    long long lanes, kept_hits, lost_hits, disagreements, rejected;
    long long rays, differences, decided, hits;
} packet_tally;

/* For every lane: the vector and the lane-by-lane filters agree, and a
 * triangle chapter 4's test hits in (t_min, t_max) is kept. */
static void check_filter(packet_tally *tally, const little_mesh *m, ray r,
                         double t_min, double t_max)
{
    watertight_ray w = watertight_ray_of(r);
    packet_ray pr = packet_ray_of(&w);
    for (int p = 0; p < m->packet_count; p++) {
        const triangle_packet *q = &m->packets[p];
        unsigned simd = triangle_packet_candidates(q, &pr, t_min, t_max,
                                                   false);
        unsigned one = triangle_packet_candidates(q, &pr, t_min, t_max, true);
        tally->disagreements += simd != one;
        for (int k = 0; k < TRIANGLE_PACKET_WIDTH; k++) {
            int i = q->triangle[k];
            bool kept = simd >> k & 1;
            triangle_hit th;
            if (i < 0) {
                tally->disagreements += kept; /* an empty lane */
                continue;
            }
            const vec3 *c = m->corners[i].p;
            bool hit = triangle_hit_prepared(&w, c[0], c[1], c[2], t_min,
                                             t_max, &th);
            tally->lanes++;
            tally->kept_hits += hit && kept;
            tally->lost_hits += hit && !kept;
            tally->rejected += !kept; /* of the misses, as hits are kept */
        }
    }
}

/* The packets' nearest and any hit against chapter 8's leaf test of the
 * same triangles in the same order, bit for bit. */
static void check_search(packet_tally *tally, const little_mesh *m, ray r,
                         double t_max, int best)
{
    watertight_ray w = watertight_ray_of(r);
    packet_ray pr = packet_ray_of(&w);
    const triangle_corners *c = m->leaf;
    triangle_hit mine = {0}, theirs = {0};
    int i = packets_nearest(m, &pr, t_max, best, &mine, &tally->decided);
    int k = triangle_nearest_of_leaf(&w, c, m->items, m->count, 0, t_max,
                                     best, &theirs);
    bool any = triangle_any_corners(&w, c, m->count, 0, t_max);
    tally->rays++, tally->hits += k >= 0;
    tally->differences += i != (k < 0 ? -1 : m->items[k]);
    tally->differences += any != packets_any(m, &pr, t_max, &tally->decided);
    if (k >= 0)
        tally->differences += memcmp(&mine, &theirs, sizeof mine) != 0;
}

/* Leaves of every kind: a size and a distance from the origin, and some
 * degenerate triangles among them. */
static const double leaf_kinds[6][2] = {{1e-3, 1},  {1, 1},    {1, 1e5},
                                        {30, 1e6},  {1e-6, 3}, {1e4, 10}};

static void random_mesh(rng_state *g, little_mesh *m, int kind)
{
    const double *sc = leaf_kinds[kind % 6];
    triangle_corners c[8];
    int unused[8];
    random_leaf(g, vec3_scale(rng_unit_vector(g, 0.1), sc[1]), sc[0], c,
                unused);
    m->count = 0, m->in_lanes = false;
    for (int k = 0; k < 8; k++)
        add_triangle(m, c[k]);
    if (kind % 5 == 0) /* a line, and a point */
        add_triangle(m, (triangle_corners){{c[0].p[0], c[0].p[1],
                                            c[0].p[1]}}),
            add_triangle(m, (triangle_corners){{c[1].p[0], c[1].p[0],
                                                c[1].p[0]}});
    for (int k = m->count - 1; k > 0; k--) { /* a leaf's order */
        int j = (int)(rng_next(g) >> 33) % (k + 1), swap = m->items[k];
        m->items[k] = m->items[j], m->items[j] = swap;
    }
    pack(m);
}

/* A ray at a point of triangle k: inside, on an edge, at a corner, or in
 * its plane, from about four sizes away. */
static ray ray_toward(rng_state *g, const little_mesh *m, int k, int kind)
{
    const triangle_corners *c = &m->corners[k % m->count];
    vec3 target = aim_at(g, c, kind);
    double size = vec3_length(vec3_sub(c->p[1], c->p[0])) + 1e-300;
    vec3 from = vec3_scale(rng_unit_vector(g, 0.1), 4 * size);
    if (kind % 7 == 3) /* along an edge: in the triangle's plane */
        from = vec3_scale(vec3_sub(c->p[1], c->p[0]), 4);
    vec3 origin = vec3_add(target, from);
    return (ray){origin, vec3_normalize(vec3_sub(target, origin))};
}

/* m's corners rounded to float, and packed again. */
static void round_to_float(little_mesh *m)
{
    for (int k = 0; k < m->count; k++)
        for (int i = 0; i < 3; i++) {
            vec3 *p = &m->corners[k].p[i];
            *p = (vec3){(float)p->x, (float)p->y, (float)p->z};
            m->vertices[3 * k + i] = *p;
        }
    pack(m);
    m->in_lanes = true;
}

/* leaves random leaves from g (in_float: their corners rounded to float,
 * decided on the packets' own), each searched by rays at eight of its
 * triangles, with and without a bound and a best: into *tally. */
static void search_random_leaves(packet_tally *tally, rng_state g,
                                 int leaves, bool in_float)
{
    little_mesh m = {0};
    for (int n = 0; n < leaves; n++) {
        random_mesh(&g, &m, n);
        if (in_float)
            round_to_float(&m);
        for (int k = 0; k < 8; k++) {
            ray r = ray_toward(&g, &m, k, n + k);
            double size = vec3_length(vec3_sub(m.corners[k].p[1],
                                                m.corners[k].p[0]));
            check_search(tally, &m, r, INFINITY, -1);
            check_search(tally, &m, r, 4 * size, m.items[k]);
        }
    }
    free(m.packets);
}

START_TEST(test_the_float_filter_keeps_every_triangle_double_hits)
{
    rng_state g = {17};
    little_mesh m = {0};
    packet_tally tally = {0};
    for (int n = 0; n < 30000; n++) {
        random_mesh(&g, &m, n);
        for (int k = 0; k < 16; k++) {
            ray r = ray_toward(&g, &m, k, n + k);
            watertight_ray w = watertight_ray_of(r);
            triangle_hit th;
            check_filter(&tally, &m, r, 0, INFINITY);
            /* from a point of the triangle, as a shadow ray leaves it */
            ray leaving = {aim_at(&g, &m.corners[k % m.count], n + k),
                           rng_unit_vector(&g, 0.1)};
            check_filter(&tally, &m, leaving, 0, INFINITY);
            int i = k % m.count;
            const vec3 *c = m.corners[i].p;
            if (!triangle_hit_prepared(&w, c[0], c[1], c[2], 0, INFINITY,
                                       &th))
                continue;
            check_filter(&tally, &m, r, 0, nextafter(th.t, INFINITY));
            check_filter(&tally, &m, r, nextafter(th.t, 0), INFINITY);
        }
    }
    free(m.packets);
    ck_assert_int_eq(tally.disagreements, 0);
    ck_assert_msg(tally.lost_hits == 0, "%lld of %lld hits lost",
                  tally.lost_hits, tally.lost_hits + tally.kept_hits);
    long long misses = tally.lanes - tally.kept_hits;
    ck_assert_msg(tally.kept_hits > tally.lanes / 20 &&
                      tally.rejected > misses / 2,
                  "%lld lanes: %lld hits; %lld of the misses rejected",
                  tally.lanes, tally.kept_hits, tally.rejected);
}
END_TEST

START_TEST(test_packets_find_what_the_double_leaf_test_finds)
{
    packet_tally tally = {0};
    search_random_leaves(&tally, (rng_state){23}, 20000, false);
    ck_assert_int_eq(tally.differences, 0);
    ck_assert_int_gt(tally.decided, 0);
}
END_TEST

START_TEST(test_packets_of_floats_decide_on_their_lanes_corners)
{
    packet_tally tally = {0};
    search_random_leaves(&tally, (rng_state){29}, 10000, true);
    ck_assert_int_eq(tally.differences, 0);
    ck_assert_msg(tally.hits > tally.rays / 4, "%lld hits of %lld rays",
                  tally.hits, tally.rays);
}
END_TEST

START_TEST(test_packets_leak_no_edge_aimed_ray)
{
    make_octahedron();
    little_mesh m = {0};
    for (int f = 0; f < 8; f++)
        add_triangle(&m, octa[f]);
    pack(&m);
    packet_tally tally = {0};
    int leaks = 0;
    for (int f = 0; f < 8; f++)
        for (int e = 0; e < 3; e++)
            for (int s = 0; s <= 16; s++)
                for (int o = 0; o < 12; o++) {
                    ray r = edge_ray(f, e, s, o);
                    watertight_ray w = watertight_ray_of(r);
                    packet_ray pr = packet_ray_of(&w);
                    triangle_hit th;
                    long long decided = 0;
                    leaks += packets_nearest(&m, &pr, INFINITY, -1, &th,
                                             &decided) < 0;
                    leaks += !packets_any(&m, &pr, INFINITY, &decided);
                    check_search(&tally, &m, r, INFINITY, -1);
                    check_filter(&tally, &m, r, 0, INFINITY);
                }
    free(m.packets);
    ck_assert_int_eq(leaks, 0);
    ck_assert_int_eq(tally.differences, 0);
    ck_assert_int_eq(tally.lost_hits, 0);
    ck_assert_int_eq(tally.disagreements, 0);
}
END_TEST

static int packets_winner(const little_mesh *m, const packet_ray *pr,
                          double t_max, int best, triangle_hit *th)
{
    long long decided = 0;
    return packets_nearest(m, pr, t_max, best, th, &decided);
}

START_TEST(test_packets_keep_the_tie_rule_in_and_across_packets)
{
    /* One triangle four times, as the mesh's triangles 2, 5, 9 and 11 of
     * twelve, packed in the order 11, 9, 5, 2, ...: in one packet or over
     * two, the lowest index wins at the tie. */
    triangle_corners one = {{{-1, -1, 2}, {2, -1, 2}, {-1, 2, 2}}};
    triangle_corners other = {{{5, 5, 1}, {6, 5, 1}, {5, 6, 1}}};
    little_mesh m = {0};
    for (int k = 0; k < 12; k++)
        add_triangle(&m, k == 2 || k == 5 || k == 9 || k == 11 ? one : other);
    const int order[12] = {11, 0, 1, 9, 3, 4, 6, 7, 5, 8, 10, 2};
    memcpy(m.items, order, sizeof order);
    pack(&m);
    watertight_ray w = watertight_ray_of((ray){{0.1, 0.2, 0}, {0, 0, 1}});
    packet_ray pr = packet_ray_of(&w);
    triangle_hit th;
    ck_assert_int_eq(packets_winner(&m, &pr, INFINITY, -1, &th), 2);
    ck_assert(th.t == 2);
    ck_assert_int_eq(packets_winner(&m, &pr, 2, 3, &th),
                     2); /* a tie with triangle 3, found before: 2 wins */
    ck_assert_int_eq(packets_winner(&m, &pr, 2, 1, &th),
                     -1); /* a tie with triangle 1: 1 keeps it */
    ck_assert_int_eq(packets_winner(&m, &pr, 2, -1, &th),
                     -1); /* nothing found yet: t_max itself is out */
    free(m.packets);
}
END_TEST

/* float_up_by_bits(x) against nextafterf, the library's step: the float
 * at or above x, bit for bit, for x of either sign and any size, floats
 * and the doubles between them, zeros, infinities, the ends of float's
 * range and a NaN. */
static void check_float_up(double x)
{
    float f = (float)x, want = (double)f < x ? nextafterf(f, INFINITY) : f;
    float got = float_up_by_bits(x);
    ck_assert_msg(memcmp(&got, &want, sizeof got) == 0,
                  "x = %a: %a, not %a", x, (double)got, (double)want);
    ck_assert_msg(isnan(x) || (double)got >= x, "x = %a: %a", x, (double)got);
}

START_TEST(test_float_up_by_bits_is_nextafterf_s_step)
{
    const double edges[] = {0.0, -0.0, INFINITY, -INFINITY, NAN, DBL_MAX,
                            -DBL_MAX, FLT_MAX, -FLT_MAX,
                            FLT_MAX * (1 + 0x1p-40), -FLT_MAX * (1 + 0x1p-40),
                            0x1p-149, -0x1p-149, 0x1p-160, -0x1p-160,
                            0x1.8p-150, -0x1.8p-150, 1, -1, 1 + 0x1p-40,
                            -1 - 0x1p-40, 1 - 0x1p-40, -1 + 0x1p-40};
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        check_float_up(edges[k]);
    rng_state g = {17};
    for (int k = 0; k < 200000; k++) {
        int e = (int)(rng_next(&g) % 300) - 160; /* float's range and past */
        double x = ldexp(rng_uniform(&g, 1, 2), e);
        x = rng_next(&g) & 1 ? -x : x;
        check_float_up(x);
        check_float_up((float)x); /* a float itself */
    }
}
END_TEST

START_TEST(test_empty_lanes_are_never_kept)
{
    /* Three triangles: the other lanes of the packet are empty, their
     * corners all at the origin, where these rays pass. */
    little_mesh m = {0};
    add_triangle(&m, (triangle_corners){{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
    add_triangle(&m, (triangle_corners){{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}});
    add_triangle(&m, (triangle_corners){{{3, 0, 0}, {0, 3, 0}, {0, 0, 3}}});
    pack(&m);
    const triangle_packet *q = &m.packets[0];
    for (int k = 3; k < TRIANGLE_PACKET_WIDTH; k++)
        ck_assert_int_eq(q->triangle[k], -1);
    rng_state g = {5};
    for (int n = 0; n < 1000; n++) {
        ray r = {vec3_scale(rng_unit_vector(&g, 0.1), 2), {0, 0, 1}};
        r.dir = vec3_normalize(vec3_scale(r.origin, -1)); /* at the origin */
        watertight_ray w = watertight_ray_of(r);
        packet_ray pr = packet_ray_of(&w);
        unsigned full = (1u << 3) - 1;
        ck_assert_uint_eq(
            triangle_packet_candidates(q, &pr, 0, INFINITY, false) & ~full,
            0);
        ck_assert_uint_eq(
            triangle_packet_candidates(q, &pr, 0, INFINITY, true) & ~full,
            0);
    }
    free(m.packets);
}
END_TEST

START_TEST(test_an_empty_lane_lets_the_edges_stop_the_filter)
{
    /* Three triangles in the octant x, y, z >= 0 and at least one empty
     * lane; rays parallel to z at x < 0 pass beside all three, an edge
     * between the ray and each: the filter must stop at the edges. */
    little_mesh m = {0};
    add_triangle(&m, (triangle_corners){{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
    add_triangle(&m, (triangle_corners){{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}});
    add_triangle(&m, (triangle_corners){{{3, 0, 0}, {0, 3, 0}, {0, 0, 3}}});
    pack(&m);
    ck_assert_int_eq(m.packets[0].triangle[TRIANGLE_PACKET_WIDTH - 1], -1);
    int stopped = 0;
    for (int n = 0; n < 100; n++) {
        ray r = {{-0.5 - 0.01 * n, 0.25 + 0.02 * n, -5}, {0, 0, 1}};
        watertight_ray w = watertight_ray_of(r);
        packet_ray pr = packet_ray_of(&w);
        ck_assert_uint_eq(
            triangle_packet_candidates(&m.packets[0], &pr, 0, INFINITY,
                                       false),
            0);
        stopped += triangle_packet_stops_at_edges(&m.packets[0], &pr);
    }
    ck_assert_int_eq(stopped, 100);
    free(m.packets);
}
END_TEST

START_TEST(test_packets_hold_the_mesh_s_triangles_in_float)
{
    rng_state g = {3};
    little_mesh m = {0};
    random_mesh(&g, &m, 2);
    ck_assert_int_eq(m.packet_count,
                     (m.count + TRIANGLE_PACKET_WIDTH - 1) /
                         TRIANGLE_PACKET_WIDTH);
    for (int j = 0; j < m.packet_count * TRIANGLE_PACKET_WIDTH; j++) {
        const triangle_packet *q = &m.packets[j / TRIANGLE_PACKET_WIDTH];
        int k = j % TRIANGLE_PACKET_WIDTH, i = q->triangle[k];
        ck_assert_int_eq(i, j < m.count ? m.items[j] : -1);
        if (i < 0)
            continue;
        float reach = 0;
        for (int c = 0; c < 3; c++) {
            vec3 p = m.corners[i].p[c];
            double xyz[3] = {p.x, p.y, p.z};
            for (int axis = 0; axis < 3; axis++) {
                ck_assert(q->corner[c][axis][k] == (float)xyz[axis]);
                reach = fmaxf(reach, fabsf((float)xyz[axis]));
            }
        }
        ck_assert(q->reach[k] == reach);
    }
    free(m.packets);
}
END_TEST

START_TEST(test_the_filter_decides_far_rays_alone)
{
    /* Rays that pass far from every triangle, or point away: the filter
     * rejects them all, and double is never asked. */
    rng_state g = {11};
    little_mesh m = {0};
    long long decided = 0;
    for (int n = 0; n < 1000; n++) {
        random_mesh(&g, &m, 1);
        ray r = ray_toward(&g, &m, n, 0);
        r.dir = vec3_scale(r.dir, -1); /* away from the target */
        watertight_ray w = watertight_ray_of(r);
        packet_ray pr = packet_ray_of(&w);
        triangle_hit th;
        ck_assert_int_eq(packets_nearest(&m, &pr, INFINITY, -1, &th,
                                         &decided), -1);
        ck_assert(!packets_any(&m, &pr, INFINITY, &decided));
    }
    free(m.packets);
    ck_assert_int_lt(decided, 100);
}
END_TEST

START_TEST(test_the_filter_rejects_rays_just_past_an_edge_alone)
{
    /* Rays along a triangle's normal that pass outside one of its edges
     * by 300 u T (u = 2^-24; T, the largest corner coordinate plus the
     * origin's, the reach of the filter's bounds). The filter's bound of
     * an edge function, divided by the edge's length, is under 100 u T
     * for an edge as long as its triangle is wide: the filter rejects
     * these rays without asking double, where a bound ten times too
     * loose would keep them. */
    rng_state g = {29};
    int rays = 0, kept = 0;
    for (int n = 0; n < 3000; n++) {
        triangle_corners c;
        for (int i = 0; i < 3; i++)
            c.p[i] = rng_unit_vector(&g, 0.1);
        int e = n % 3;
        vec3 a = c.p[e], b = c.p[(e + 1) % 3], opposite = c.p[(e + 2) % 3];
        vec3 normal = vec3_cross(vec3_sub(b, a), vec3_sub(opposite, a));
        double edge = vec3_length(vec3_sub(b, a));
        double others = fmax(vec3_length(vec3_sub(opposite, a)),
                             vec3_length(vec3_sub(opposite, b)));
        if (vec3_length(normal) < 0.2 * edge * edge || edge < 0.5 * others)
            continue; /* a sliver, or an edge short for its triangle */
        /* outward in the plane, across the edge from the opposite corner */
        vec3 out = vec3_normalize(vec3_cross(vec3_sub(b, a), normal));
        if (vec3_dot(out, vec3_sub(opposite, a)) > 0)
            out = vec3_scale(out, -1);
        vec3 on_edge = vec3_add(a, vec3_scale(vec3_sub(b, a),
                                              rng_uniform01(&g)));
        vec3 axis = vec3_normalize(normal);
        vec3 above = vec3_add(on_edge, vec3_scale(axis, 2));
        double reach = 0, origin_reach = 0;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                reach = fmax(reach, fabs(vec3_axis(c.p[i], k)));
        for (int k = 0; k < 3; k++)
            origin_reach = fmax(origin_reach, fabs(vec3_axis(above, k)));
        double past = 300 * 0x1p-24 * (reach + origin_reach);
        ray r = {vec3_add(above, vec3_scale(out, past)),
                 vec3_scale(axis, -1)};
        little_mesh m = {0};
        add_triangle(&m, c);
        pack(&m);
        watertight_ray w = watertight_ray_of(r);
        packet_ray pr = packet_ray_of(&w);
        rays++;
        kept += triangle_packet_candidates(m.packets, &pr, 0, INFINITY,
                                           false) != 0;
        kept += triangle_packet_candidates(m.packets, &pr, 0, INFINITY,
                                           true) != 0;
        free(m.packets);
    }
    ck_assert_int_gt(rays, 1000);
    ck_assert_msg(kept == 0, "%d of %d rays kept", kept, rays);
}
END_TEST

/* ------------------------------------------------------------ in float */

/* For every packet: the float decision in vectors and lane by lane hit the
 * same lanes, and the filter keeps each of them (they read the same float
 * edge functions, whose rounding the filter's bounds cover). */
static void check_float_hits(packet_tally *tally, const little_mesh *m,
                             ray r, double t_min, double t_max)
{
    watertight_ray w = watertight_ray_of(r);
    packet_ray pr = packet_ray_of(&w);
    for (int p = 0; p < m->packet_count; p++) {
        const triangle_packet *q = &m->packets[p];
        unsigned simd = triangle_packet_float_hits(q, &pr, t_min, t_max,
                                                   false);
        unsigned one = triangle_packet_float_hits(q, &pr, t_min, t_max, true);
        unsigned kept = triangle_packet_candidates(q, &pr, t_min, t_max,
                                                   false);
        tally->disagreements += simd != one;
        tally->lost_hits += __builtin_popcount(simd & ~kept);
        tally->kept_hits += __builtin_popcount(simd);
        tally->lanes += TRIANGLE_PACKET_WIDTH;
    }
}

START_TEST(test_float_hits_are_lanes_the_filter_keeps)
{
    rng_state g = {29};
    little_mesh m = {0};
    packet_tally tally = {0};
    for (int n = 0; n < 20000; n++) {
        random_mesh(&g, &m, n);
        for (int k = 0; k < 8; k++) {
            ray r = ray_toward(&g, &m, k, n + k);
            check_float_hits(&tally, &m, r, 0, INFINITY);
            ray leaving = {aim_at(&g, &m.corners[k % m.count], n + k),
                           rng_unit_vector(&g, 0.1)};
            check_float_hits(&tally, &m, leaving, 0, INFINITY);
            check_float_hits(&tally, &m, r, 0, 4);
        }
    }
    free(m.packets);
    ck_assert_int_eq(tally.disagreements, 0);
    ck_assert_msg(tally.lost_hits == 0, "%lld of %lld float hits rejected",
                  tally.lost_hits, tally.kept_hits);
    ck_assert_msg(tally.kept_hits > tally.lanes / 20, "%lld hits in %lld",
                  tally.kept_hits, tally.lanes);
}
END_TEST

START_TEST(test_float_hits_every_triangle_hit_well_inside)
{
    /* A ray at a point whose barycentric coordinates are all at least
     * 1/16, from either side (both windings): float's edge functions are
     * within e_E of the exact ones, for these triangles (no more than a
     * thousand of their sizes from the origin, no sliver, not seen
     * edge-on) below a thousandth of the determinant, so float must hit
     * every one. */
    const double kinds[3][2] = {{1, 1}, {1e-3, 1}, {1e4, 10}};
    rng_state g = {31};
    little_mesh m = {0};
    int tried = 0, missed = 0;
    for (int n = 0; n < 20000; n++) {
        const double *k = kinds[n % 3];
        vec3 centre = vec3_scale(rng_unit_vector(&g, 0.1), k[1]), p[3];
        for (int i = 0; i < 3; i++)
            p[i] = vec3_add(centre, vec3_scale(rng_unit_vector(&g, 0.1), k[0]));
        vec3 normal = vec3_cross(vec3_sub(p[1], p[0]), vec3_sub(p[2], p[0]));
        if (vec3_length(normal) < 0.1 * k[0] * k[0])
            continue; /* a sliver */
        double b[3] = {1 + 13 * rng_uniform01(&g), 1 + 13 * rng_uniform01(&g),
                       1 + 13 * rng_uniform01(&g)}, sum = b[0] + b[1] + b[2];
        vec3 target = vec3_add(vec3_scale(p[0], b[0] / sum),
                               vec3_add(vec3_scale(p[1], b[1] / sum),
                                        vec3_scale(p[2], b[2] / sum)));
        vec3 origin = vec3_add(target, vec3_scale(rng_unit_vector(&g, 0.1),
                                                  4 * k[0]));
        ray r = {origin, vec3_normalize(vec3_sub(target, origin))};
        if (fabs(vec3_dot(r.dir, normal)) < 0.1 * vec3_length(normal))
            continue; /* a grazing ray sees a sliver */
        m.count = 0;
        add_triangle(&m, (triangle_corners){{p[0], p[1], p[2]}});
        pack(&m);
        watertight_ray w = watertight_ray_of(r);
        packet_ray pr = packet_ray_of(&w);
        triangle_hit exact, fast;
        if (!triangle_hit_prepared(&w, p[0], p[1], p[2], 0, INFINITY, &exact))
            continue;
        tried++;
        missed += triangle_packets_nearest_float(&pr, m.packets, 1, 0,
                                                 INFINITY, -1, &fast) != 0;
        missed += !triangle_packets_any_float(&pr, m.packets, 1, 0, INFINITY);
    }
    free(m.packets);
    ck_assert_int_gt(tried, 15000);
    ck_assert_int_eq(missed, 0);
}
END_TEST

START_TEST(test_the_float_path_leaks_no_edge_aimed_ray)
{
    /* Every ray at an edge or a corner of the closed octahedron hits it,
     * in float as in double: the shared edges' functions are each other's
     * negatives. */
    make_octahedron();
    little_mesh m = {0};
    for (int f = 0; f < 8; f++)
        add_triangle(&m, octa[f]);
    pack(&m);
    int leaks = 0, rays = 0;
    for (int f = 0; f < 8; f++)
        for (int e = 0; e < 3; e++)
            for (int s = 0; s <= 16; s++)
                for (int o = 0; o < 12; o++) {
                    watertight_ray w = watertight_ray_of(edge_ray(f, e, s, o));
                    packet_ray pr = packet_ray_of(&w);
                    triangle_hit th;
                    rays++;
                    leaks += triangle_packets_nearest_float(
                                 &pr, m.packets, m.packet_count, 0, INFINITY,
                                 -1, &th) < 0;
                    leaks += !triangle_packets_any_float(
                        &pr, m.packets, m.packet_count, 0, INFINITY);
                }
    free(m.packets);
    ck_assert_int_eq(rays, 8 * 3 * 17 * 12);
    ck_assert_int_eq(leaks, 0);
}
END_TEST

START_TEST(test_the_float_path_keeps_the_tie_rule)
{
    /* As test_packets_keep_the_tie_rule_in_and_across_packets: one
     * triangle four times among twelve, in one packet or over two. */
    triangle_corners one = {{{-1, -1, 2}, {2, -1, 2}, {-1, 2, 2}}};
    triangle_corners other = {{{5, 5, 1}, {6, 5, 1}, {5, 6, 1}}};
    little_mesh m = {0};
    for (int k = 0; k < 12; k++)
        add_triangle(&m, k == 2 || k == 5 || k == 9 || k == 11 ? one : other);
    const int order[12] = {11, 0, 1, 9, 3, 4, 6, 7, 5, 8, 10, 2};
    memcpy(m.items, order, sizeof order);
    pack(&m);
    /* from either side: the determinant of either sign */
    const ray rays[2] = {{{0.1, 0.2, 0}, {0, 0, 1}},
                         {{0.1, 0.2, 4}, {0, 0, -1}}};
    for (int k = 0; k < 2; k++) {
        watertight_ray w = watertight_ray_of(rays[k]);
        packet_ray pr = packet_ray_of(&w);
        const triangle_packet *q = m.packets;
        int n = m.packet_count;
        triangle_hit th;
        ck_assert_int_eq(
            triangle_packets_nearest_float(&pr, q, n, 0, INFINITY, -1, &th), 2);
        ck_assert(th.t == 2);
        ck_assert(th.b[0] + th.b[1] + th.b[2] > 0.999f);
        /* a tie with triangle 3, found before: 2 wins; with 1: 1 keeps it;
         * nothing found yet: t_max itself is out */
        ck_assert_int_eq(
            triangle_packets_nearest_float(&pr, q, n, 0, 2, 3, &th), 2);
        ck_assert_int_eq(
            triangle_packets_nearest_float(&pr, q, n, 0, 2, 1, &th), -1);
        ck_assert_int_eq(
            triangle_packets_nearest_float(&pr, q, n, 0, 2, -1, &th), -1);
        ck_assert(!triangle_packets_any_float(&pr, q, n, 0, 2));
        ck_assert(triangle_packets_any_float(&pr, q, n, 0, 2.5));
    }
    free(m.packets);
}
END_TEST

Suite *ch10_packets_suite(void)
{
    Suite *s = suite_create("ch10 packets");
    TCase *leaves = tcase_create("leaves");
    tcase_set_timeout(leaves, 120);
    tcase_add_test(leaves,
                   test_tightened_leaf_is_chapter_4s_test_on_random_rays);
    tcase_add_test(leaves, test_tightened_leaf_leaks_no_edge_aimed_ray);
    tcase_add_test(leaves, test_tightened_leaf_keeps_the_tie_rule);
    tcase_add_test(leaves,
                   test_tightened_leaf_never_hits_a_degenerate_triangle);
    suite_add_tcase(s, leaves);
    TCase *packets = tcase_create("packets");
    tcase_set_timeout(packets, 120);
    tcase_add_slow_test(packets,
                   test_the_float_filter_keeps_every_triangle_double_hits);
    tcase_add_test(packets, test_packets_find_what_the_double_leaf_test_finds);
    tcase_add_test(packets, test_packets_leak_no_edge_aimed_ray);
    tcase_add_test(packets,
                   test_packets_of_floats_decide_on_their_lanes_corners);
    tcase_add_test(packets,
                   test_packets_keep_the_tie_rule_in_and_across_packets);
    tcase_add_test(packets, test_float_up_by_bits_is_nextafterf_s_step);
    tcase_add_test(packets, test_empty_lanes_are_never_kept);
    tcase_add_test(packets, test_an_empty_lane_lets_the_edges_stop_the_filter);
    tcase_add_test(packets, test_packets_hold_the_mesh_s_triangles_in_float);
    tcase_add_test(packets, test_the_filter_decides_far_rays_alone);
    tcase_add_test(packets,
                   test_the_filter_rejects_rays_just_past_an_edge_alone);
    tcase_add_test(packets, test_float_hits_are_lanes_the_filter_keeps);
    tcase_add_test(packets, test_float_hits_every_triangle_hit_well_inside);
    tcase_add_test(packets, test_the_float_path_leaks_no_edge_aimed_ray);
    tcase_add_test(packets, test_the_float_path_keeps_the_tie_rule);
    suite_add_tcase(s, packets);
    return s;
}
