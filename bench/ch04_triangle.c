/* ch04_triangle.c: do rays leak through the shared edges of a closed mesh?
 * And what does brute force cost as meshes grow?
 *
 *   build/rel/bench/ch04_triangle [meshes/bunny.obj] > figures/ch04-triangle.csv
 *
 * Leaks. The closed mesh is an icosahedron subdivided twice (320 triangles,
 * 162 vertices, 480 edges) on the unit sphere. Rays are aimed exactly at
 * points of its edges (at 1/8, 2/8, ..., 7/8 of each edge) and at its
 * vertices, from 4 origins each, 3 to 5 units away in directions within 60
 * degrees of the outward normal. Such a ray enters the closed surface there,
 * so it must hit one of the triangles that touch its target (the two that
 * share the edge, or the five or six around the vertex); one that hits none
 * of them has leaked through a crack. Each method is run in double and float, with the mesh at the
 * origin and translated by (1e4, 1e4, 1e4) (origins moving with it). Rows:
 *   METHOD-PRECISION,origin|1e4,ns_per_test,leak rate,leak_rate
 * where ns_per_test is the time of one ray-triangle test (every fourth ray
 * against every triangle, mesh at the origin), the six methods timed in the
 * same interleaved rounds (bench/timing.h).
 *
 * Brute force. The first N triangles of the Stanford bunny (N from 100 to
 * all 69,451), tested by mesh_intersect against 64 rays aimed into its box,
 * the seven N timed in the same interleaved rounds:
 *   brute-force,N,ns_per_ray,triangles tested per ray,tests_per_ray
 * CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "obj.h"
#include "../tests/rng.h"
#include "timing.h"

#if defined(YOURS_SHEET) || defined(YOURS_MOLLER_TRUMBORE) || defined(YOURS_WATERTIGHT)
/* make chart-ch04 WORKBOOK=1 defines YOURS_NAME for each method the reader
 * has started (exercises 4.1-4.4): their functions, renamed yours_... in
 * copies of the workbook's objects, are measured and timed in the same
 * rounds as the book's six, as "yours-NAME". */
#define YOURS_METHODS
#define Y(name) \
    bool yours_triangle_hit_##name(vec3, vec3, vec3, ray, double, double, triangle_hit *); \
    bool yours_triangle_hit_##name##_float(vec3, vec3, vec3, ray, double, double, triangle_hit *);
Y(sheet) Y(moller_trumbore) Y(watertight)
#undef Y
#define Y(name, label) {"yours-" label, "double", yours_triangle_hit_##name}, \
                       {"yours-" label, "float", yours_triangle_hit_##name##_float},
static const triangle_method_entry yours[] = {
#ifdef YOURS_SHEET
    Y(sheet, "sheet")
#endif
#ifdef YOURS_MOLLER_TRUMBORE
    Y(moller_trumbore, "moller-trumbore")
#endif
#ifdef YOURS_WATERTIGHT
    Y(watertight, "watertight")
#endif
};
#undef Y
#define N_METHODS (TRIANGLE_METHOD_COUNT + (int)(sizeof yours / sizeof yours[0]))
static triangle_method_entry methods[N_METHODS]; /* the book's six, then yours */
#else
/* The six methods as chapter 4 lists them: name, precision, function. */
#define methods TRIANGLE_METHODS
#define N_METHODS TRIANGLE_METHOD_COUNT
#endif

/* ---------------------------------------------------------------- the closed mesh */

#define MAX_VERTICES 200
#define MAX_FACES 400

static vec3 vertices[MAX_VERTICES];
static int faces[MAX_FACES][3];
static int n_vertices, n_faces;

/* The vertex halfway between a and b, pushed out to the unit sphere; each
 * edge's midpoint is made once so that neighbours share it. */
static int midpoint(int a, int b, int cache[MAX_VERTICES][MAX_VERTICES])
{
    if (cache[a][b] >= 0)
        return cache[a][b];
    vertices[n_vertices] = vec3_normalize(vec3_scale(vec3_add(vertices[a], vertices[b]), 0.5));
    cache[a][b] = cache[b][a] = n_vertices;
    return n_vertices++;
}

static void subdivide(void)
{
    static int cache[MAX_VERTICES][MAX_VERTICES];
    static int next[MAX_FACES][3];
    memset(cache, -1, sizeof cache);
    int n = 0;
    for (int f = 0; f < n_faces; f++) {
        int a = faces[f][0], b = faces[f][1], c = faces[f][2];
        int ab = midpoint(a, b, cache), bc = midpoint(b, c, cache), ca = midpoint(c, a, cache);
        int quads[4][3] = {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}};
        memcpy(next[n], quads, sizeof quads);
        n += 4;
    }
    memcpy(faces, next, (size_t)n * sizeof faces[0]);
    n_faces = n;
}

