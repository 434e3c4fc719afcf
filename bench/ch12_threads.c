/* ch12_threads.c: chapter 8's bunny scene rendered on one core and on two.
 *
 *   build/rel/bench/ch12_threads > figures/ch12-threads.csv
 *
 * Run from the top of the repository, after make: bin/ch12 renders
 * chapter 8's bunny scene with --threads 1 and 2, in turns, THREAD_ROUNDS
 * times each; the phases are read as --stats reports them (wall clock) and
 * summarised like the harness's rounds (bench/timing.h: the median and the
 * quartiles). The CSV starts with its machine line; its columns are
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns:
 *   threads,1|2,ns_per_render,ms,render_ms   threads,2,0,speedup,speedup
 *   scene,bunny,ns_per_load,ms,load_ms (reading the scene, building its
 *   trees; from both kinds of run)
 * and for a terrain of two million triangles (ch09_meshes.h, written once
 * to build/ch12-terrain.obj) drawn at 512 x 512, the whole run, from the
 * start of the process to its end, timed by the wall clock, WHOLE_ROUNDS
 * times each:
 *   whole,1|2,ns_per_run,ms,run_ms   whole,2,0,speedup,speedup
 *   terrain,1|2,ns_per_load,ms,load_ms (its reading and its trees)
 *   terrain-render,1|2,ns_per_render,ms,render_ms
 *   terrain-build,1|2,ns_per_build,ms,build_ms (its trees, as --stats says)
 *   terrain-read,1|2,ns_per_read,ms,read_ms (the loading but the trees)
 * the parts of a run that stay on one thread, as --stats times them (its
 * "one-thread time" line and the PNG's writing), and the rest of the
 * whole run that no phase holds (the process's start and end):
 *   terrain-file|terrain-arrays|terrain-gaps|terrain-collapse|
 *   terrain-write|terrain-rest,1|2,ns,ms,ms
 *   terrain-serial,1|2,ns,ms,ms (their sum, run by run)
 * the share of the whole run on one core that they take, and the time on
 * two cores that Amdahl's law gives for that share:
 *   serial,measured,0,percent,percent   amdahl,2,ns,ms,predicted_ms
 * and Karp and Flatt's experimentally determined serial fraction of the
 * whole run and of each phase, from the medians on one core and on two
 * (2 t2 / t1 - 1, in per cent):
 *   karp-flatt,whole|terrain|terrain-read|terrain-build|terrain-render,0,
 *   percent,percent */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ch09_meshes.h"
#include "timing.h"

enum { THREAD_ROUNDS = 7, WHOLE_ROUNDS = 5, TERRAIN_SIDE = 1000 };

/* What one run of bin --stats reports, in ms of the wall clock: its
 * phases, the trees' build in the scene's, and the steps on one thread. */
typedef struct {
    double render, load, build, write;
    double file, arrays, gaps, collapse; /* "one-thread time" */
} run_report;

/* Runs bin SCENE --threads N --stats once, into *r; false when the binary
 * or the scene is not there, or it fails. */
static bool run_renderer(const char *bin, const char *scene, int threads, run_report *r)
{
    char command[512];
    snprintf(command, sizeof command, "%s %s --threads %d --stats -o /dev/null 2>&1", bin,
             scene, threads);
    FILE *p = popen(command, "r");
    char line[256];
    *r = (run_report){0};
    while (p != NULL && fgets(line, sizeof line, p) != NULL) {
        if (strncmp(line, "trees built in ", 15) == 0)
            r->build = atof(line + 15);
        const char *at = strstr(line, "render "), *scene_at = strstr(line, "scene ");
        const char *write_at = strstr(line, "write ");
        if (strncmp(line, "time ", 5) == 0 && at && scene_at && write_at) /* the wall clock's */
            r->render = atof(at + 7), r->load = atof(scene_at + 6), r->write = atof(write_at + 6);
        if (strncmp(line, "one-thread time ", 16) == 0)
            sscanf(strstr(line, "file read"), "file read %lf ms, arrays %lf ms, gaps %lf ms, "
                   "collapse %lf ms", &r->file, &r->arrays, &r->gaps, &r->collapse);
    }
    return p != NULL && pclose(p) == 0 && r->render > 0;
}

