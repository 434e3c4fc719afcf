/* ch13_antialias.c: what each way of sampling a pixel costs, in rays and
 * in time, against how far its picture is from the truth.
 *
 *   build/rel/bench/ch13_antialias > figures/ch13-antialias.csv
 *
 * Two scenes, 128 x 96 pixels: chapter 8's twenty spheres (the built-in
 * scene of bin/ch08) and a checkered floor running to the horizon (that of
 * scenes/ch13-checker.scene), whose far checks are finer than a pixel.
 * For each: one ray through each centre; the regular grid of 2 x 2, 4 x 4
 * and 8 x 8 rays; jittered rays, 2 x 2 to 8 x 8; jittered 4 x 4 with the
 * tent filter; and the adaptive pattern at depth 3 with thresholds from
 * 0.2 to 0.01 (and 0.02 at depth 4); and the adaptive pattern at its
 * defaults (threshold 0.05, depth 3) with the two remedies for corners
 * that alias: a minimum depth (adaptive-min, PARAM the minimum depth, 1
 * or 2) and jittered corners (adaptive-jittered, PARAM the minimum depth,
 * 0 or 1). The reference is 16 x 16 jittered
 * rays a pixel, box filter. Errors: the rms difference of the 8-bit sRGB
 * codes from the reference's, over every channel of every pixel; and the
 * share of pixels with a channel more than one code away. Time: a whole
 * render (render, one thread, the adaptive pattern's corners prepared
 * each time) per pixel, the methods of a scene taking turns in 5 rounds.
 * The reference's own error is measured too, as its distance from 1,024
 * jittered rays a pixel (row SCENE-reference,256, no time); and the tent
 * against its own converged picture, 256 jittered rays through the tent
 * (row SCENE-tent-own,16, no time), since against the box's it loses by
 * construction.
 * Rows, for each scene-method and param (samples, the threshold, or the
 * minimum depth):
 *   SCENE-METHOD,PARAM,ns_per_pixel,rays_per_pixel,rays_per_pixel
 *   SCENE-METHOD,PARAM,ns_per_pixel,RMS,rms_codes
 *   SCENE-METHOD,PARAM,ns_per_pixel,SHARE,share_off
 * Columns: method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "antialias.h"
#include "render_util.h"
#include "timing.h"

#define ROUNDS 5 /* a round renders every method once: seconds */

static const char SPHERES[] =
    "camera fov 45\n"
    "image 128 96\n"
    "background gradient 0.9 0.9 0.92  0.45 0.55 0.8\n"
    "ambient 0.3 0.3 0.3\n"
    "material default ambient 0.15 diffuse 0.7 specular 0.5 shininess 60\n"
    "material floor diffuse 0.8 specular 0\n"
    "sphere center 0 -1001 6.5 radius 1000 color 0.7 0.68 0.62 material "
    "floor\n"
    "sphere center 0.55 -0.84 6.50 radius 0.16 color 0.90 0.25 0.25\n"
    "sphere center -0.53 -0.74 6.01 radius 0.26 color 0.25 0.44 0.90\n"
    "sphere center 0.07 -0.78 7.34 radius 0.22 color 0.63 0.90 0.25\n"
    "sphere center 0.58 -0.83 5.75 radius 0.17 color 0.90 0.25 0.82\n"
    "sphere center -1.02 -0.73 6.68 radius 0.27 color 0.25 0.90 0.79\n"
    "sphere center 0.94 -0.77 7.10 radius 0.23 color 0.90 0.60 0.25\n"
    "sphere center -0.31 -0.81 5.36 radius 0.19 color 0.41 0.25 0.90\n"
    "sphere center -0.58 -0.71 7.61 radius 0.29 color 0.28 0.90 0.25\n"
    "sphere center 1.23 -0.76 6.05 radius 0.24 color 0.90 0.25 0.47\n"
    "sphere center -1.26 -0.80 5.98 radius 0.20 color 0.25 0.66 0.90\n"
    "sphere center 0.60 -0.84 7.79 radius 0.16 color 0.85 0.90 0.25\n"
    "sphere center 0.44 -0.74 5.09 radius 0.26 color 0.76 0.25 0.90\n"
    "sphere center -1.32 -0.78 7.26 radius 0.22 color 0.25 0.90 0.57\n"
    "sphere center 1.54 -0.83 6.84 radius 0.17 color 0.90 0.38 0.25\n"
    "sphere center -0.93 -0.73 5.17 radius 0.27 color 0.25 0.31 0.90\n"
    "sphere center -0.21 -0.77 8.15 radius 0.23 color 0.50 0.90 0.25\n"
    "sphere center 1.31 -0.81 5.40 radius 0.19 color 0.90 0.25 0.68\n"
    "sphere center -1.75 -0.71 6.43 radius 0.29 color 0.25 0.87 0.90\n"
    "sphere center 1.27 -0.76 7.76 radius 0.24 color 0.90 0.74 0.25\n"
    "sphere center -0.08 -0.80 4.67 radius 0.20 color 0.55 0.25 0.90\n"
    "light directional direction 1 -1.5 1.2 intensity 0.5 0.5 0.5\n"
    "light point position -3 3 2 intensity 0.8 0.8 0.8\n";

