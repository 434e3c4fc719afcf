/* ch09_bvh.c: chapter 9's binary BVH against chapter 8's kd-tree: time
 * per ray against wrong answers, and the builds' time and bytes.
 *
 *   build/rel-lto/bench/ch09_bvh > figures/ch09-bvh.csv
 *
 * The meshes: the Stanford bunny and the teapot, read as ch08_rays.h
 * reads them (float vertices), and the bunny moved by 10^6 on every axis
 * ("bunny-far": its float vertices plus 10^6, in double, which are no
 * longer floats). The methods (METHODS):
 *   kdtree    chapter 8's kd-tree, the program's default;
 *   bvh-M     chapter 9's binary BVH built with M = 4, 8, 16, 32, 64 bins;
 *   naive     the BVH of 32 bins with every node's box rounded to the
 *             nearest float, with no pad, and the ray's origin rounded to
 *             the nearest float too; the walk (bvh.h's) and the leaves'
 *             tests are the program's (failures/ch09_naive_bvh.h): what
 *             the outward rounding buys.
 *
 * Time: one operation is one ray's closest hit (mesh_nearest; the naive
 * search for naive), over the SIDE x SIDE rays of ch08_rays.h at K = 1,
 * every method of one mesh timed together by bench/timing.h. The far
 * bunny's BVH takes about a thousand times as long a ray (its float
 * boxes cannot be smaller than the float spacing at 10^6, 1/16): it gets
 * FAR_SIDE x FAR_SIDE rays and FAR_ROUNDS rounds.
 * Wrong answers: a ray whose triangle or t (bit for bit) differs from
 * brute force's (every triangle tested), on two sets of rays:
 *   ordinary     every STRIDE-th row and column of the timed rays (the
 *                far bunny's: all of them);
 *   adversarial  from random points a box diagonal from the mesh's centre,
 *                in double (not rounded to float), ADVERSARIAL of each
 *                kind (FAR_ADVERSARIAL for the far bunny): aimed at a
 *                vertex, aimed at a point of an edge, and
 *                along an axis through a vertex (in the planes of the
 *                faces of the boxes that the vertex bounds).
 * Builds: each tree of the bunny and the teapot built BUILD_ROUNDS times,
 * the trees of one mesh interleaved.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns),
 * after the "# machine:" line:
 *   METHOD,MESH,ns_per_ray,WRONG,ordinary_wrong_per_million,q1,q3,wall
 *   METHOD,MESH,ns_per_ray,WRONG,adversarial_wrong_per_million,q1,q3,wall
 *       (one timing, twice: a mark for each set of rays)
 *   METHOD-build,MESH,ns_per_build,NS,ns_per_triangle,q1,q3,wall
 *   tradeoff,METHOD@MESH,ns_per_ray,NS,build_ns_per_triangle,q1,q3,wall
 *       (a ray's time and quartiles beside the build's median)
 *   breakeven,MESH,0,R,rays_per_triangle  (from the medians: the rays a
 *       triangle at which the kd-tree's rays, faster than bvh-32's by D
 *       ns, have repaid its build, slower by B ns: B / D / triangles;
 *       -1 when the BVH's rays are no slower)
 *   bytes,METHOD@MESH,,B,bytes_per_triangle
 *   nodes,METHOD@MESH,,N,nodes_per_ray   (on the timed rays: the kd-tree's
 *       nodes visited, a BVH's nodes whose children were tested)
 *   tests,METHOD@MESH,,N,triangle_tests_per_ray
 *   rays,MESH,,N,ordinary_rays|adversarial_rays */
#include <string.h>

#include "../failures/ch09_naive_bvh.h"
#include "../tests/rng.h"
#include "ch08_rays.h"
#include "timing.h"

enum {
    SIDE = 256,        /* rays a side of the timed image */
    STRIDE = 8,        /* every 8th row and column: 32 x 32 ordinary rays */
    ADVERSARIAL = 512, /* rays of each kind */
    FAR_SIDE = 16,     /* the far bunny's rays, all of them ordinary */
    FAR_ROUNDS = 5,    /* its BVH's batch takes a tenth of a second */
    FAR_ADVERSARIAL = 256,
    BUILD_ROUNDS = 7
};

static const struct {
    const char *name;
    int bins;   /* 0: the kd-tree */
    bool naive; /* boxes and origin rounded to nearest */
} METHODS[] = {{"kdtree", 0, false}, {"bvh-4", 4, false},
               {"bvh-8", 8, false},  {"bvh-16", 16, false},
               {"bvh-32", 32, false}, {"bvh-64", 64, false},
               {"naive", 32, true}};
