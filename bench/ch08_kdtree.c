/* ch08_kdtree.c: what a kd-tree costs and what it saves.
 *
 *   build/rel/bench/ch08_kdtree [BUNNY.obj TEAPOT.obj] > figures/ch08-kdtree.csv
 *   build/rel/bench/ch08_kdtree --fans    (section 7 alone)
 *
 * Every time is taken by the harness of timing.h: thread CPU time, the
 * methods of one comparison interleaved round by round, the median and
 * quartiles of the rounds (21 rounds, or fewer where one operation takes
 * seconds, as stated below). The CSV starts with its machine line; its
 * columns are method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns.
 * Rows with an empty ns_per_op are counts; rows with ns_per_op 0 are
 * derived from the medians of other rows. Every ray set is ch08_rays.h's.
 *
 * 1. The benchmark's rays through the renderer's tree (mesh_nearest), for
 *    the bunny and the teapot at K = 1 and 2.5, timed together with the
 *    recursive walk and a shuffled order on the bunny at K = 1; and the
 *    two meshes' builds:
 *      kdtree,MESH-K,ns_per_ray,Mrays/s,mrays_per_s
 *      hits,MESH-K,,count,kdtree_hits   distance,MESH-K,,sum,kdtree_sum_t
 *      walk-recursive|walk-iterative,bunny-1.0,ns_per_ray,nodes,nodes_per_ray
 *      kdtree-shuffled,bunny-1.0,ns_per_ray,Mrays/s,mrays_per_s (the same
 *          rays in a pseudo-random order instead of the pixels')
 *      kdtree-build,MESH,ns_per_build,ms,build_ms
 * 2. Where the time of a ray goes (bunny, K = 1 and 2.5, 512 x 512 rays
 *    from the renderer's camera): making the camera's ray, then its
 *    per-ray constants (1 / d and chapter 4's shear, which the search
 *    makes again once the ray is inside the box, as it tests the box
 *    again), then the box test, then the walk and the leaves, each step
 *    timed with the steps before it, the eight together:
 *      fixed-cost,STEP@K,ns_per_ray_so_far,share,share_of_ray
 *    (share: this step's part of the whole ray's median time).
 * 3. The crossover: the first N triangles of the bunny (N = 1, 2, 4, ...,
 *    all), 64 x 64 rays at K = 1 fitted to their box (SLOW_ROUNDS rounds
 *    from 16,384 triangles), by brute force, by a
 *    median-split tree and by the SAH tree (every tree forced, however
 *    small), the three interleaved; and N random spheres searched as a list
 *    or through the objects' tree, the two interleaved:
 *      brute-force|median|sah,N,ns_per_ray,tests,triangle_tests_per_ray
 *      METHOD,N,,count,rays_unlike_brute_force (hit or distance differs)
 *      objects-list|objects-tree,N,ns_per_ray,tests,sphere_tests_per_ray
 *      crossover,triangles|spheres,0,N,tree_faster_from (from the medians)
 * 4. The SAH's parameters, one at a time from the defaults (bunny, K = 1,
 *    256 x 256 rays): each family's trees traced interleaved (21 rounds)
 *    and built interleaved (SLOW_ROUNDS rounds):
 *      sah-FAMILY,VALUE,ns_per_ray,ms,build_ms (the build's median)
 *      sah-build-FAMILY,VALUE,ns_per_build,ns,ns_per_ray (the trace's)
 *      sah-FAMILY,VALUE,,count,nodes|references_per_triangle
 *    FAMILY: traversal-cost, empty-bonus, max-depth.
 * 5. Build time per triangle against N for subdivided, bumpy spheres of
 *    1,280 to 1,310,720 triangles (made here, no download), the builds of
 *    one size interleaved (SLOW_ROUNDS rounds from 327,680 triangles; the
 *    per-node sort is not run at 1,310,720, where one build takes 10 s):
 *      build-sah|build-sorting|build-median,N,ns_per_triangle,ms,build_ms
 * 6. (Chapter 12's bench/ch12_threads.c times the render on one core and on two.)
 * 7. Two 16 MiB OBJ files of one fan face, made in memory and read by
 *    mesh_parse_obj (fan_text): "distinct", as many rim vertices as fit
 *    (f 1 2 3 ... N), and "coincident", three vertices and
 *    f 1 2 3 2 3 2 3 ..., whose triangles all coincide. Their reading and
 *    their builds (SLOW_ROUNDS rounds) are timed, the two kinds
 *    interleaved; the rays are the benchmark's at K = 0.5 for the square
 *    [-1, 1]^2 that both fans cover, 4 x 4 of them (2 x 2 through the
 *    coincident fan), through the tree and by brute force, interleaved:
 *      fan-load|fan-build,KIND,ns,ms,load_ms|build_ms
 *      fan,KIND,,count,bytes|triangles|nodes   fan,KIND,,refs,
 *          references_per_triangle
 *      fan-tree|fan-brute,KIND,ns_per_ray,tests,triangle_tests_per_ray
 *      fan,KIND,0,s,render_320x240_s (a 320 x 240 picture at the tree's
 *      time per ray)   fan,KIND,0,ratio,brute_over_tree */