/* The bunny scene, rendered on one core and on two in turns: the render
 * phase only (the scene's loading and its trees are built on one core),
 * summarised over THREAD_ROUNDS runs of each as the harness does. */
static int threads(void)
{
    const char *bin = "bin/ch12", *scene = "build/tangle/ch12/scenes/ch08-bunny.scene";
    double render[2][THREAD_ROUNDS], load[2 * THREAD_ROUNDS];
    for (int r = 0; r < THREAD_ROUNDS; r++)
        for (int j = 0; j < 2; j++) {
            int k = (r + j) % 2; /* 1 then 2 threads, then 2 then 1 */
            run_report run;
            if (!run_renderer(bin, scene, k + 1, &run)) {
                fprintf(stderr, "ch12_threads: cannot run %s %s\n", bin, scene);
                return 1; /* run from the top of the repository, after make */
            }
            render[k][r] = 1e6 * run.render, load[2 * r + k] = 1e6 * run.load;
        }
    bench_timing t[2], loading;
    for (int k = 0; k < 2; k++) {
        bench_timing_of_samples(render[k], THREAD_ROUNDS, &t[k]);
        bench_row("threads", k ? "2" : "1", &t[k], "%.1f", t[k].median / 1e6, "render_ms");
    }
    bench_timing_of_samples(load, 2 * THREAD_ROUNDS, &loading);
    printf("threads,2,0,%.3f,speedup\n", t[0].median / t[1].median);
    bench_row("scene", "bunny", &loading, "%.1f", loading.median / 1e6, "load_ms");
    return 0;
}

/* Writes the terrain of 2 TERRAIN_SIDE^2 triangles to obj, and a scene
 * that draws it to scene; false when a file cannot be written. */
static bool write_terrain(const char *obj, const char *scene)
{
    FILE *f = fopen(obj, "w"), *g = fopen(scene, "w");
    bool ok = f != NULL && g != NULL;
    if (ok) {
        mesh m = terrain_mesh(TERRAIN_SIDE);
        for (int k = 0; k < m.vertex_count; k++)
            fprintf(f, "v %.9g %.9g %.9g\n", m.vertices[k].x, m.vertices[k].y,
                    m.vertices[k].z);
        for (int k = 0; k < m.triangle_count; k++)
            fprintf(f, "f %d %d %d\n", m.triangles[k].v[0] + 1, m.triangles[k].v[1] + 1,
                    m.triangles[k].v[2] + 1);
        mesh_free(&m);
        fprintf(g, "camera fov 60\nimage 512 512\nambient 0.2 0.2 0.2\n"
                   "mesh file %s scale 10 offset -5 -1.5 3 color 0.5 0.6 0.4\n"
                   "light directional direction 1 -1 1 intensity 0.8 0.8 0.8\n",
                strrchr(obj, '/') ? strrchr(obj, '/') + 1 : obj); /* beside */
    }
    ok = (f == NULL || fclose(f) == 0) && (g == NULL || fclose(g) == 0) && ok;
    return ok;
}

static double wall_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

/* The phases and the parts of the terrain's runs: what a round measured
 * of each, in ns, for one thread and for two. */
enum { WHOLE, LOADING, DRAWING, BUILDING, READING, FILE_READ, ARRAYS, GAPS,
       COLLAPSE, WRITING, REST, SERIAL, MEASURES };