enum { N_METHODS = sizeof METHODS / sizeof METHODS[0] };
enum { BREAKEVEN_METHOD = 4 }; /* bvh-32: the default bins */

/* ---------------------------------------------------------------- trees */

/* m sharing its arrays, with no tree. */
static mesh bare(const mesh *m)
{
    mesh b = *m;
    b.tree = (kdtree){0}, b.leaf_corners = NULL, b.bvh = (bvh){0};
    return b;
}

/* Builds method k's tree of t, which shares a mesh's arrays. */
static void build_method(mesh *t, int k)
{
    bool ok;
    if (METHODS[k].bins == 0) {
        kdtree_params p = kdtree_default_params();
        ok = mesh_build_tree(t, &p);
    } else {
        bvh_params p = {.bins = METHODS[k].bins};
        ok = mesh_build_bvh(t, &p);
    }
    if (!ok)
        exit(1);
}

/* Method k's nearest hit along mr: its triangle, or -1. */
static int nearest_by(const mesh *t, int k, const mesh_ray *mr,
                      triangle_hit *th, render_stats *stats)
{
    return METHODS[k].naive ? naive_bvh_nearest(t, mr, th, stats)
                            : mesh_nearest(t, mr, 0, INFINITY, th, stats);
}

/* ---------------------------------------------------------------- rays */

/* What a ray found: its triangle (-1: none) and t. */
typedef struct {
    int triangle;
    double t;
} answer;

static answer answer_of(const mesh *t, int k, ray r, render_stats *stats)
{
    mesh_ray mr = mesh_ray_of(r);
    triangle_hit th;
    int i = k < 0 ? mesh_nearest(t, &mr, 0, INFINITY, &th, stats)
                  : nearest_by(t, k, &mr, &th, stats);
    return (answer){i, i >= 0 ? th.t : INFINITY};
}

static bool same(answer a, answer b)
{
    return a.triangle == b.triangle && memcmp(&a.t, &b.t, sizeof a.t) == 0;
}

/* The ordinary rays: every stride-th row and column of the side x side
 * rays, in double. */
static ray *ordinary_rays(const float_ray *rays, int side, int stride, int *n)
{
    ray *out = malloc((size_t)side * side * sizeof *out);
    if (out == NULL)
        exit(1);
    *n = 0;
    for (int y = 0; y < side; y += stride)
        for (int x = 0; x < side; x += stride)
            out[(*n)++] = ray_of(&rays[(size_t)y * side + x]);
    return out;
}

/* A random corner of a random triangle of m. */
static vec3 some_vertex(const mesh *m, rng_state *r)
{
    const int *v = m->triangles[rng_next(r) % m->triangle_count].v;
    return m->vertices[v[rng_next(r) % 3]];
}

/* 3 n rays at m from points a box diagonal from its centre: n aimed at
 * vertices, n at points of edges, n along the axes through vertices. */
static ray *adversarial_rays(const mesh *m, int n)
{
    ray *out = malloc(3 * (size_t)n * sizeof *out);
    if (out == NULL)
        exit(1);
    rng_state r = {20260917};
    vec3 c = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    double diag = vec3_length(vec3_sub(m->bounds.hi, m->bounds.lo));
    for (int k = 0; k < n; k++) {
        vec3 o = vec3_add(c, vec3_scale(rng_unit_vector(&r, 0.1), diag));
        out[3 * k] = (ray){o, vec3_sub(some_vertex(m, &r), o)};
        const int *v = m->triangles[rng_next(&r) % m->triangle_count].v;
        int e = (int)(rng_next(&r) % 3); /* the edge from corner e */
        vec3 a = m->vertices[v[e]], b = m->vertices[v[(e + 1) % 3]];
        vec3 on = vec3_add(a, vec3_scale(vec3_sub(b, a), rng_uniform01(&r)));
        out[3 * k + 1] = (ray){o, vec3_sub(on, o)};
        int axis = (int)(rng_next(&r) % 3);
        double sign = rng_next(&r) >> 63 ? 1 : -1, d[3] = {0, 0, 0};
        d[axis] = sign;
        vec3 dir = {d[0], d[1], d[2]}, at = some_vertex(m, &r);
        out[3 * k + 2] = (ray){vec3_sub(at, vec3_scale(dir, diag)), dir};
    }
    return out;
}