#include <string.h>

#include "../tests/rng.h"
#include "camera.h"
#include "scene.h"
#include "search.h"
#include "trees.h"
#include "ch08_rays.h"
#include "timing.h"

/* SLOW_ROUNDS: the rounds of cases whose one batch takes a tenth of a
 * second or more, where 21 rounds of every such case would take minutes. */
enum { SIDE = 1024, SLOW_ROUNDS = 5 };

/* ---------------------------------------------------------------- cases */

static bool build(mesh *m, kdtree_params p)
{
    return mesh_build_tree(m, &p);
}

static kdtree_params forced(kdtree_method method)
{
    kdtree_params p = kdtree_default_params();
    p.method = method;
    p.min_items = 1; /* a tree however few the triangles */
    return p;
}

/* A mesh that shares m's vertices and triangles and has no tree yet: the
 * tree it gets is its own. */
static mesh sharing(const mesh *m)
{
    mesh copy = *m;
    copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
    return copy;
}

static void free_tree(mesh *m)
{
    kdtree_free(&m->tree);
    free(m->leaf_corners), m->leaf_corners = NULL;
}

/* A case of the harness: each operation builds the tree of its mesh
 * (a copy sharing the triangles) with its parameters. */
typedef struct {
    mesh m;
    kdtree_params p;
} build_case;

static void build_run(void *ctx, long reps)
{
    build_case *b = ctx;
    for (long r = 0; r < reps; r++)
        if (!build(&b->m, b->p))
            exit(1);
    bench_sink += b->m.tree.node_count;
}

/* A case of the harness: each operation traces the next of the rays
 * rays[0..n), through m's tree (or its triangles, without one). */
typedef struct {
    const mesh *m;
    const float_ray *rays;
    long n, next;
    bool recursive;
} ray_case;

static void ray_case_run(void *ctx, long reps)
{
    ray_case *c = ctx;
    render_stats stats = {0};
    double sum = 0;
    for (long r = 0; r < reps; r++) {
        mesh_ray mr = mesh_ray_of(ray_of(&c->rays[c->next]));
        c->next = c->next + 1 == c->n ? 0 : c->next + 1;
        triangle_hit th;
        int hit = c->recursive ? mesh_nearest_recursive(c->m, &mr, 0, INFINITY, &th, &stats)
                               : mesh_nearest(c->m, &mr, 0, INFINITY, &th, &stats);
        sum += hit >= 0 ? th.t : 0;
    }
    bench_sink += sum;
}

/* What tracing rays[0..n) through m finds and counts, once: the hits, the
 * sum of their distances, and each ray's distance in t (infinity: a
 * miss) when t is not NULL. */
typedef struct {
    long hits;
    double sum_t;
    render_stats stats;
} trace_count;

static trace_count count_rays(const mesh *m, const float_ray *rays, int n, bool recursive,
                              float *t)
{
    trace_count c = {0, 0, {0}};
    for (int k = 0; k < n; k++) {
        mesh_ray mr = mesh_ray_of(ray_of(&rays[k]));
        triangle_hit th;
        int hit = recursive ? mesh_nearest_recursive(m, &mr, 0, INFINITY, &th, &c.stats)
                            : mesh_nearest(m, &mr, 0, INFINITY, &th, &c.stats);
        c.hits += hit >= 0;
        c.sum_t += hit >= 0 ? th.t : 0;
        if (t)
            t[k] = hit >= 0 ? (float)th.t : INFINITY;
    }
    return c;
}

/* ---------------------------------------------------------------- 1 */

/* The two meshes' trees with the defaults, built in turns. */
static void tree_builds(const mesh *meshes, const char **names)
{
    build_case b[2] = {{sharing(&meshes[0]), kdtree_default_params()},
                       {sharing(&meshes[1]), kdtree_default_params()}};
    bench_case cases[2] = {{"kdtree-build", names[0], build_run, &b[0], 1},
                           {"kdtree-build", names[1], build_run, &b[1], 1}};
    bench_timing t[2];
    bench_time_cases(cases, 2, t);
    for (int k = 0; k < 2; k++) {
        bench_row("kdtree-build", names[k], &t[k], "%.3f", t[k].median / 1e6, "build_ms");
        free_tree(&b[k].m);
    }
    fflush(stdout);
}

