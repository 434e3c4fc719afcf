/* ch08_kdtree.c: what a kd-tree costs and what it saves.
 *
 *   build/rel/bench/ch08_kdtree [BUNNY.obj TEAPOT.obj] > figures/ch08-kdtree.csv
 *
 * Rows (method,param,ns_per_op,error,error_kind); every time is processor
 * time (cpu_seconds in ch08_rays.h), every ray set is the one of ch08_rays.h.
 *
 * 1. The benchmark's rays through the renderer's tree (mesh_nearest), one
 *    thread, for the bunny and the teapot at K = 1 and 2.5, timed together
 *    with the recursive walk by the harness of timing.h (thread CPU time,
 *    interleaved rounds, quartiles in the last columns):
 *      kdtree,MESH-K,ns_per_ray,Mrays/s,mrays_per_s (median of the rounds)
 *      hits,MESH-K,0,count,kdtree_hits   distance,MESH-K,0,sum,kdtree_sum_t
 *      build,MESH,ms,ms,kdtree_build_ms (median of BUILDS)
 *    and the recursive walk against the iterative one (bunny, K = 1):
 *      walk-recursive|walk-iterative,bunny-1.0,ns_per_ray,nodes,nodes_per_ray
 * 2. Where the time of a ray goes (bunny, K = 1 and 2.5): making the
 *    camera's ray, then its per-ray constants, then the box test, then the
 *    walk and the leaves, each step timed with the ones before it (ns_per_op:
 *    the steps so far; error: this step's share of the whole ray's time):
 *      fixed-cost,STEP@K,ns_per_ray,share,share_of_ray
 * 3. The crossover: the first N triangles of the bunny (N = 1, 2, 4, ...,
 *    all), 64 x 64 rays at K = 1 fitted to their box, by brute force, by a
 *    median-split tree and by the SAH tree (every tree forced, however
 *    small); and N random spheres searched as a list or through the
 *    objects' tree:
 *      brute-force|median|sah,N,ns_per_ray,tests,triangle_tests_per_ray
 *      METHOD,N,0,count,rays_unlike_brute_force (hit or distance differs)
 *      objects-list|objects-tree,N,ns_per_ray,tests,sphere_tests_per_ray
 * 4. The SAH's parameters, one at a time from the defaults (bunny, K = 1,
 *    256 x 256 rays): build time against trace time
 *      sah-traversal-cost|sah-empty-bonus|sah-max-depth,VALUE,ns_per_ray,
 *          ms,build_ms   (and nodes, references_per_triangle)
 * 5. Build time per triangle against N for subdivided, bumpy spheres of
 *    1,280 to 1,310,720 triangles (made here, no download), by the three
 *    builds:
 *      build-sah|build-sorting|build-median,N,ns_per_triangle,ms,build_ms
 * 6. Threads: bin/ch08 renders the chapter's bunny scene with --threads 1
 *    and 2, three times each (the render phase that --stats reports, the
 *    best of three):
 *      threads,1|2,ms,ms,render_ms   threads,2,0,speedup,speedup
 *      scene,bunny,ms,ms,load_ms   (reading the scene and building its trees)
 * 7. A 16 MiB OBJ file of one fan face, made in memory and read by
 *    mesh_parse_obj (fan_text): "distinct", as many rim vertices as fit
 *    (f 1 2 3 ... N), and "coincident", three vertices and
 *    f 1 2 3 2 3 2 3 ..., whose triangles all coincide. The rays are the
 *    benchmark's at K = 0.5 for the square [-1, 1]^2 that both fans cover,
 *    4 x 4 of them (2 x 2 through the coincident fan), through the tree
 *    and by brute force, timed by the harness of timing.h (thread CPU
 *    time, the two interleaved round by round):
 *      fan,KIND,ms,ms,load_ms | build_ms   fan,KIND,0,count,triangles
 *      fan,KIND,0,count,nodes   fan,KIND,0,refs,references_per_triangle
 *      fan-tree|fan-brute,KIND,ns_per_ray,tests,triangle_tests_per_ray
 *      fan,KIND,0,s,render_320x240_s (a 320 x 240 picture at the tree's
 *      time per ray)   fan,KIND,0,ratio,brute_over_tree
 *    These rows and those of section 1 but the build have the harness's
 *    quartile columns; the CSV starts with its machine line. */