static const char CHECKER[] =
    "camera fov 60\n"
    "image 128 96\n"
    "background 0.75 0.8 0.9\n"
    "ambient 0.4 0.4 0.4\n"
    "material floor diffuse 0.6 specular 0\n"
    "triangle a -2000 -1 0.5  b 2000 -1 0.5  c 0 -1 4000 color 0.9 0.9 0.9 "
    "material floor checker 0.1 0.1 0.1 tile 1\n"
    "light directional direction 0.3 -1 0.5 intensity 0.6 0.6 0.6\n";

/* One way of sampling, as the CSV names it. */
typedef struct {
    const char *method, *param;
    pixel_sampling ps;
} way;

#define GRID(n) {.pattern = PIXEL_GRID, .side = n}
#define JITTER(n) {.pattern = PIXEL_JITTERED, .side = n}
#define ADAPTIVE(t, d) {.pattern = PIXEL_ADAPTIVE, .threshold = t, .depth = d}
/* The default adaptive pattern with a minimum depth m, its points on the
 * grid or jittered. */
#define ADAPTIVE_MIN(m, jitter)                                        \
    {.pattern = PIXEL_ADAPTIVE, .threshold = 0.05, .depth = 3,          \
     .min_depth = m, .jittered_corners = jitter}

static const way WAYS[] = {
    {"center", "1", {.pattern = PIXEL_CENTER, .side = 1}},
    {"grid", "4", GRID(2)},
    {"grid", "16", GRID(4)},
    {"grid", "64", GRID(8)},
    {"jittered", "4", JITTER(2)},
    {"jittered", "9", JITTER(3)},
    {"jittered", "16", JITTER(4)},
    {"jittered", "25", JITTER(5)},
    {"jittered", "36", JITTER(6)},
    {"jittered", "49", JITTER(7)},
    {"jittered", "64", JITTER(8)},
    {"tent", "16", {.pattern = PIXEL_JITTERED, .side = 4,
                    .filter = FILTER_TENT}},
    {"adaptive", "0.2", ADAPTIVE(0.2, 3)},
    {"adaptive", "0.1", ADAPTIVE(0.1, 3)},
    {"adaptive", "0.05", ADAPTIVE(0.05, 3)},
    {"adaptive", "0.02", ADAPTIVE(0.02, 3)},
    {"adaptive", "0.01", ADAPTIVE(0.01, 3)},
    {"adaptive-d4", "0.02", ADAPTIVE(0.02, 4)},
    {"adaptive-min", "1", ADAPTIVE_MIN(1, false)},
    {"adaptive-min", "2", ADAPTIVE_MIN(2, false)},
    {"adaptive-jittered", "0", ADAPTIVE_MIN(0, true)},
    {"adaptive-jittered", "1", ADAPTIVE_MIN(1, true)},
};
enum { WAYS_N = sizeof WAYS / sizeof WAYS[0] };

/* Renders s with ps into img (its size); the work done. */
static render_stats render_way(scene *s, pixel_sampling ps, image *img)
{
    s->pixels = ps;
    render_stats st = {0};
    render(s, img, &st);
    return st;
}

typedef struct {
    scene *s;
    image *img;
    pixel_sampling ps;
} way_case;

/* reps pixels: whole renders of the image. */
static void run_way(void *ctx, long reps)
{
    way_case *c = ctx;
    long pixels = (long)c->img->width * c->img->height;
    for (long done = 0; done < reps; done += pixels) {
        render_way(c->s, c->ps, c->img);
        bench_sink += c->img->pixels[0].x;
    }
}

