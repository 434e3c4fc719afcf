/* ch06_penumbra.c: how close does a soft shadow get to the truth for the
 * time it costs, with N shadow rays per point and light spread by each of
 * three patterns?
 *
 *   build/rel/bench/ch06_penumbra > figures/ch06-penumbra.csv
 *
 * The scene: a floor, a sphere and a disc light above and beside it, seen
 * so that the sphere's umbra and penumbra fill most of a 96 x 72 image. For
 * each pattern (uniform, stratified, grid) and N = 1, 2, 4, ..., 256, the
 * program renders the image (render_rows, as bin/ch06 does) and the error
 * is the root mean square, over every pixel and channel, of the difference
 * from a reference rendered with 16,384 stratified samples (whose own rms
 * error, estimated from two references with different seeds, is printed
 * as the row reference,16384). Seeds are fixed: every run gives the same
 * errors. Rows:
 *   PATTERN,N,ns_per_pixel,rms,rms_error
 * Columns: method,param,ns_per_op,error,error_kind. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "render_util.h"
#include "timing.h"

static const char SCENE[] =
    "image 96 72\n"
    "camera fov 40\n"
    "ambient 0.1 0.1 0.1\n"
    "material floor ambient 0.3 diffuse 0.85 specular 0\n"
    "triangle a -40 -1 0  b 40 -1 0  c -40 -1 60 material floor\n"
    "triangle a 40 -1 0  b 40 -1 60  c -40 -1 60 material floor\n"
    "sphere center 0 -0.4 5 radius 0.5\n"
    "light area position 0.8 2 5.2 direction 0 -1 0 radius 0.8 intensity 1 1 1\n";

static void load(scene *s)
{
    bench_load_scene(s, SCENE, sizeof SCENE - 1, "penumbra");
}

static void render_with(scene *s, image *img, enum sample_pattern pattern, int n)
{
    s->lights[0].pattern = pattern;
    s->lights[0].samples = n;
    render_stats stats = {0};
    render(s, img, &stats);
}

/* One timed case: a sampling pattern and a number of samples. */
typedef struct {
    scene *s;
    image *img;
    enum sample_pattern pattern;
    int n;
} penumbra_case;

/* reps pixels: whole renders of the image. */
static void run_penumbra_case(void *ctx, long reps)
{
    penumbra_case *c = ctx;
    long pixels = (long)c->img->width * c->img->height;
    for (long done = 0; done < reps; done += pixels) {
        render_with(c->s, c->img, c->pattern, c->n);
        bench_sink += c->img->pixels[0].x;
    }
}

int main(void)
{
    scene s;
    load(&s);
    image ref, other, img;
    if (!image_init(&ref, s.cam.width, s.cam.height) ||
        !image_init(&other, s.cam.width, s.cam.height) ||
        !image_init(&img, s.cam.width, s.cam.height))
        abort();
    render_with(&s, &ref, SAMPLE_STRATIFIED, 16384);
    /* the same reference from other seeds: the light moved by nothing but
     * its bits, which seed every point's stream */
    s.lights[0].position.x = nextafter(s.lights[0].position.x, 1);
    render_with(&s, &other, SAMPLE_STRATIFIED, 16384);
    s.lights[0].position.x = nextafter(s.lights[0].position.x, 0);
    bench_print_machine();
    bench_csv_header();
    bench_row("reference", "16384", NULL, "%.3g", image_rms(&ref, &other) / sqrt(2),
              "rms_error");
    const char *names[] = {"uniform", "stratified", "grid"};
    const enum sample_pattern patterns[] = {SAMPLE_UNIFORM, SAMPLE_STRATIFIED, SAMPLE_GRID};
    long pixels = (long)img.width * img.height;
    for (int n = 1; n <= 256; n *= 2) {
        penumbra_case ctx[3];
        bench_case cases[3];
        bench_timing timing[3];
        char param[16];
        snprintf(param, sizeof param, "%d", n);
        for (int p = 0; p < 3; p++) {
            ctx[p] = (penumbra_case){&s, &img, patterns[p], n};
            cases[p] = (bench_case){names[p], param, run_penumbra_case, &ctx[p], pixels};
        }
        bench_time_cases(cases, 3, timing); /* the patterns take turns */
        for (int p = 0; p < 3; p++) {
            render_with(&s, &img, patterns[p], n);
            bench_row(names[p], param, &timing[p], "%.6f", image_rms(&img, &ref), "rms_error");
        }
        fflush(stdout);
    }
    image_free(&ref), image_free(&other), image_free(&img);
    scene_free(&s);
    return 0;
}