#include <string.h>

#include "rng.h"
#include "camera.h"
#include "scene.h"
#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 1024, ROUNDS = 5, BUILDS = 5 };

static volatile double sink; /* keeps the compiler from dropping work */

/* ---------------------------------------------------------------- timing */

/* Runs one batch of work(arg) as often as it takes to fill min_seconds of
 * processor time; the seconds one batch took. The one timing function. */
static double time_batch(void (*work)(void *), void *arg, double min_seconds)
{
    int runs = 0;
    double start = cpu_seconds(), elapsed;
    do {
        work(arg);
        runs++;
        elapsed = cpu_seconds() - start;
    } while (elapsed < min_seconds);
    return elapsed / runs;
}

/* ---------------------------------------------------------------- trees */

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

typedef struct {
    mesh *m;
    kdtree_params p;
} build_job;

static void build_work(void *arg)
{
    build_job *j = arg;
    if (!build(j->m, j->p))
        exit(1);
}

static double build_ms(mesh *m, kdtree_params p)
{
    build_job j = {m, p};
    double ms[BUILDS];
    for (int b = 0; b < BUILDS; b++)
        ms[b] = 1e3 * time_batch(build_work, &j, 0);
    return median_of(ms, BUILDS);
}

/* ---------------------------------------------------------------- tracing */

typedef struct {
    const mesh *m;
    const float_ray *rays;
    int n;
    bool recursive;
    render_stats stats;
    batch result;
    float *t; /* NULL, or each ray's distance (infinity: a miss) */
} trace_job;

static void trace_work(void *arg)
{
    trace_job *j = arg;
    j->stats = (render_stats){0};
    j->result = (batch){0, 0, 0};
    for (int k = 0; k < j->n; k++) {
        mesh_ray mr = mesh_ray_of(ray_of(&j->rays[k]));
        triangle_hit th;
        int hit = j->recursive
                      ? mesh_nearest_recursive(j->m, &mr, 0, INFINITY, &th, &j->stats)
                      : mesh_nearest(j->m, &mr, 0, INFINITY, &th, &j->stats);
        j->result.hits += hit >= 0;
        j->result.sum_t += hit >= 0 ? th.t : 0;
        if (j->t)
            j->t[k] = hit >= 0 ? (float)th.t : INFINITY;
    }
}

/* Nanoseconds per ray, the median of ROUNDS batches. */
static double ns_per_ray(trace_job *j, double min_seconds)
{
    double ns[ROUNDS];
    for (int r = 0; r < ROUNDS; r++)
        ns[r] = 1e9 * time_batch(trace_work, j, min_seconds) / j->n;
    return median_of(ns, ROUNDS);
}

/* ---------------------------------------------------------------- 1 */

/* One case of the harness: reps rays of rays[0..n), in turn. */
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

/* The benchmark's rays through the bunny and the teapot at K = 1 and 2.5,
 * and the recursive walk on the bunny at K = 1, the five timed together by
 * the harness (interleaved rounds, thread CPU time). */
static void exact_rays(mesh *meshes, const char **names)
{
    for (int k = 0; k < 2; k++) {
        double ms = build_ms(&meshes[k], kdtree_default_params());
        printf("build,%s,%.3f,%.3f,kdtree_build_ms\n", names[k], ms, ms);
    }
    enum { CASES = 5 };
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
    bench_timing t[CASES];
    bench_time_cases(cases, CASES, t);
    for (int c = 0; c < 4; c++) {
        trace_job j = {rc[c].m, rays[c], SIDE * SIDE, false, {0}, {0, 0, 0}, NULL};
        trace_work(&j); /* the hits and distances, once */
        bench_row("kdtree", params[c], &t[c], "%.4f", 1e3 / t[c].median, "mrays_per_s");
        printf("hits,%s,0,%ld,kdtree_hits\n", params[c], j.result.hits);
        printf("distance,%s,0,%.6f,kdtree_sum_t\n", params[c], j.result.sum_t);
        if (c == 0) { /* the recursive walk against the iterative one */
            for (int w = 0; w < 2; w++) {
                j.recursive = w == 0;
                trace_work(&j);
                bench_row(w == 0 ? "walk-recursive" : "walk-iterative", params[0],
                          &t[w == 0 ? 4 : 0], "%.3f", (double)j.stats.kd_nodes / j.n,
                          "nodes_per_ray");
            }
            printf("walk,%s,0,%.4f,recursive_over_iterative\n", params[0],
                   t[4].median / t[0].median);
        }
    }
    for (int c = 0; c < 4; c++)
        free(rays[c]);
    fflush(stdout);
}