/* A copy of rays[0..n) in a pseudo-random order, from a fixed seed. */
static float_ray *shuffled(const float_ray *rays, long n)
{
    float_ray *copy = malloc((size_t)n * sizeof *copy);
    if (copy == NULL)
        exit(1);
    memcpy(copy, rays, (size_t)n * sizeof *copy);
    rng_state rng = {0x2545F4914F6CDD1DULL};
    for (long k = n - 1; k > 0; k--) { /* Fisher-Yates */
        long j = (long)(rng_uniform01(&rng) * (double)(k + 1));
        float_ray swap = copy[k];
        copy[k] = copy[j], copy[j] = swap;
    }
    return copy;
}

/* The benchmark's rays through the bunny and the teapot at K = 1 and 2.5,
 * the recursive walk on the bunny at K = 1, and the same rays of the bunny
 * in a shuffled order, the six interleaved. */
static void exact_rays(const mesh *meshes, const char **names)
{
    enum { CASES = 6 };
    float_ray *rays[4];
    ray_case rc[CASES];
    bench_case cases[CASES];
    char params[4][32];
    long n = (long)SIDE * SIDE;
    for (int c = 0; c < 4; c++) {
        double K = c % 2 == 0 ? 1.0 : 2.5;
        rays[c] = make_rays(&meshes[c / 2], K, SIDE);
        snprintf(params[c], sizeof params[c], "%s-%.1f", names[c / 2], K);
        rc[c] = (ray_case){&meshes[c / 2], rays[c], n, 0, false};
        cases[c] = (bench_case){"kdtree", params[c], ray_case_run, &rc[c], n};
    }
    rc[4] = (ray_case){&meshes[0], rays[0], n, 0, true};
    cases[4] = (bench_case){"walk-recursive", params[0], ray_case_run, &rc[4], n};
    float_ray *mixed = shuffled(rays[0], n);
    rc[5] = (ray_case){&meshes[0], mixed, n, 0, false};
    cases[5] = (bench_case){"kdtree-shuffled", params[0], ray_case_run, &rc[5], n};
    bench_timing t[CASES];
    bench_time_cases(cases, CASES, t);
    for (int c = 0; c < 4; c++) {
        trace_count found = count_rays(rc[c].m, rays[c], (int)n, false, NULL);
        bench_row("kdtree", params[c], &t[c], "%.4f", 1e3 / t[c].median, "mrays_per_s");
        printf("hits,%s,,%ld,kdtree_hits\n", params[c], found.hits);
        printf("distance,%s,,%.6f,kdtree_sum_t\n", params[c], found.sum_t);
    }
    for (int w = 0; w < 2; w++) { /* the recursive walk against the iterative one */
        trace_count walk = count_rays(&meshes[0], rays[0], (int)n, w == 0, NULL);
        bench_row(w == 0 ? "walk-recursive" : "walk-iterative", params[0], &t[w == 0 ? 4 : 0],
                  "%.3f", (double)walk.stats.kd_nodes / (double)n, "nodes_per_ray");
    }
    bench_row("kdtree-shuffled", params[0], &t[5], "%.4f", 1e3 / t[5].median, "mrays_per_s");
    for (int c = 0; c < 4; c++)
        free(rays[c]);
    free(mixed);
    fflush(stdout);
}

/* ---------------------------------------------------------------- 2 */

/* A case of the harness: each operation is the next pixel's ray from the
 * renderer's camera, taken through the first `steps` steps of a ray. */
typedef struct {
    const mesh *m;
    camera_view view;
    int side, steps;
    long next; /* the next pixel */
} fixed_case;

static void fixed_run(void *ctx, long reps)
{
    fixed_case *j = ctx;
    render_stats stats = {0};
    double sum = 0;
    for (long r = 0; r < reps; r++) {
        /* row by row, as the renderer goes (with a row and a column
           counter instead, the camera's ray alone measured 12.8 ns, not 5.7:
           the steps' shares move with the loop around them) */
        int px = (int)(j->next % j->side), py = (int)(j->next / j->side);
        j->next = (j->next + 1) % ((long)j->side * j->side);
        ray ray = camera_view_ray(&j->view, px, py);
        sum += ray.dir.x;
        if (j->steps < 2)
            continue;
        mesh_ray mr = mesh_ray_of(ray); /* 1 / d */
        watertight_ray shear = watertight_ray_of(ray); /* the search's */
        sum += mr.inv_dir.x + shear.sz;
        if (j->steps < 3)
            continue;
        double near = 0, far = INFINITY;
        sum += box_clip(&j->m->bounds, mr.r.origin, mr.inv_dir, &near, &far);
        if (j->steps < 4)
            continue;
        triangle_hit th;
        sum += mesh_nearest(j->m, &mr, 0, INFINITY, &th, &stats);
    }
    bench_sink += sum;
}

/* The bunny where the renderer's camera sees it as the benchmark's rays
 * do at distance K: the camera looks down +z from the origin, so the mesh
 * is turned half a turn about y and moved; its own tree, built anew. */
