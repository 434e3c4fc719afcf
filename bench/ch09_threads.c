/* ch09_threads.c: chapter 8's bunny scene rendered on one core and on two.
 *
 *   build/rel/bench/ch09_threads > figures/ch09-threads.csv
 *
 * Run from the top of the repository, after make: bin/ch09 renders
 * chapter 8's bunny scene with --threads 1 and 2, in turns, THREAD_ROUNDS
 * times each; the phases are read as --stats reports them (wall clock) and
 * summarised like the harness's rounds (bench/timing.h: the median and the
 * quartiles). The CSV starts with its machine line; its columns are
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns:
 *   threads,1|2,ns_per_render,ms,render_ms   threads,2,0,speedup,speedup
 *   scene,bunny,ns_per_load,ms,load_ms (reading the scene, building its
 *   trees; from both kinds of run) */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "timing.h"

enum { THREAD_ROUNDS = 7 };

/* Runs bin SCENE --threads N --stats once: the render phase and the scene
 * phase (reading the files, building the trees) as it reports them, in ms
 * of the wall clock; false when the binary or the scene is not there, or
 * it fails. */
static bool run_renderer(const char *bin, const char *scene, int threads, double *render,
                         double *load)
{
    char command[512];
    snprintf(command, sizeof command, "%s %s --threads %d --stats -o /dev/null 2>&1", bin,
             scene, threads);
    FILE *p = popen(command, "r");
    char line[256];
    *render = 0, *load = 0;
    while (p != NULL && fgets(line, sizeof line, p) != NULL) {
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
    const char *bin = "bin/ch09", *scene = "build/tangle/ch09/scenes/ch08-bunny.scene";
    double render[2][THREAD_ROUNDS], load[2 * THREAD_ROUNDS];
    for (int r = 0; r < THREAD_ROUNDS; r++)
        for (int j = 0; j < 2; j++) {
            int k = (r + j) % 2; /* 1 then 2 threads, then 2 then 1 */
            double ms = 0, load_ms = 0;
            if (!run_renderer(bin, scene, k + 1, &ms, &load_ms)) {
                fprintf(stderr, "ch09_threads: cannot run %s %s\n", bin, scene);
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

int main(void)
{
    bench_print_machine();
    bench_csv_header();
    return threads();
}