/* ---------------------------------------------------------------- 2 */

typedef struct {
    const mesh *m;
    camera_view view;
    int side, steps;
} fixed_job;

static void fixed_work(void *arg)
{
    fixed_job *j = arg;
    render_stats stats = {0};
    double sum = 0;
    for (int py = 0; py < j->side; py++)
        for (int px = 0; px < j->side; px++) {
            ray r = camera_view_ray(&j->view, px, py);
            sum += r.dir.x;
            if (j->steps < 2)
                continue;
            mesh_ray mr = mesh_ray_of(r);
            sum += mr.shear.sz;
            if (j->steps < 3)
                continue;
            double near = 0, far = INFINITY;
            sum += box_clip(&j->m->bounds, mr.r.origin, mr.inv_dir, &near, &far);
            if (j->steps < 4)
                continue;
            triangle_hit th;
            sum += mesh_nearest(j->m, &mr, 0, INFINITY, &th, &stats);
        }
    sink += sum;
}

/* The renderer's camera at the eye of the benchmark: the camera looks down
 * +z from the origin, so the mesh is turned half a turn about y and moved
 * to sit where the benchmark's rays see it. */
static void fixed_costs(const mesh *bunny)
{
    static const char *steps[4] = {"camera ray", "per-ray constants", "box test",
                                   "walk and leaves"};
    for (int k = 0; k < 2; k++) {
        double K = k == 0 ? 1.0 : 2.5;
        mesh m = *bunny; /* the same tree; vertices moved in a copy */
        vec3 c = vec3_scale(vec3_add(m.bounds.lo, m.bounds.hi), 0.5);
        double diag = vec3_length(vec3_sub(m.bounds.hi, m.bounds.lo));
        m.vertices = malloc((size_t)m.vertex_count * sizeof *m.vertices);
        for (int v = 0; v < m.vertex_count; v++) {
            vec3 p = vec3_sub(bunny->vertices[v], c); /* turned: x, z negated */
            m.vertices[v] = (vec3){-p.x, p.y, K * diag - p.z};
        }
        mesh_compute_bounds(&m);
        m.tree = (kdtree){0}, m.leaf_corners = NULL;
        if (!build(&m, kdtree_default_params()))
            exit(1);
        camera cam = {.fov_deg = 60, .width = 512, .height = 512};
        fixed_job j = {&m, camera_view_of(&cam), 512, 0};
        double cumulative[4];
        for (int s = 0; s < 4; s++) {
            j.steps = s + 1;
            double ns[ROUNDS];
            for (int r = 0; r < ROUNDS; r++)
                ns[r] = 1e9 * time_batch(fixed_work, &j, 0.05) / (512.0 * 512);
            cumulative[s] = median_of(ns, ROUNDS);
        }
        for (int s = 0; s < 4; s++) /* each step's share of the whole ray */
            printf("fixed-cost,%s@%.1f,%.2f,%.4f,share_of_ray\n", steps[s], K, cumulative[s],
                   (cumulative[s] - (s ? cumulative[s - 1] : 0)) / cumulative[3]);
        free(m.vertices);
        kdtree_free(&m.tree);
        free(m.leaf_corners);
    }
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

static void crossover_meshes(const mesh *bunny)
{
    static const char *names[3] = {"brute-force", "median", "sah"};
    double sizes[32], ns[3][32];
    int count = 0;
    int n_rays = 64 * 64;
    float *reference = malloc((size_t)n_rays * sizeof *reference), *t = malloc((size_t)n_rays * sizeof *t);
    for (int n = 1;; n = 2 * n < bunny->triangle_count ? 2 * n : bunny->triangle_count) {
        mesh m = first_triangles(bunny, n);
        float_ray *rays = make_rays(&m, 1.0, 64);
        for (int method = 0; method < 3; method++) {
            bool ok = method == 0 || build(&m, forced(method == 1 ? KDTREE_MEDIAN : KDTREE_SAH));
            if (!ok)
                exit(1);
            trace_job j = {&m, rays, n_rays, false, {0}, {0, 0, 0}, method == 0 ? reference : t};
            trace_work(&j); /* the distances, and the tests counted once */
            long differ = 0;
            for (int k = 0; method > 0 && k < n_rays; k++)
                differ += !(reference[k] == t[k] || (isinf(reference[k]) && isinf(t[k])));
            double tests = (double)j.stats.triangle_tests / n_rays;
            j.t = NULL;
            ns[method][count] = ns_per_ray(&j, 0.02);
            printf("%s,%d,%.2f,%.3f,triangle_tests_per_ray\n", names[method], n,
                   ns[method][count], tests);
            printf("%s,%d,0,%ld,rays_unlike_brute_force\n", names[method], n, differ);
            kdtree_free(&m.tree);
            free(m.leaf_corners), m.leaf_corners = NULL;
        }
        free(rays);
        fflush(stdout);
        sizes[count++] = n;
        if (n == bunny->triangle_count)
            break;
    }
    free(reference), free(t);
    int all = count - 1, at64 = 6; /* sizes[6] = 64 */
    printf("crossover,triangles,0,%.1f,tree_faster_from\n",
           crossover(sizes, ns[0], ns[2], count));
    printf("speedup,bunny,0,%.1f,brute_over_sah\n", ns[0][all] / ns[2][all]);
    printf("speedup,bunny,0,%.3f,median_over_sah\n", ns[1][all] / ns[2][all]);
    printf("growth,sah,0,%.3f,all_over_64\n", ns[2][all] / ns[2][at64]);
}

typedef struct {
    const scene *s;
    const ray *rays;
    int n;
    render_stats stats;
} scene_job;

static void scene_work(void *arg)
{
    scene_job *j = arg;
    j->stats = (render_stats){0};
    for (int k = 0; k < j->n; k++) {
        hit h;
        sink += scene_intersect(j->s, j->rays[k], 0, INFINITY, &h, &j->stats);
    }
}

/* A pseudo-random number in [0, 1), from a fixed seed. */
static double uniform01(void)
{
    static bench_rng rng = {0x9E3779B97F4A7C15ULL}; /* fixed seed */
    return bench_rng_uniform01(&rng);
}

static void crossover_objects(void)
{
    enum { RAYS = 4096 };
    ray rays[RAYS];
    for (int k = 0; k < RAYS; k++) { /* from the eye into the cube [-1, 1]^2 at z = 6 */
        vec3 aim = {2 * uniform01() - 1, 2 * uniform01() - 1, 6};
        rays[k] = (ray){{0, 0, 0}, vec3_normalize(aim)};
    }
    double sizes[11], ns_list[2][11];
    for (int n = 1, count = 0; n <= 1024; n *= 2, count++)
        for (int tree = 0; tree < 2; tree++) {
            scene s;
            scene_init(&s);
            for (int k = 0; k < n; k++) { /* spheres in the cube [-1, 1]^3 around z = 6 */
                object o = {.kind = SHAPE_SPHERE};
                o.sphere.center = (vec3){2 * uniform01() - 1, 2 * uniform01() - 1,
                                         5 + 2 * uniform01()};
                o.sphere.radius = 0.5 / sqrt(n) * (0.5 + uniform01());
                if (!scene_add_object(&s, o))
                    exit(1);
            }
            s.tree_params.min_items = 1;
            s.tree_params.method = tree ? KDTREE_SAH : KDTREE_NONE;
            if (!scene_build_trees(&s))
                exit(1);
            scene_job j = {&s, rays, RAYS, {0}};
            scene_work(&j);
            double tests = (double)j.stats.sphere_tests / RAYS, ns[ROUNDS];
            for (int r = 0; r < ROUNDS; r++)
                ns[r] = 1e9 * time_batch(scene_work, &j, 0.02) / RAYS;
            sizes[count] = n;
            ns_list[tree][count] = median_of(ns, ROUNDS);
            printf("objects-%s,%d,%.2f,%.3f,sphere_tests_per_ray\n", tree ? "tree" : "list", n,
                   ns_list[tree][count], tests);
            scene_free(&s);
        }
    printf("crossover,spheres,0,%.1f,tree_faster_from\n",
           crossover(sizes, ns_list[0], ns_list[1], 11));
}

/* ---------------------------------------------------------------- 4 */

static double default_ms, default_ns; /* the defaults' point, for ratios */

static void sah_point(mesh *m, const float_ray *rays, int n, const char *what, double value,
                      kdtree_params p)
{
    double ms = build_ms(m, p);
    if (!build(m, p))
        exit(1);
    trace_job j = {m, rays, n, false, {0}, {0, 0, 0}, NULL};
    double ns = ns_per_ray(&j, 0.05);
    if (default_ms == 0)
        default_ms = ms, default_ns = ns;
    printf("sah-%s,%g,%.2f,%.3f,build_ms\n", what, value, ns, ms);
    printf("sah-%s,%g,%.2f,%.3f,build_over_default\n", what, value, ns, ms / default_ms);
    printf("sah-%s,%g,%.2f,%.3f,time_over_default\n", what, value, ns, ns / default_ns);
    printf("sah-%s,%g,%.2f,%d,nodes\n", what, value, ns, m->tree.node_count);
    printf("sah-%s,%g,%.2f,%.3f,references_per_triangle\n", what, value, ns,
           (double)m->tree.item_count / m->triangle_count);
    fflush(stdout);
}

static void sah_parameters(mesh *bunny)
{
    float_ray *rays = make_rays(bunny, 1.0, 256);
    int n = 256 * 256;
    const double costs[] = {5, 10, 15, 20, 30, 45, 60, 80, 120, 180};
    const double bonuses[] = {0, 0.1, 0.2, 0.3, 0.5, 0.8};
    const int depths[] = {12, 16, 18, 20, 22, 24, 28, 32};
    sah_point(bunny, rays, n, "defaults", 0, kdtree_default_params());
    for (size_t k = 0; k < sizeof costs / sizeof *costs; k++) {
        kdtree_params p = kdtree_default_params();
        p.traversal_cost = costs[k];
        sah_point(bunny, rays, n, "traversal-cost", costs[k], p);
    }
    for (size_t k = 0; k < sizeof bonuses / sizeof *bonuses; k++) {
        kdtree_params p = kdtree_default_params();
        p.empty_bonus = bonuses[k];
        sah_point(bunny, rays, n, "empty-bonus", bonuses[k], p);
    }
    for (size_t k = 0; k < sizeof depths / sizeof *depths; k++) {
        kdtree_params p = kdtree_default_params();
        p.max_depth = depths[k];
        sah_point(bunny, rays, n, "max-depth", depths[k], p);
    }
    free(rays);
}

/* ---------------------------------------------------------------- 5 */

/* A sphere of 20 4^levels triangles: an icosahedron whose triangles are
 * each cut into four, levels times, with its vertices pushed out to a bumpy
 * surface, radius 1 + 0.1 sin(5x) sin(7y) sin(6z) + a finer ripple, so
 * that the triangles are neither all alike nor evenly spread. */
static mesh bumpy_sphere(int levels)
{
    mesh m = {0};
    int faces = 20, vertices = 12;
    for (int l = 0; l < levels; l++)
        vertices += faces * 3, faces *= 4;
    m.vertices = malloc((size_t)vertices * sizeof *m.vertices);
    m.triangles = malloc((size_t)faces * sizeof *m.triangles);
    double g = (1 + sqrt(5.0)) / 2;
    const double corners[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                   {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                   {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const int ico[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int k = 0; k < 12; k++)
        m.vertices[k] = vec3_normalize((vec3){corners[k][0], corners[k][1], corners[k][2]});
    for (int f = 0; f < 20; f++)
        m.triangles[f] = (mesh_triangle){{ico[f][0], ico[f][1], ico[f][2]}};
    m.vertex_count = 12, m.triangle_count = 20;
    for (int l = 0; l < levels; l++) {
        int n = m.triangle_count;
        for (int f = 0; f < n; f++) { /* each triangle makes its own midpoints:
                                         equal sums, so equal points */
            const int *v = m.triangles[f].v;
            int mid[3];
            for (int e = 0; e < 3; e++) {
                vec3 a = m.vertices[v[e]], b = m.vertices[v[(e + 1) % 3]];
                m.vertices[m.vertex_count] = vec3_normalize(vec3_add(a, b));
                mid[e] = m.vertex_count++;
            }
            int a = v[0], b = v[1], c = v[2];
            m.triangles[f] = (mesh_triangle){{a, mid[0], mid[2]}};
            m.triangles[m.triangle_count++] = (mesh_triangle){{mid[0], b, mid[1]}};
            m.triangles[m.triangle_count++] = (mesh_triangle){{mid[2], mid[1], c}};
            m.triangles[m.triangle_count++] = (mesh_triangle){{mid[0], mid[1], mid[2]}};
        }
    }
    for (int k = 0; k < m.vertex_count; k++) {
        vec3 p = m.vertices[k];
        double r = 1 + 0.1 * sin(5 * p.x) * sin(7 * p.y) * sin(6 * p.z) +
                   0.02 * sin(40 * p.x + 3 * p.y) * sin(37 * p.z);
        m.vertices[k] = vec3_scale(p, r);
    }
    mesh_compute_bounds(&m);
    return m;
}

static void build_scaling(void)
{
    static const char *names[3] = {"build-sah", "build-sorting", "build-median"};
    static const kdtree_method methods[3] = {KDTREE_SAH, KDTREE_SAH_SORTING, KDTREE_MEDIAN};
    double per[3][6], sizes[6]; /* ns per triangle */
    for (int levels = 3; levels <= 8; levels++) {
        mesh m = bumpy_sphere(levels);
        for (int k = 0; k < 3; k++) {
            double ms = levels < 7 ? build_ms(&m, forced(methods[k]))
                                   : 1e3 * time_batch(build_work, &(build_job){&m, forced(methods[k])}, 0);
            per[k][levels - 3] = 1e6 * ms / m.triangle_count;
            printf("%s,%d,%.2f,%.3f,build_ms\n", names[k], m.triangle_count,
                   per[k][levels - 3], ms);
            fflush(stdout);
        }
        sizes[levels - 3] = m.triangle_count;
        mesh_free(&m);
    }
    /* from the smallest mesh to the largest: per triangle, and per level */
    for (int k = 0; k < 3; k++) {
        double grow = per[k][5] / per[k][0];
        printf("scaling,%s,0,%.3f,growth_per_triangle\n", names[k], grow);
        printf("scaling,%s,0,%.3f,growth_per_level\n", names[k],
               grow * log2(sizes[0]) / log2(sizes[5]));
    }
    printf("scaling,sorting-over-sah@%d,0,%.3f,ratio\n", (int)sizes[0], per[1][0] / per[0][0]);
    printf("scaling,sorting-over-sah@%d,0,%.3f,ratio\n", (int)sizes[5], per[1][5] / per[0][5]);
}

/* ---------------------------------------------------------------- 6 */

/* The render phase of bin/ch08 SCENE --threads N --stats, as it reports
 * it (wall clock, ms), the best of three, and in *load the scene phase
 * (reading the files and building the trees); 0 when the binary or the
 * scene is not there. */
static double render_ms(const char *bin, const char *scene, int threads, double *load)
{
    char n[16], command[512];
    snprintf(n, sizeof n, "%d", threads);
    snprintf(command, sizeof command, "%s %s --threads %s --stats -o /dev/null 2>&1", bin,
             scene, n);
    double best = 0;
    for (int r = 0; r < 3; r++) {
        FILE *p = popen(command, "r");
        char line[256];
        double ms = 0;
        while (p != NULL && fgets(line, sizeof line, p) != NULL) {
            const char *at = strstr(line, "render "), *scene_at = strstr(line, "scene ");
            if (strstr(line, "time") && at && scene_at)
                ms = atof(at + 7), *load = atof(scene_at + 6);
        }
        if (p == NULL || pclose(p) != 0 || ms <= 0)
            return 0;
        best = r == 0 || ms < best ? ms : best;
    }
    return best;
}

/* The chapter's figure, rendered on one core and on two: the render phase
 * only (the scene's loading and its trees are built on one core). */
static void threads(void)
{
    const char *bin = "bin/ch08", *scene = "build/tangle/ch08/scenes/ch08-bunny.scene";
    double load;
    double one = render_ms(bin, scene, 1, &load), two = render_ms(bin, scene, 2, &load);
    if (one == 0 || two == 0)
        return; /* run from the top of the repository, after make */
    printf("threads,1,%.1f,%.1f,render_ms\nthreads,2,%.1f,%.1f,render_ms\n", one, one, two, two);
    printf("threads,2,0,%.3f,speedup\n", one / two);
    printf("scene,bunny,%.1f,%.1f,load_ms\n", load, load);
    printf("scene,bunny,0,%.3f,load_over_render_on_two\n", load / two);
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

typedef struct {
    const mesh *m;
    const float_ray *rays;
    int n, next;
} fan_job;

static void fan_run(void *ctx, long reps)
{
    fan_job *j = ctx;
    render_stats stats = {0};
    double sum = 0;
    for (long r = 0; r < reps; r++) {
        mesh_ray mr = mesh_ray_of(ray_of(&j->rays[j->next]));
        j->next = (j->next + 1) % j->n;
        triangle_hit th;
        sum += mesh_nearest(j->m, &mr, 0, INFINITY, &th, &stats) >= 0 ? th.t : 0;
    }
    bench_sink += sum;
}

static double fan_tests(const mesh *m, const float_ray *rays, int n)
{
    render_stats stats = {0};
    for (int k = 0; k < n; k++) {
        mesh_ray mr = mesh_ray_of(ray_of(&rays[k]));
        triangle_hit th;
        mesh_nearest(m, &mr, 0, INFINITY, &th, &stats);
    }
    return (double)stats.triangle_tests / n;
}

static void fans(void)
{
    for (int c = 0; c < 2; c++) {
        const char *kind = c ? "coincident" : "distinct";
        size_t length;
        char *text = fan_text(c, &length);
        mesh m = {0};
        parse_error err;
        double t0 = cpu_seconds();
        if (!mesh_parse_obj(&m, text, length, kind, &err)) {
            fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col, err.message);
            exit(1);
        }
        double load = 1e3 * (cpu_seconds() - t0);
        free(text);
        mesh_compute_bounds(&m);
        t0 = cpu_seconds();
        if (!build(&m, kdtree_default_params()))
            exit(1);
        double build_time = 1e3 * (cpu_seconds() - t0);
        printf("fan,%s,0,%zu,bytes\n", kind, length);
        printf("fan,%s,0,%d,triangles\n", kind, m.triangle_count);
        printf("fan,%s,%.1f,%.1f,load_ms\n", kind, load, load);
        printf("fan,%s,%.1f,%.1f,build_ms\n", kind, build_time, build_time);
        printf("fan,%s,0,%d,nodes\n", kind, m.tree.node_count);
        printf("fan,%s,0,%.3f,references_per_triangle\n", kind,
               (double)m.tree.item_count / m.triangle_count);
        fflush(stdout);
        /* the benchmark's rays (K = 0.5) for the square [-1, 1]^2 at z = 0,
           which both fans cover; 4 x 4 rays, 2 x 2 through the coincident */
        mesh view = {.bounds = {{-1, -1, 0}, {1, 1, 0}}};
        int side = c ? 2 : FAN_SIDE, n = side * side;
        float_ray *rays = make_rays(&view, 0.5, side);
        mesh brute = m; /* the same triangles, no tree */
        brute.tree = (kdtree){0}, brute.leaf_corners = NULL;
        fan_job jobs[2] = {{&m, rays, n, 0}, {&brute, rays, n, 0}};
        bench_case cases[2] = {{"fan-tree", kind, fan_run, &jobs[0], n},
                               {"fan-brute", kind, fan_run, &jobs[1], n}};
        bench_timing t[2];
        bench_time_cases(cases, 2, t);
        bench_row("fan-tree", kind, &t[0], "%.1f", fan_tests(&m, rays, n),
                  "triangle_tests_per_ray");
        bench_row("fan-brute", kind, &t[1], "%.1f", fan_tests(&brute, rays, n),
                  "triangle_tests_per_ray");
        printf("fan,%s,0,%.1f,render_320x240_s\n", kind, 320 * 240 * t[0].median * 1e-9);
        printf("fan,%s,0,%.3f,brute_over_tree\n", kind, t[1].median / t[0].median);
        fflush(stdout);
        free(rays);
        mesh_free(&m);
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
    exact_rays(meshes, names);
    fixed_costs(&meshes[0]);
    threads();
    crossover_objects();
    sah_parameters(&meshes[0]);
    crossover_meshes(&meshes[0]);
    build_scaling();
    fans();
    for (int k = 0; k < 2; k++)
        mesh_free(&meshes[k]);
    return 0;
}