static const struct {
    const char *method, *kind;
} MEASURE[MEASURES] = {
    {"whole", "run_ms"},          {"terrain", "load_ms"},
    {"terrain-render", "render_ms"}, {"terrain-build", "build_ms"},
    {"terrain-read", "read_ms"},  {"terrain-file", "ms"},
    {"terrain-arrays", "ms"},     {"terrain-gaps", "ms"},
    {"terrain-collapse", "ms"},   {"terrain-write", "ms"},
    {"terrain-rest", "ms"},       {"terrain-serial", "ms"}};

/* One round's measures of a run that took whole ms and reported r. */
static void measures_of(double whole, const run_report *r, double *m)
{
    m[WHOLE] = whole, m[LOADING] = r->load, m[DRAWING] = r->render;
    m[BUILDING] = r->build, m[READING] = r->load - r->build;
    m[FILE_READ] = r->file, m[ARRAYS] = r->arrays, m[GAPS] = r->gaps;
    m[COLLAPSE] = r->collapse, m[WRITING] = r->write;
    m[REST] = whole - (r->load + r->render + r->write); /* start and end */
    m[SERIAL] = r->file + r->arrays + r->gaps + r->collapse + r->write + m[REST];
    for (int k = 0; k < MEASURES; k++)
        m[k] *= 1e6; /* ns */
}

/* The terrain's whole run on one core and on two, in turns. */
static int whole_runs(void)
{
    const char *bin = "bin/ch12", *obj = "build/ch12-terrain.obj";
    const char *scene = "build/ch12-terrain.scene";
    if (!write_terrain(obj, scene)) {
        fprintf(stderr, "ch12_threads: cannot write %s and %s\n", obj, scene);
        return 1;
    }
    static double sample[2][MEASURES][WHOLE_ROUNDS];
    for (int r = 0; r < WHOLE_ROUNDS; r++)
        for (int j = 0; j < 2; j++) {
            int k = (r + j) % 2;
            double start = wall_ms(), m[MEASURES];
            run_report run;
            if (!run_renderer(bin, scene, k + 1, &run)) {
                fprintf(stderr, "ch12_threads: cannot run %s %s\n", bin, scene);
                return 1;
            }
            measures_of(wall_ms() - start, &run, m);
            for (int q = 0; q < MEASURES; q++)
                sample[k][q][r] = m[q];
        }
    bench_timing t[2][MEASURES];
    for (int k = 0; k < 2; k++)
        for (int q = 0; q < MEASURES; q++) {
            bench_timing_of_samples(sample[k][q], WHOLE_ROUNDS, &t[k][q]);
            bench_row(MEASURE[q].method, k ? "2" : "1", &t[k][q], "%.1f",
                      t[k][q].median / 1e6, MEASURE[q].kind);
        }
    printf("whole,2,0,%.3f,speedup\n", t[0][WHOLE].median / t[1][WHOLE].median);
    /* the parts on one thread, as a share of the run on one core, and
     * Amdahl's law for that share: t2 = t1 (s + (1 - s) / 2) */
    double s = t[0][SERIAL].median / t[0][WHOLE].median;
    printf("serial,measured,0,%.1f,percent\n", 100 * s);
    printf("amdahl,2,%.3f,%.1f,predicted_ms\n", t[0][WHOLE].median * (s + (1 - s) / 2),
           t[0][WHOLE].median * (s + (1 - s) / 2) / 1e6);
    /* Karp and Flatt: the serial fraction that the speed-up on two gives */
    const int phase[] = {WHOLE, LOADING, READING, BUILDING, DRAWING};
    const char *name[] = {"whole", "terrain", "terrain-read", "terrain-build",
                          "terrain-render"};
    for (int k = 0; k < 5; k++)
        printf("karp-flatt,%s,0,%.1f,percent\n", name[k],
               100 * (2 * t[1][phase[k]].median / t[0][phase[k]].median - 1));
    remove(obj), remove(scene);
    return 0;
}

int main(void)
{
    bench_print_machine();
    bench_csv_header();
    return threads() || whole_runs();
}