static mesh bunny_before_camera(const mesh *bunny, double K)
{
    mesh m = sharing(bunny);
    vec3 c = vec3_scale(vec3_add(m.bounds.lo, m.bounds.hi), 0.5);
    double diag = vec3_length(vec3_sub(m.bounds.hi, m.bounds.lo));
    m.vertices = malloc((size_t)m.vertex_count * sizeof *m.vertices);
    if (m.vertices == NULL)
        exit(1);
    for (int v = 0; v < m.vertex_count; v++) {
        vec3 p = vec3_sub(bunny->vertices[v], c); /* turned: x, z negated */
        m.vertices[v] = (vec3){-p.x, p.y, K * diag - p.z};
    }
    mesh_compute_bounds(&m);
    if (!build(&m, kdtree_default_params()))
        exit(1);
    return m;
}

static void fixed_costs(const mesh *bunny)
{
    static const char *steps[4] = {"camera ray", "per-ray constants", "box test",
                                   "walk and leaves"};
    enum { PIXELS = 512 };
    camera cam = {.fov_deg = 60, .width = PIXELS, .height = PIXELS};
    mesh m[2] = {bunny_before_camera(bunny, 1.0), bunny_before_camera(bunny, 2.5)};
    fixed_case fc[8];
    bench_case cases[8];
    char params[8][48];
    for (int c = 0; c < 8; c++) {
        snprintf(params[c], sizeof params[c], "%s@%.1f", steps[c % 4], c < 4 ? 1.0 : 2.5);
        fc[c] = (fixed_case){&m[c / 4], camera_view_of(&cam), PIXELS, c % 4 + 1, 0};
        cases[c] = (bench_case){"fixed-cost", params[c], fixed_run, &fc[c],
                                (long)PIXELS * PIXELS};
    }
    bench_timing t[8];
    bench_time_cases(cases, 8, t);
    for (int c = 0; c < 8; c++) { /* each step's share of the whole ray */
        double before = c % 4 ? t[c - 1].median : 0, whole = t[c / 4 * 4 + 3].median;
        bench_row("fixed-cost", params[c], &t[c], "%.4f", (t[c].median - before) / whole,
                  "share_of_ray");
    }
    for (int k = 0; k < 2; k++) {
        free(m[k].vertices);
        free_tree(&m[k]);
    }
    fflush(stdout);
}

/* ---------------------------------------------------------------- 3 */

/* Where the line b crosses below the line a, both sampled at n[0..count)
 * (increasing): after the last size at which b is not cheaper, by
 * interpolating the difference linearly in log n. */
static double crossover(const double *n, const double *a, const double *b, int count)
{
    int last = -1;
    for (int k = 0; k < count; k++)
        if (b[k] >= a[k])
            last = k;
    if (last < 0)
        return n[0];
    if (last == count - 1)
        return n[count - 1];
    double d0 = b[last] - a[last], d1 = b[last + 1] - a[last + 1];
    double f = d0 / (d0 - d1);
    return exp(log(n[last]) + f * (log(n[last + 1]) - log(n[last])));
}

/* The first n triangles of whole, sharing its vertices; bounds of those. */
static mesh first_triangles(const mesh *whole, int n)
{
    mesh m = {.vertices = whole->vertices, .vertex_count = whole->vertex_count,
              .triangles = whole->triangles, .triangle_count = n};
    box b = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (int k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            vec3 v = whole->vertices[whole->triangles[k].v[c]];
            b = (box){vec3_min(b.lo, v), vec3_max(b.hi, v)};
        }
    m.bounds = b;
    return m;
}

/* How many of the n rays a tree answers unlike brute force: another hit,
 * or another distance (reference: brute force's distances). */
static long unlike(const float *reference, const float *t, int n)
{
    long differ = 0;
    for (int k = 0; k < n; k++)
        differ += !(reference[k] == t[k] || (isinf(reference[k]) && isinf(t[k])));
    return differ;
}

/* Brute force, the median-split tree and the SAH tree on the first n
 * triangles, the three interleaved (in SLOW_ROUNDS rounds from 16,384
 * triangles, where one pass of brute force takes a second or more); their
 * medians in ns[0..3). */