/* ---------------------------------------------------------------- a mesh */

typedef struct {
    const char *name;
    mesh m;                  /* no tree: brute force */
    mesh trees[N_METHODS];   /* sharing m's arrays, each with its tree */
    float_ray *rays;         /* the timed rays */
    int side, rounds;
    int stride, adversarial; /* of the rays that count wrong answers */
    bench_timing time[N_METHODS];  /* a ray */
    bench_timing build[N_METHODS]; /* a build (not the naive one's) */
} subject;

/* A case of the harness: each operation is the next of the timed rays
 * through one method's tree. */
typedef struct {
    const subject *s;
    int method;
    long next;
} ray_case;

static void ray_case_run(void *ctx, long reps)
{
    ray_case *c = ctx;
    const mesh *t = &c->s->trees[c->method];
    long n = (long)c->s->side * c->s->side;
    render_stats stats = {0};
    double sum = 0;
    for (long r = 0; r < reps; r++) {
        mesh_ray mr = mesh_ray_of(ray_of(&c->s->rays[c->next]));
        c->next = c->next + 1 == n ? 0 : c->next + 1;
        triangle_hit th;
        int hit = nearest_by(t, c->method, &mr, &th, &stats);
        sum += hit >= 0 ? th.t : 0;
    }
    bench_sink += sum;
}

/* Every method's rays of s, timed together. */
static void time_rays(subject *s)
{
    ray_case rc[N_METHODS];
    bench_case cases[N_METHODS];
    long n = (long)s->side * s->side;
    for (int k = 0; k < N_METHODS; k++) {
        rc[k] = (ray_case){s, k, 0};
        cases[k] = (bench_case){METHODS[k].name, s->name, ray_case_run,
                                &rc[k], n};
    }
    bench_time_cases_rounds(cases, N_METHODS, s->rounds, s->time);
}

/* The rays of rays[0..n) on which each method's answer is not brute
 * force's, a million rays. */
static void wrong_per_million(const subject *s, const ray *rays, int n,
                              double wrong[N_METHODS])
{
    for (int k = 0; k < N_METHODS; k++)
        wrong[k] = 0;
    for (int i = 0; i < n; i++) {
        render_stats stats = {0};
        answer truth = answer_of(&s->m, -1, rays[i], &stats);
        for (int k = 0; k < N_METHODS; k++)
            wrong[k] += !same(answer_of(&s->trees[k], k, rays[i], &stats),
                              truth);
    }
    for (int k = 0; k < N_METHODS; k++)
        wrong[k] *= 1e6 / n;
}

/* The nodes and the triangle tests of each method, a timed ray. */
static void count_visits(const subject *s)
{
    long n = (long)s->side * s->side;
    for (int k = 0; k < N_METHODS; k++) {
        render_stats stats = {0};
        for (long i = 0; i < n; i++)
            answer_of(&s->trees[k], k, ray_of(&s->rays[i]), &stats);
        char param[64];
        snprintf(param, sizeof param, "%s@%s", METHODS[k].name, s->name);
        double nodes = METHODS[k].bins ? stats.bvh_nodes : stats.kd_nodes;
        bench_row("nodes", param, NULL, "%.2f", nodes / n, "nodes_per_ray");
        bench_row("tests", param, NULL, "%.2f",
                  (double)stats.triangle_tests / n, "triangle_tests_per_ray");
        bench_row("bytes", param, NULL, "%.1f",
                  (double)mesh_tree_bytes(&s->trees[k]) /
                      s->m.triangle_count, "bytes_per_triangle");
    }
}

/* s's trees, its rays' times and its wrong answers, as CSV rows. */
static void measure(subject *s)
{
    for (int k = 0; k < N_METHODS; k++) {
        s->trees[k] = bare(&s->m);
        build_method(&s->trees[k], k);
        if (METHODS[k].naive)
            naive_bvh_boxes(&s->trees[k], 0);
    }
    s->rays = make_rays(&s->m, 1.0, s->side);
    time_rays(s);
    int n_ordinary;
    ray *ordinary = ordinary_rays(s->rays, s->side, s->stride, &n_ordinary);
    ray *adversarial = adversarial_rays(&s->m, s->adversarial);
    double wrong[2][N_METHODS];
    wrong_per_million(s, ordinary, n_ordinary, wrong[0]);
    wrong_per_million(s, adversarial, 3 * s->adversarial, wrong[1]);
    for (int k = 0; k < N_METHODS; k++) {
        bench_row(METHODS[k].name, s->name, &s->time[k], "%.0f", wrong[0][k],
                  "ordinary_wrong_per_million");
        bench_row(METHODS[k].name, s->name, &s->time[k], "%.0f", wrong[1][k],
                  "adversarial_wrong_per_million");
    }
    printf("rays,%s,,%d,ordinary_rays\n", s->name, n_ordinary);
    printf("rays,%s,,%d,adversarial_rays\n", s->name, 3 * s->adversarial);
    count_visits(s);
    free(ordinary), free(adversarial);
    fflush(stdout);
}

