/* ch11_threads.c: chapter 8's bunny scene rendered on one core and on two.
 *
 *   build/rel/bench/ch11_threads > figures/ch11-threads.csv
 *
 * Run from the top of the repository, after make: bin/ch11 renders
 * chapter 8's bunny scene with --threads 1 and 2, in turns, THREAD_ROUNDS
 * times each; the phases are read as --stats reports them (wall clock) and
 * summarised like the harness's rounds (bench/timing.h: the median and the
 * quartiles). The CSV starts with its machine line; its columns are
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns:
 *   threads,1|2,ns_per_render,ms,render_ms   threads,2,0,speedup,speedup
 *   scene,bunny,ns_per_load,ms,load_ms (reading the scene, building its
 *   trees; from both kinds of run)
 * and for a terrain of two million triangles (ch09_meshes.h, written once
 * to build/ch11-terrain.obj) drawn at 512 x 512, the whole run, from the
 * start of the process to its end, timed by the wall clock, WHOLE_ROUNDS
 * times each:
 *   whole,1|2,ns_per_run,ms,run_ms   whole,2,0,speedup,speedup
 *   terrain,1|2,ns_per_load,ms,load_ms (its reading and its trees)
 *   terrain-render,1|2,ns_per_render,ms,render_ms
 *   terrain-build,1|2,ns_per_build,ms,build_ms (its trees, as --stats says)
 *   terrain-read,1|2,ns_per_read,ms,read_ms (the loading but the trees)
 * and the serial share of the whole run and of each phase that Amdahl's
 * law gives for the medians on two cores (2 t2 / t1 - 1, in per cent):
 *   serial,whole|terrain|terrain-read|terrain-build|terrain-render,0,
 *   percent,percent */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ch09_meshes.h"
#include "timing.h"

enum { THREAD_ROUNDS = 7, WHOLE_ROUNDS = 5, TERRAIN_SIDE = 1000 };

/* Runs bin SCENE --threads N --stats once: the render phase and the scene
 * phase (reading the files, building the trees), and the trees' build in
 * it, as it reports them, in ms of the wall clock; false when the binary
 * or the scene is not there, or it fails. */
static bool run_renderer(const char *bin, const char *scene, int threads, double *render,
                         double *load, double *build)
{
    char command[512];
    snprintf(command, sizeof command, "%s %s --threads %d --stats -o /dev/null 2>&1", bin,
             scene, threads);
    FILE *p = popen(command, "r");
    char line[256];
    *render = 0, *load = 0, *build = 0;
    while (p != NULL && fgets(line, sizeof line, p) != NULL) {
        if (strncmp(line, "trees built in ", 15) == 0)
            *build = atof(line + 15);
        const char *at = strstr(line, "render "), *scene_at = strstr(line, "scene ");
        if (strncmp(line, "time ", 5) == 0 && at && scene_at) /* the wall clock's line */
            *render = atof(at + 7), *load = atof(scene_at + 6);
    }
    return p != NULL && pclose(p) == 0 && *render > 0;
}

/* The bunny scene, rendered on one core and on two in turns: the render
 * phase only (the scene's loading and its trees are built on one core),
 * summarised over THREAD_ROUNDS runs of each as the harness does. */
static int threads(void)
{
    const char *bin = "bin/ch11", *scene = "build/tangle/ch11/scenes/ch08-bunny.scene";
    double render[2][THREAD_ROUNDS], load[2 * THREAD_ROUNDS];
    for (int r = 0; r < THREAD_ROUNDS; r++)
        for (int j = 0; j < 2; j++) {
            int k = (r + j) % 2; /* 1 then 2 threads, then 2 then 1 */
            double ms = 0, load_ms = 0, build_ms;
            if (!run_renderer(bin, scene, k + 1, &ms, &load_ms, &build_ms)) {
                fprintf(stderr, "ch11_threads: cannot run %s %s\n", bin, scene);
                return 1; /* run from the top of the repository, after make */
            }
            render[k][r] = 1e6 * ms, load[2 * r + k] = 1e6 * load_ms;
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

/* The terrain's whole run on one core and on two, in turns. */
static int whole_runs(void)
{
    const char *bin = "bin/ch11", *obj = "build/ch11-terrain.obj";
    const char *scene = "build/ch11-terrain.scene";
    if (!write_terrain(obj, scene)) {
        fprintf(stderr, "ch11_threads: cannot write %s and %s\n", obj, scene);
        return 1;
    }
    double run[2][WHOLE_ROUNDS], load[2][WHOLE_ROUNDS], draw[2][WHOLE_ROUNDS];
    double built[2][WHOLE_ROUNDS], read[2][WHOLE_ROUNDS];
    for (int r = 0; r < WHOLE_ROUNDS; r++)
        for (int j = 0; j < 2; j++) {
            int k = (r + j) % 2;
            double render_ms, load_ms, build_ms, start = wall_ms();
            if (!run_renderer(bin, scene, k + 1, &render_ms, &load_ms, &build_ms)) {
                fprintf(stderr, "ch11_threads: cannot run %s %s\n", bin, scene);
                return 1;
            }
            run[k][r] = 1e6 * (wall_ms() - start), load[k][r] = 1e6 * load_ms;
            draw[k][r] = 1e6 * render_ms, built[k][r] = 1e6 * build_ms;
            read[k][r] = 1e6 * (load_ms - build_ms);
        }
    bench_timing t[2], loading[2], drawing[2], building[2], reading[2];
    for (int k = 0; k < 2; k++) {
        bench_timing_of_samples(run[k], WHOLE_ROUNDS, &t[k]);
        bench_timing_of_samples(load[k], WHOLE_ROUNDS, &loading[k]);
        bench_timing_of_samples(draw[k], WHOLE_ROUNDS, &drawing[k]);
        bench_timing_of_samples(built[k], WHOLE_ROUNDS, &building[k]);
        bench_timing_of_samples(read[k], WHOLE_ROUNDS, &reading[k]);
        bench_row("whole", k ? "2" : "1", &t[k], "%.1f", t[k].median / 1e6, "run_ms");
        bench_row("terrain", k ? "2" : "1", &loading[k], "%.1f",
                  loading[k].median / 1e6, "load_ms");
        bench_row("terrain-render", k ? "2" : "1", &drawing[k], "%.1f",
                  drawing[k].median / 1e6, "render_ms");
        bench_row("terrain-build", k ? "2" : "1", &building[k], "%.1f",
                  building[k].median / 1e6, "build_ms");
        bench_row("terrain-read", k ? "2" : "1", &reading[k], "%.1f",
                  reading[k].median / 1e6, "read_ms");
    }
    printf("whole,2,0,%.3f,speedup\n", t[0].median / t[1].median);
    /* Amdahl: t2 = t1 (s + (1 - s) / 2) */
    printf("serial,whole,0,%.1f,percent\n", 100 * (2 * t[1].median / t[0].median - 1));
    const char *phase[] = {"terrain", "terrain-read", "terrain-build", "terrain-render"};
    const bench_timing *of[][2] = {{&loading[0], &loading[1]},
                                   {&reading[0], &reading[1]},
                                   {&building[0], &building[1]},
                                   {&drawing[0], &drawing[1]}};
    for (int k = 0; k < 4; k++)
        printf("serial,%s,0,%.1f,percent\n", phase[k],
               100 * (2 * of[k][1]->median / of[k][0]->median - 1));
    remove(obj), remove(scene);
    return 0;
}

int main(void)
{
    bench_print_machine();
    bench_csv_header();
    return threads() || whole_runs();
}