static void crossover_point(const mesh *bunny, int n, float *reference, float *t, double *ns)
{
    static const char *names[3] = {"brute-force", "median", "sah"};
    enum { RAYS = 64 * 64 };
    mesh m[3];
    m[0] = first_triangles(bunny, n);
    float_ray *rays = make_rays(&m[0], 1.0, 64);
    ray_case rc[3];
    bench_case cases[3];
    char param[16];
    snprintf(param, sizeof param, "%d", n);
    for (int k = 0; k < 3; k++) {
        m[k] = m[0];
        if (k > 0 && !build(&m[k], forced(k == 1 ? KDTREE_MEDIAN : KDTREE_SAH)))
            exit(1);
        rc[k] = (ray_case){&m[k], rays, RAYS, 0, false};
        cases[k] = (bench_case){names[k], param, ray_case_run, &rc[k], RAYS};
    }
    bench_timing timing[3];
    if (n < 16384)
        bench_time_cases(cases, 3, timing);
    else
        bench_time_cases_rounds(cases, 3, SLOW_ROUNDS, timing);
    for (int k = 0; k < 3; k++) {
        trace_count c = count_rays(&m[k], rays, RAYS, false, k == 0 ? reference : t);
        ns[k] = timing[k].median;
        bench_row(names[k], param, &timing[k], "%.3f", (double)c.stats.triangle_tests / RAYS,
                  "triangle_tests_per_ray");
        printf("%s,%d,,%ld,rays_unlike_brute_force\n", names[k], n,
               k == 0 ? 0 : unlike(reference, t, RAYS));
        if (k > 0)
            free_tree(&m[k]);
    }
    free(rays);
    fflush(stdout);
}

static void crossover_meshes(const mesh *bunny)
{
    double sizes[32], ns[3][32];
    int count = 0;
    float *reference = malloc(64 * 64 * sizeof *reference), *t = malloc(64 * 64 * sizeof *t);
    if (reference == NULL || t == NULL)
        exit(1);
    for (int n = 1;; n = 2 * n < bunny->triangle_count ? 2 * n : bunny->triangle_count) {
        double point[3];
        crossover_point(bunny, n, reference, t, point);
        for (int k = 0; k < 3; k++)
            ns[k][count] = point[k];
        sizes[count++] = n;
        if (n == bunny->triangle_count)
            break;
    }
    free(reference), free(t);
    printf("crossover,triangles,0,%.1f,tree_faster_from\n",
           crossover(sizes, ns[0], ns[2], count));
}

/* A case of the harness: each operation is the next ray of rays[0..n)
 * through the scene's objects. */
typedef struct {
    const scene *s;
    const ray *rays;
    long n, next;
} scene_case;

static void scene_run(void *ctx, long reps)
{
    scene_case *c = ctx;
    render_stats stats = {0};
    double sum = 0;
    for (long r = 0; r < reps; r++) {
        hit h;
        sum += scene_intersect(c->s, c->rays[c->next], 0, INFINITY, &h, &stats);
        c->next = c->next + 1 == c->n ? 0 : c->next + 1;
    }
    bench_sink += sum;
}

/* A pseudo-random number in [0, 1), from a fixed seed. */
static double uniform01(void)
{
    static rng_state rng = {0x9E3779B97F4A7C15ULL}; /* fixed seed */
    return rng_uniform01(&rng);
}

/* The spheres of one point of the chart: n in the cube [-1, 1]^3 around
 * z = 6, smaller as there are more, added to both scenes. */
static void add_spheres(scene *list, scene *tree, int n)
{
    for (int k = 0; k < n; k++) {
        object o = {.kind = SHAPE_SPHERE};
        o.sphere.center = (vec3){2 * uniform01() - 1, 2 * uniform01() - 1, 5 + 2 * uniform01()};
        o.sphere.radius = 0.5 / sqrt(n) * (0.5 + uniform01());
        if (!scene_add_object(list, o) || !scene_add_object(tree, o))
            exit(1);
    }
}

/* The same n spheres as a list and through a tree, interleaved. */
static void objects_point(int n, const ray *rays, int count, double *ns)
{
    scene s[2];
    scene_init(&s[0]), scene_init(&s[1]);
    add_spheres(&s[0], &s[1], n);
    scene_case sc[2];
    bench_case cases[2];
    char param[16];
    snprintf(param, sizeof param, "%d", n);
    for (int tree = 0; tree < 2; tree++) {
        s[tree].tree_params.min_items = 1;
        s[tree].tree_params.method = tree ? KDTREE_SAH : KDTREE_NONE;
        if (!scene_build_trees(&s[tree], NULL))
            exit(1);
        sc[tree] = (scene_case){&s[tree], rays, count, 0};
        cases[tree] = (bench_case){tree ? "objects-tree" : "objects-list", param, scene_run,
                                   &sc[tree], count};
    }
    bench_timing t[2];
    bench_time_cases(cases, 2, t);
    for (int tree = 0; tree < 2; tree++) {
        render_stats stats = {0};
        for (int k = 0; k < count; k++) {
            hit h;
            scene_intersect(&s[tree], rays[k], 0, INFINITY, &h, &stats);
        }
        ns[tree] = t[tree].median;
        bench_row(cases[tree].method, param, &t[tree], "%.3f",
                  (double)stats.sphere_tests / count, "sphere_tests_per_ray");
        scene_free(&s[tree]);
    }
    fflush(stdout);
}