/* ---------------------------------------------------------------- builds */

/* A case of the harness: each operation builds one method's tree. */
typedef struct {
    mesh t;
    int method;
} build_case;

static void build_run(void *ctx, long reps)
{
    build_case *b = ctx;
    for (long r = 0; r < reps; r++)
        build_method(&b->t, b->method);
    bench_sink += b->t.bvh.node_count + b->t.tree.node_count;
}

/* Every tree of s but the naive one (the same build as bvh-32), built in
 * turns. */
static void time_builds(subject *s)
{
    enum { BUILDS = N_METHODS - 1 };
    build_case b[BUILDS];
    bench_case cases[BUILDS];
    bench_timing *t = s->build;
    char names[BUILDS][32];
    for (int k = 0; k < BUILDS; k++) {
        b[k] = (build_case){bare(&s->m), k};
        snprintf(names[k], sizeof names[k], "%s-build", METHODS[k].name);
        cases[k] = (bench_case){names[k], s->name, build_run, &b[k], 1};
    }
    bench_time_cases_rounds(cases, BUILDS, BUILD_ROUNDS, t);
    for (int k = 0; k < BUILDS; k++) {
        bench_row(names[k], s->name, &t[k], "%.1f",
                  t[k].median / s->m.triangle_count, "ns_per_triangle");
        mesh_free_tree(&b[k].t);
    }
    fflush(stdout);
}

/* Each tree's time a ray beside its build's time a triangle, in one row
 * for the chart; and the rays a triangle from which the kd-tree's faster
 * rays repay its slower build, against the BVH of BREAKEVEN_METHOD. */
static void tradeoff_rows(const subject *s)
{
    for (int k = 0; k < N_METHODS - 1; k++) {
        char param[64];
        snprintf(param, sizeof param, "%s@%s", METHODS[k].name, s->name);
        bench_row("tradeoff", param, &s->time[k], "%.1f",
                  s->build[k].median / s->m.triangle_count,
                  "build_ns_per_triangle");
    }
    int b = BREAKEVEN_METHOD;
    double saved = s->build[0].median - s->build[b].median; /* by the BVH */
    double lost = s->time[b].median - s->time[0].median;    /* a ray */
    printf("breakeven,%s,0,%.1f,rays_per_triangle\n", s->name,
           lost > 0 ? saved / lost / s->m.triangle_count : -1);
}

int main(int argc, char **argv)
{
    const char *bunny = argc > 1 ? argv[1] : "meshes/bunny.obj";
    const char *teapot = argc > 2 ? argv[2] : "meshes/teapot-8.obj";
    bench_print_machine();
    bench_csv_header();
    static subject s[3] = {
        {.name = "bunny", .side = SIDE, .stride = STRIDE,
         .adversarial = ADVERSARIAL},
        {.name = "teapot", .side = SIDE, .stride = STRIDE,
         .adversarial = ADVERSARIAL},
        {.name = "bunny-far", .side = FAR_SIDE, .rounds = FAR_ROUNDS,
         .stride = 1, .adversarial = FAR_ADVERSARIAL}};
    load_float_mesh(bunny, &s[0].m);
    load_float_mesh(teapot, &s[1].m);
    load_float_mesh(bunny, &s[2].m);
    for (int k = 0; k < s[2].m.vertex_count; k++) /* moved by 10^6 */
        s[2].m.vertices[k] = vec3_add(s[2].m.vertices[k], (vec3){1e6, 1e6, 1e6});
    mesh_compute_bounds(&s[2].m);
    for (int k = 0; k < 3; k++) {
        s[k].rounds = s[k].rounds ? s[k].rounds : bench_rounds();
        measure(&s[k]);
    }
    for (int k = 0; k < 2; k++)
        time_builds(&s[k]);
    for (int k = 0; k < 2; k++)
        tradeoff_rows(&s[k]);
    return 0;
}