/* The rms of the 8-bit code differences, and the share of pixels with a
 * channel more than one code off. */
static void code_errors(const image *a, const image *ref, double *rms,
                        double *share)
{
    double sum = 0;
    long off = 0;
    size_t n = (size_t)a->width * a->height;
    for (size_t k = 0; k < n; k++) {
        vec3 p = a->pixels[k], q = ref->pixels[k];
        int d[3] = {srgb_to_byte(p.x) - srgb_to_byte(q.x),
                    srgb_to_byte(p.y) - srgb_to_byte(q.y),
                    srgb_to_byte(p.z) - srgb_to_byte(q.z)};
        sum += d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        off += abs(d[0]) > 1 || abs(d[1]) > 1 || abs(d[2]) > 1;
    }
    *rms = sqrt(sum / (3.0 * n));
    *share = (double)off / n;
}

/* The errors of img against ref, as untimed rows METHOD,PARAM. */
static void untimed_rows(const char *method, const char *param,
                         const image *img, const image *ref)
{
    bench_timing none = {0};
    double rms, share;
    code_errors(img, ref, &rms, &share);
    bench_row(method, param, &none, "%.3f", rms, "rms_codes");
    bench_row(method, param, &none, "%.4f", share, "share_off");
}

/* A converged picture of s: side x side jittered rays, through filter. */
static void converged(scene *s, int side, pixel_filter filter, image *img)
{
    if (!image_init(img, s->cam.width, s->cam.height))
        abort();
    render_way(s,
               (pixel_sampling){.pattern = PIXEL_JITTERED, .side = side,
                                .filter = filter},
               img);
}

/* How far the reference is from a finer one, and the tent from its own
 * converged picture. */
static void reference_rows(scene *s, const char *name, const image *ref)
{
    char method[48];
    image finer, tent_ref, tent;
    converged(s, 32, FILTER_BOX, &finer);
    snprintf(method, sizeof method, "%s-reference", name);
    untimed_rows(method, "256", ref, &finer);
    converged(s, 16, FILTER_TENT, &tent_ref);
    converged(s, 4, FILTER_TENT, &tent);
    snprintf(method, sizeof method, "%s-tent-own", name);
    untimed_rows(method, "16", &tent, &tent_ref);
    image_free(&finer), image_free(&tent_ref), image_free(&tent);
}

static void bench_scene(const char *name, const char *text)
{
    scene s;
    bench_load_scene(&s, text, strlen(text), name);
    image ref, img[WAYS_N];
    converged(&s, 16, FILTER_BOX, &ref);
    long pixels = (long)s.cam.width * s.cam.height;
    way_case ctx[WAYS_N];
    bench_case cases[WAYS_N];
    bench_timing t[WAYS_N];
    char methods[WAYS_N][48];
    for (int k = 0; k < WAYS_N; k++) {
        if (!image_init(&img[k], s.cam.width, s.cam.height))
            abort();
        snprintf(methods[k], sizeof methods[k], "%s-%s", name,
                 WAYS[k].method);
        ctx[k] = (way_case){&s, &img[k], WAYS[k].ps};
        cases[k] = (bench_case){methods[k], WAYS[k].param, run_way,
                                &ctx[k], pixels};
    }
    bench_time_cases_rounds(cases, WAYS_N, ROUNDS, t);
    for (int k = 0; k < WAYS_N; k++) {
        render_stats st = render_way(&s, WAYS[k].ps, &img[k]);
        double rms, share;
        code_errors(&img[k], &ref, &rms, &share);
        bench_row(methods[k], WAYS[k].param, &t[k], "%.3f",
                  (double)st.primary_rays / pixels, "rays_per_pixel");
        bench_row(methods[k], WAYS[k].param, &t[k], "%.3f", rms,
                  "rms_codes");
        bench_row(methods[k], WAYS[k].param, &t[k], "%.4f", share,
                  "share_off");
        image_free(&img[k]);
    }
    reference_rows(&s, name, &ref);
    fflush(stdout);
    image_free(&ref);
    scene_free(&s);
}

int main(void)
{
    bench_print_machine();
    bench_csv_header();
    bench_scene("spheres", SPHERES);
    bench_scene("checker", CHECKER);
    return 0;
}