static void crossover_objects(void)
{
    enum { RAYS = 4096 };
    static ray rays[RAYS];
    for (int k = 0; k < RAYS; k++) { /* from the eye into the square [-1, 1]^2 at z = 6 */
        vec3 aim = {2 * uniform01() - 1, 2 * uniform01() - 1, 6};
        rays[k] = (ray){{0, 0, 0}, vec3_normalize(aim)};
    }
    double sizes[11], ns[2][11];
    for (int n = 1, count = 0; n <= 1024; n *= 2, count++) {
        double point[2];
        objects_point(n, rays, RAYS, point);
        sizes[count] = n, ns[0][count] = point[0], ns[1][count] = point[1];
    }
    printf("crossover,spheres,0,%.1f,tree_faster_from\n", crossover(sizes, ns[0], ns[1], 11));
}

/* ---------------------------------------------------------------- 4 */

/* One family of the SAH's parameters: the values of one parameter, the
 * others at their defaults. */
typedef struct {
    const char *name;
    const double *values;
    int count;
} sah_family;

static kdtree_params with_value(const char *family, double value)
{
    kdtree_params p = kdtree_default_params();
    if (strcmp(family, "traversal-cost") == 0)
        p.traversal_cost = value;
    else if (strcmp(family, "empty-bonus") == 0)
        p.empty_bonus = value;
    else
        p.max_depth = (int)value;
    return p;
}

/* The family's trees traced interleaved, and built interleaved. */
static void sah_family_points(const mesh *bunny, const float_ray *rays, int n, sah_family f)
{
    enum { MAX = 16 };
    mesh traced[MAX];
    build_case builds[MAX];
    ray_case rc[MAX];
    bench_case trace_cases[MAX], build_cases[MAX];
    char params[MAX][16], build_name[64], trace_name[64];
    snprintf(trace_name, sizeof trace_name, "sah-%s", f.name);
    snprintf(build_name, sizeof build_name, "sah-build-%s", f.name);
    for (int k = 0; k < f.count; k++) {
        kdtree_params p = with_value(f.name, f.values[k]);
        snprintf(params[k], sizeof params[k], "%g", f.values[k]);
        traced[k] = sharing(bunny);
        if (!build(&traced[k], p))
            exit(1);
        rc[k] = (ray_case){&traced[k], rays, n, 0, false};
        trace_cases[k] = (bench_case){trace_name, params[k], ray_case_run, &rc[k], n};
        builds[k] = (build_case){sharing(bunny), p};
        build_cases[k] = (bench_case){build_name, params[k], build_run, &builds[k], 1};
    }
    bench_timing trace[MAX], built[MAX];
    bench_time_cases(trace_cases, f.count, trace);
    bench_time_cases_rounds(build_cases, f.count, SLOW_ROUNDS, built);
    for (int k = 0; k < f.count; k++) {
        const kdtree *tree = &traced[k].tree;
        bench_row(trace_name, params[k], &trace[k], "%.3f", built[k].median / 1e6, "build_ms");
        bench_row(build_name, params[k], &built[k], "%.2f", trace[k].median, "ns_per_ray");
        printf("%s,%s,,%d,nodes\n", trace_name, params[k], tree->node_count);
        printf("%s,%s,,%.3f,references_per_triangle\n", trace_name, params[k],
               (double)tree->item_count / bunny->triangle_count);
        free_tree(&traced[k]);
        free_tree(&builds[k].m);
    }
    fflush(stdout);
}

static void sah_parameters(const mesh *bunny)
{
    float_ray *rays = make_rays(bunny, 1.0, 256);
    static const double costs[] = {5, 10, 15, 20, 30, 45, 60, 80, 120, 180};
    static const double bonuses[] = {0, 0.1, 0.2, 0.3, 0.5, 0.8};
    static const double depths[] = {12, 16, 18, 20, 22, 24, 28, 32};
    const sah_family families[3] = {{"traversal-cost", costs, 10},
                                    {"empty-bonus", bonuses, 6},
                                    {"max-depth", depths, 8}};
    for (int k = 0; k < 3; k++)
        sah_family_points(bunny, rays, 256 * 256, families[k]);
    free(rays);
}

/* ---------------------------------------------------------------- 5 */

/* A sphere of 20 4^levels triangles: the unit icosphere (ch08_rays.h) with
 * its vertices pushed out to a bumpy surface, radius 1 + 0.1 sin(5x)
 * sin(7y) sin(6z) + a finer ripple, so that the triangles are neither all
 * alike nor evenly spread. */
static mesh bumpy_sphere(int levels)
{
    mesh m = unit_icosphere(levels);
    for (int k = 0; k < m.vertex_count; k++) {
        vec3 p = m.vertices[k];
        double r = 1 + 0.1 * sin(5 * p.x) * sin(7 * p.y) * sin(6 * p.z) +
                   0.02 * sin(40 * p.x + 3 * p.y) * sin(37 * p.z);
        m.vertices[k] = vec3_scale(p, r);
    }
    mesh_compute_bounds(&m);
    return m;
}

