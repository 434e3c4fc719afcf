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
#include "bench_util.h"

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
    scene_error err;
    scene_init(s);
    if (!scene_parse(s, SCENE, sizeof SCENE - 1, "penumbra", &err)) {
        fprintf(stderr, "%s:%d:%d: %s\n", err.file, err.line, err.col, err.message);
        exit(1);
    }
}

static void render_with(scene *s, image *img, enum sample_pattern pattern, int n)
{
    s->lights[0].pattern = pattern;
    s->lights[0].samples = n;
    render_stats stats = {0};
    render(s, img, &stats);
}

/* Time per pixel of one render: one small function, for the harness. */
static double time_render(scene *s, image *img, enum sample_pattern pattern, int n)
{
    enum { BATCHES = 5 };
    double batch[BATCHES];
    for (int b = 0; b < BATCHES; b++) {
        double t0 = now_ns();
        render_with(s, img, pattern, n);
        batch[b] = (now_ns() - t0) / ((double)img->width * img->height);
    }
    return median(batch, BATCHES);
}

static double rms(const image *a, const image *b)
{
    double sum = 0;
    size_t n = (size_t)a->width * a->height;
    for (size_t k = 0; k < n; k++) {
        vec3 d = vec3_sub(a->pixels[k], b->pixels[k]);
        sum += vec3_dot(d, d);
    }
    return sqrt(sum / (3.0 * n));
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
    printf("method,param,ns_per_op,error,error_kind\n");
    printf("reference,16384,0,%.3g,rms_error\n", rms(&ref, &other) / sqrt(2));
    const char *names[] = {"uniform", "stratified", "grid"};
    const enum sample_pattern patterns[] = {SAMPLE_UNIFORM, SAMPLE_STRATIFIED, SAMPLE_GRID};
    for (int p = 0; p < 3; p++)
        for (int n = 1; n <= 256; n *= 2) {
            double ns = time_render(&s, &img, patterns[p], n);
            printf("%s,%d,%.1f,%.6f,rms_error\n", names[p], n, ns, rms(&img, &ref));
            fflush(stdout);
        }
    image_free(&ref), image_free(&other), image_free(&img);
    scene_free(&s);
    return 0;
}