static void make_icosphere(void)
{
    double g = (1 + sqrt(5.0)) / 2; /* the golden ratio: corners of an icosahedron */
    const double corners[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                   {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                   {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const int ico[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    n_vertices = 12;
    for (int k = 0; k < 12; k++)
        vertices[k] = vec3_normalize((vec3){corners[k][0], corners[k][1], corners[k][2]});
    n_faces = 20;
    memcpy(faces, ico, sizeof ico);
    subdivide();
    subdivide();
}

/* ---------------------------------------------------------------- the rays */

#define SEED 0xDA3E39CB94B95BDBULL /* fixed seed */
static rng_state rng = {SEED};

static double uniform01(void) { return rng_uniform01(&rng); }

#define MAX_RAYS 30000
static ray rays[MAX_RAYS];
static int touching[MAX_RAYS][7]; /* faces around each ray's target, -1 ended */
static int n_rays;

/* The faces that contain vertex a, and b too unless b < 0, into list[7]. */
static void faces_around(int a, int b, int list[7])
{
    int n = 0;
    for (int f = 0; f < n_faces && n < 6; f++) {
        bool has_a = faces[f][0] == a || faces[f][1] == a || faces[f][2] == a;
        bool has_b = b < 0 || faces[f][0] == b || faces[f][1] == b || faces[f][2] == b;
        if (has_a && has_b)
            list[n++] = f;
    }
    list[n] = -1;
}

/* Rays from 4 origins outside towards target, all shifted by offset. */
static void aim_at(vec3 target, vec3 offset, int a, int b)
{
    for (int k = 0; k < 4 && n_rays < MAX_RAYS; k++) {
        vec3 out = rng_near_direction(&rng, vec3_normalize(target));
        vec3 origin = vec3_add(target, vec3_scale(out, 3 + 2 * uniform01()));
        vec3 o = vec3_add(origin, offset), aim = vec3_add(target, offset);
        faces_around(a, b, touching[n_rays]);
        rays[n_rays++] = (ray){o, vec3_normalize(vec3_sub(aim, o))};
    }
}

static void make_rays(vec3 offset)
{
    n_rays = 0;
    rng.state = SEED; /* the same rays at both offsets */
    for (int f = 0; f < n_faces; f++)
        for (int e = 0; e < 3; e++) {
            int a = faces[f][e], b = faces[f][(e + 1) % 3];
            if (a > b)
                continue; /* each edge once */
            for (int s = 1; s < 8; s++)
                aim_at(vec3_add(vertices[a], vec3_scale(vec3_sub(vertices[b], vertices[a]), s / 8.0)),
                       offset, a, b);
        }
    for (int v = 0; v < n_vertices; v++)
        aim_at(vertices[v], offset, v, -1);
}

/* ---------------------------------------------------------------- measuring */

static double leak_rate(triangle_method test, vec3 offset)
{
    vec3 moved[MAX_VERTICES];
    for (int v = 0; v < n_vertices; v++)
        moved[v] = vec3_add(vertices[v], offset);
    int leaks = 0;
    for (int k = 0; k < n_rays; k++) {
        bool hit = false;
        triangle_hit th;
        for (const int *f = touching[k]; *f >= 0 && !hit; f++)
            hit = test(moved[faces[*f][0]], moved[faces[*f][1]], moved[faces[*f][2]], rays[k], 0,
                       INFINITY, &th);
        leaks += !hit;
    }
    return (double)leaks / n_rays;
}

/* ---------------------------------------------------------------- speed */

/* reps ray-triangle tests: whole passes of every fourth ray against every
 * triangle of the mesh at the origin. */
static void run_test(void *ctx, long reps)
{
    triangle_method test = *(const triangle_method *)ctx;
    long pass = (long)((n_rays + 3) / 4) * n_faces;
    for (long done = 0; done < reps; done += pass) {
        int hits = 0;
        triangle_hit th;
        for (int k = 0; k < n_rays; k += 4)
            for (int f = 0; f < n_faces; f++)
                hits += test(vertices[faces[f][0]], vertices[faces[f][1]], vertices[faces[f][2]],
                             rays[k], 0, INFINITY, &th);
        bench_sink += hits;
    }
}

static void leaks_and_speed(void)
{
    static triangle_method tests[N_METHODS];
    static char names[N_METHODS][48];
    bench_case cases[N_METHODS];
    bench_timing timing[N_METHODS];
#ifdef YOURS_METHODS
    for (int m = 0; m < N_METHODS; m++)
        methods[m] = m < TRIANGLE_METHOD_COUNT ? TRIANGLE_METHODS[m]
                                               : yours[m - TRIANGLE_METHOD_COUNT];
#endif
    make_rays((vec3){0, 0, 0});
    for (int m = 0; m < N_METHODS; m++) {
        tests[m] = methods[m].hit;
        snprintf(names[m], sizeof names[m], "%s-%s", methods[m].name, methods[m].precision);
        cases[m] = (bench_case){names[m], "origin", run_test, &tests[m],
                                (long)((n_rays + 3) / 4) * n_faces};
    }
    bench_time_cases(cases, N_METHODS, timing);
    const vec3 offsets[2] = {{0, 0, 0}, {1e4, 1e4, 1e4}};
    const char *placed[2] = {"origin", "1e4"};
    for (int o = 0; o < 2; o++) {
        make_rays(offsets[o]);
        for (int m = 0; m < N_METHODS; m++)
            bench_row(names[m], placed[o], &timing[m], "%.6f",
                      leak_rate(methods[m].hit, offsets[o]), "leak_rate");
    }
}

/* ---------------------------------------------------------------- brute force */

enum { PROBES = 64, N_COUNTS = 7 };
static ray probes[PROBES];

typedef struct {
    mesh view; /* the bunny with triangle_count cut to N */
    long long tests;
} brute_force_case;

/* reps rays against the first N triangles, whole passes over the probes. */
static void run_brute_force(void *ctx, long reps)
{
    brute_force_case *b = ctx;
    for (long done = 0; done < reps; done += PROBES) {
        hit h;
        int hits = 0;
        for (int k = 0; k < PROBES; k++)
            hits += mesh_intersect(&b->view, probes[k], 0, INFINITY, &h, &b->tests);
        bench_sink += hits;
    }
}

static void brute_force(const char *path)
{
    mesh bunny = {0};
    parse_error err;
    if (!mesh_load_obj(&bunny, path, &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col, err.message);
        exit(1);
    }
    mesh_compute_bounds(&bunny);
    vec3 centre = vec3_scale(vec3_add(bunny.bounds.lo, bunny.bounds.hi), 0.5);
    vec3 size = vec3_sub(bunny.bounds.hi, bunny.bounds.lo);
    for (int k = 0; k < PROBES; k++) { /* from the front, into the box */
        vec3 aim = {centre.x + size.x * (uniform01() - 0.5), centre.y + size.y * (uniform01() - 0.5),
                    centre.z};
        vec3 origin = {centre.x, centre.y, centre.z - 4 * size.z};
        probes[k] = (ray){origin, vec3_normalize(vec3_sub(aim, origin))};
    }
    int all = bunny.triangle_count;
    const int counts[N_COUNTS] = {100, 300, 1000, 3000, 10000, 30000, all};
    static brute_force_case runs[N_COUNTS];
    static char params[N_COUNTS][16];
    bench_case cases[N_COUNTS];
    bench_timing timing[N_COUNTS];
    for (int c = 0; c < N_COUNTS; c++) {
        runs[c].view = bunny;
        runs[c].view.triangle_count = counts[c] < all ? counts[c] : all;
        snprintf(params[c], sizeof params[c], "%d", runs[c].view.triangle_count);
        cases[c] = (bench_case){"brute-force", params[c], run_brute_force, &runs[c], PROBES};
    }
    bench_time_cases(cases, N_COUNTS, timing);
    for (int c = 0; c < N_COUNTS; c++) {
        runs[c].tests = 0;
        run_brute_force(&runs[c], PROBES); /* one pass, counted */
        bench_row("brute-force", params[c], &timing[c], "%.1f", (double)runs[c].tests / PROBES,
                  "tests_per_ray");
    }
    mesh_free(&bunny);
}

int main(int argc, char **argv)
{
    make_icosphere();
    bench_print_machine();
    bench_csv_header();
    leaks_and_speed();
    brute_force(argc > 1 ? argv[1] : "meshes/bunny.obj");
    return 0;
}