/* The three builds of one bumpy sphere, interleaved; ns per triangle. */
static void build_scaling_point(int levels, double *per)
{
    static const char *names[3] = {"build-sah", "build-sorting", "build-median"};
    static const kdtree_method methods[3] = {KDTREE_SAH, KDTREE_SAH_SORTING, KDTREE_MEDIAN};
    mesh m = bumpy_sphere(levels);
    build_case builds[3];
    bench_case cases[3];
    int count = 0, map[3]; /* the builds run at this size */
    char param[16];
    snprintf(param, sizeof param, "%d", m.triangle_count);
    for (int k = 0; k < 3; k++) {
        per[k] = 0;
        if (methods[k] == KDTREE_SAH_SORTING && levels >= 8)
            continue; /* 10 s a build */
        builds[count] = (build_case){sharing(&m), forced(methods[k])};
        cases[count] = (bench_case){names[k], param, build_run, &builds[count], 1};
        map[count++] = k;
    }
    bench_timing t[3];
    if (levels < 7)
        bench_time_cases(cases, count, t);
    else
        bench_time_cases_rounds(cases, count, SLOW_ROUNDS, t);
    for (int c = 0; c < count; c++) {
        bench_timing each = bench_timing_scaled(t[c], 1.0 / m.triangle_count);
        per[map[c]] = each.median;
        bench_row(names[map[c]], param, &each, "%.3f", t[c].median / 1e6, "build_ms");
        free_tree(&builds[c].m);
    }
    mesh_free(&m);
    fflush(stdout);
}

static void build_scaling(void)
{
    double per[6][3], sizes[6]; /* ns per triangle */
    for (int levels = 3; levels <= 8; levels++) {
        build_scaling_point(levels, per[levels - 3]);
        sizes[levels - 3] = 20 << (2 * levels);
    }
    /* from the smallest mesh to the largest: per triangle, and per level */
    double grow = per[5][0] / per[0][0];
    printf("scaling,build-sah,0,%.3f,growth_per_triangle\n", grow);
    printf("scaling,build-sah,0,%.3f,growth_per_level\n",
           grow * log2(sizes[0]) / log2(sizes[5]));
}

/* ---------------------------------------------------------------- 7 */

enum { FAN_BYTES = 16 << 20, FAN_SIDE = 4 };

/* The OBJ text of one fan face in at most FAN_BYTES bytes; its length in
 * *length. coincident: three vertices and as many indices 2 3 2 3 ... as
 * fit; otherwise vertex 1 at (0, -10, 0) and the rim vertices 2 ... N,
 * as many as fit with their indices, evenly from (-1, 1, 0) to (1, 1, 0):
 * thin, nearly upright strips side by side, distinct, which cover the
 * square [-1, 1]^2 of the view. */
static char *fan_text(bool coincident, size_t *length)
{
    char *text = malloc(FAN_BYTES);
    if (text == NULL)
        exit(1);
    size_t n = 0;
    if (coincident) {
        n += (size_t)sprintf(text, "v -4 -2 0\nv 4 -2 0\nv 0 4 0\nf 1 2 3");
        while (n + 2 + 1 <= FAN_BYTES) {
            memcpy(text + n, n % 4 == 1 ? " 3" : " 2", 2); /* alternate 2, 3 */
            n += 2;
        }
        text[n++] = '\n';
        *length = n;
        return text;
    }
    /* distinct: how many rim vertices fit, then write them */
    int rim = 0;
    size_t vbytes = 10 /* "v 0 -10 0\n" */, fbytes = 1 + 2 + 1; /* "f 1" "\n" */
    char line[64];
    for (;; rim++) {
        size_t vl = 2 + 10 + 5; /* "v %+.7f 1 0\n": 17 */
        size_t fl = (size_t)snprintf(line, sizeof line, " %d", rim + 2);
        if (vbytes + vl + fbytes + fl > FAN_BYTES)
            break;
        vbytes += vl, fbytes += fl;
    }
    n += (size_t)sprintf(text, "v 0 -10 0\n");
    for (int k = 0; k < rim; k++)
        n += (size_t)sprintf(text + n, "v %+.7f 1 0\n", -1 + 2.0 * k / (rim - 1));
    n += (size_t)sprintf(text + n, "f 1");
    for (int k = 0; k < rim; k++)
        n += (size_t)sprintf(text + n, " %d", k + 2);
    text[n++] = '\n';
    if (n > FAN_BYTES)
        exit(1);
    *length = n;
    return text;
}

/* A case of the harness: each operation reads the OBJ text into a mesh,
 * then frees it. */
typedef struct {
    const char *text, *name;
    size_t length;
} load_case;

static void load_run(void *ctx, long reps)
{
    load_case *c = ctx;
    for (long r = 0; r < reps; r++) {
        mesh m = {0};
        parse_error err;
        if (!mesh_parse_obj(&m, c->text, c->length, c->name, &err)) {
            fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col, err.message);
            exit(1);
        }
        bench_sink += m.triangle_count;
        mesh_free(&m);
    }
}

static double fan_tests(const mesh *m, const float_ray *rays, int n)
{
    return (double)count_rays(m, rays, n, false, NULL).stats.triangle_tests / n;
}

/* The rays through one fan, with its tree and by brute force, interleaved. */
static void fan_rays(const mesh *m, const char *kind, bool coincident)
{
    /* the benchmark's rays (K = 0.5) for the square [-1, 1]^2 at z = 0,
       which both fans cover; 4 x 4 rays, 2 x 2 through the coincident */
    mesh view = {.bounds = {{-1, -1, 0}, {1, 1, 0}}};
    int side = coincident ? 2 : FAN_SIDE, n = side * side;
    float_ray *rays = make_rays(&view, 0.5, side);
    mesh brute = sharing(m); /* the same triangles, no tree */
    ray_case rc[2] = {{m, rays, n, 0, false}, {&brute, rays, n, 0, false}};
    bench_case cases[2] = {{"fan-tree", kind, ray_case_run, &rc[0], n},
                           {"fan-brute", kind, ray_case_run, &rc[1], n}};
    bench_timing t[2];
    bench_time_cases(cases, 2, t);
    bench_row("fan-tree", kind, &t[0], "%.1f", fan_tests(m, rays, n), "triangle_tests_per_ray");
    bench_row("fan-brute", kind, &t[1], "%.1f", fan_tests(&brute, rays, n),
              "triangle_tests_per_ray");
    printf("fan,%s,0,%.1f,render_320x240_s\n", kind, 320 * 240 * t[0].median * 1e-9);
    printf("fan,%s,0,%.3f,brute_over_tree\n", kind, t[1].median / t[0].median);
    free(rays);
    fflush(stdout);
}

static void fans(void)
{
    static const char *kinds[2] = {"distinct", "coincident"};
    char *text[2];
    mesh m[2];
    load_case loads[2];
    build_case builds[2];
    bench_case load_cases[2], build_cases[2];
    for (int c = 0; c < 2; c++) {
        size_t length;
        text[c] = fan_text(c, &length);
        loads[c] = (load_case){text[c], kinds[c], length};
        load_cases[c] = (bench_case){"fan-load", kinds[c], load_run, &loads[c], 1};
        m[c] = (mesh){0};
        parse_error err;
        if (!mesh_parse_obj(&m[c], text[c], length, kinds[c], &err))
            exit(1);
        mesh_compute_bounds(&m[c]);
        builds[c] = (build_case){sharing(&m[c]), kdtree_default_params()};
        build_cases[c] = (bench_case){"fan-build", kinds[c], build_run, &builds[c], 1};
    }
    bench_timing loaded[2], built[2];
    bench_time_cases(load_cases, 2, loaded);
    bench_time_cases_rounds(build_cases, 2, SLOW_ROUNDS, built);
    for (int c = 0; c < 2; c++) {
        free_tree(&builds[c].m);
        free(text[c]);
        if (!build(&m[c], kdtree_default_params()))
            exit(1);
        printf("fan,%s,,%zu,bytes\n", kinds[c], loads[c].length);
        printf("fan,%s,,%d,triangles\n", kinds[c], m[c].triangle_count);
        bench_row("fan-load", kinds[c], &loaded[c], "%.1f", loaded[c].median / 1e6, "load_ms");
        bench_row("fan-build", kinds[c], &built[c], "%.1f", built[c].median / 1e6, "build_ms");
        printf("fan,%s,,%d,nodes\n", kinds[c], m[c].tree.node_count);
        printf("fan,%s,,%.3f,references_per_triangle\n", kinds[c],
               (double)m[c].tree.item_count / m[c].triangle_count);
        fan_rays(&m[c], kinds[c], c == 1);
        mesh_free(&m[c]);
    }
}

int main(int argc, char **argv)
{
    const char *paths[2] = {argc > 1 ? argv[1] : "meshes/bunny.obj",
                            argc > 2 ? argv[2] : "meshes/teapot-8.obj"};
    const char *names[2] = {"bunny", "teapot"};
    bench_print_machine();
    bench_csv_header();
    if (argc > 1 && strcmp(argv[1], "--fans") == 0) { /* section 7 alone */
        fans();
        return 0;
    }
    mesh meshes[2];
    for (int k = 0; k < 2; k++) {
        load_float_mesh(paths[k], &meshes[k]);
        if (!build(&meshes[k], kdtree_default_params()))
            return 1;
    }
    tree_builds(meshes, names);
    exact_rays(meshes, names);
    fixed_costs(&meshes[0]);
    crossover_objects();
    sah_parameters(&meshes[0]);
    crossover_meshes(&meshes[0]);
    build_scaling();
    fans();
    for (int k = 0; k < 2; k++)
        mesh_free(&meshes[k]);
    return 0;
}
