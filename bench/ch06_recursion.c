/* ch06_recursion.c: a depth limit against a contribution cutoff, between
 * two facing mirrors.
 *
 *   build/rel/bench/ch06_recursion > figures/ch06-recursion.csv
 *
 * The scene: two facing mirrors, one ahead of the eye and one behind it
 * (reflectivity 0.9, but 0.5 on the right half of the one ahead), a matte
 * floor, a chrome sphere (0.4) and a matte one; 96 x 72 pixels. The reference is the same render with depth limit 100
 * and no cutoff (0.9^100 < 3e-5 of a pixel is left out). Two series:
 *   depth,D,ns_per_pixel,rms,rms_error,rays_per_pixel
 *     depth limit D from 0 to 64, no cutoff;
 *   cutoff,W,ns_per_pixel,rms,rms_error,rays_per_pixel
 *     cutoff W from 0.5 down to 1e-4, depth limit 100.
 *   depth-rays,D,... and cutoff-rays,W,...: the same rays per pixel in the
 *     error column, so that the chapter's quotes can be checked.
 * rms is over every pixel and channel of the linear image; rays per pixel
 * counts primary, shadow and reflection rays. Columns:
 * method,param,ns_per_op,error,error_kind, and rays_per_pixel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render.h"
#include "scene_file.h"
#include "render_util.h"
#include "timing.h"

static const char SCENE[] =
    "image 96 72\n"
    "camera fov 60\n"
    "ambient 0.2 0.2 0.2\n"
    "background 0.3 0.4 0.6\n"
    "material mirror ambient 0.02 diffuse 0.1 specular 0 reflect 0.9\n"
    "material dim ambient 0.1 diffuse 0.4 specular 0 reflect 0.5\n"
    "material chrome ambient 0.05 diffuse 0.3 specular 0.5 shininess 60 reflect 0.4\n"
    "material matte ambient 0.2 diffuse 0.8 specular 0\n"
    "triangle a -30 -1 6  b 0 -1 6  c 0 30 6 color 0.8 0.9 0.8 material mirror\n"
    "triangle a -30 -1 6  b 0 30 6  c -30 30 6 color 0.8 0.9 0.8 material mirror\n"
    "triangle a 0 -1 6  b 30 -1 6  c 30 30 6 color 0.9 0.8 0.7 material dim\n"
    "triangle a 0 -1 6  b 30 30 6  c 0 30 6 color 0.9 0.8 0.7 material dim\n"
    "triangle a -30 -1 -1  b 30 30 -1  c 30 -1 -1 color 0.8 0.9 0.8 material mirror\n"
    "triangle a -30 -1 -1  b -30 30 -1  c 30 30 -1 color 0.8 0.9 0.8 material mirror\n"
    "triangle a -30 -1 -1  b 30 -1 -1  c 30 -1 6 color 0.8 0.75 0.7 material matte\n"
    "triangle a -30 -1 -1  b 30 -1 6  c -30 -1 6 color 0.8 0.75 0.7 material matte\n"
    "sphere center -0.8 -0.4 3.5 radius 0.6 color 0.9 0.9 0.9 material chrome\n"
    "sphere center 0.9 -0.6 4 radius 0.4 color 0.9 0.3 0.2 material matte\n"
    "light point position 0 3 2 intensity 1 1 1\n";

/* Renders with the limits; returns the rays per pixel. */
static double render_with(scene *s, image *img, int depth, double cutoff)
{
    render_stats st = bench_render_with_limits(s, img, depth, cutoff);
    double rays = (double)(st.primary_rays + st.shadow_rays + st.reflection_rays);
    return rays / ((double)img->width * img->height);
}

/* One timed case: a depth limit and a cutoff. */
typedef struct {
    scene *s;
    image *img;
    int depth;
    double cutoff;
} recursion_case;

/* reps pixels: whole renders of the image. */
static void run_recursion_case(void *ctx, long reps)
{
    recursion_case *c = ctx;
    long pixels = (long)c->img->width * c->img->height;
    for (long done = 0; done < reps; done += pixels)
        bench_sink += render_with(c->s, c->img, c->depth, c->cutoff);
}

/* Two rows, the error and the rays per pixel, each ending with the rays per
 * pixel as a ninth column (the chart plots it). */
static void row(scene *s, image *img, const image *ref, const char *name, double param,
                int depth, double cutoff)
{
    char p[32], rays_name[48];
    snprintf(p, sizeof p, "%g", param);
    snprintf(rays_name, sizeof rays_name, "%s-rays", name);
    recursion_case ctx = {s, img, depth, cutoff};
    long pixels = (long)img->width * img->height;
    bench_case c = {name, p, run_recursion_case, &ctx, pixels};
    bench_timing t;
    bench_time_cases(&c, 1, &t);
    double rays = render_with(s, img, depth, cutoff);
    printf("%s,%s,%.3f,%.6f,rms_error,%.3f,%.3f,%.3f,%.3f\n", name, p, t.median,
           image_rms(img, ref), t.q1, t.q3, t.wall_median, rays);
    printf("%s,%s,%.3f,%.3f,rays_per_pixel,%.3f,%.3f,%.3f,%.3f\n", rays_name, p, t.median,
           rays, t.q1, t.q3, t.wall_median, rays);
    fflush(stdout);
}

int main(void)
{
    scene s;
    bench_load_scene(&s, SCENE, sizeof SCENE - 1, "recursion");
    image ref, img;
    if (!image_init(&ref, s.cam.width, s.cam.height) ||
        !image_init(&img, s.cam.width, s.cam.height))
        abort();
    double ref_rays = render_with(&s, &ref, 100, 0);
    bench_print_machine();
    printf("method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns,"
           "rays_per_pixel\n");
    printf("reference,100,,0,rms_error,,,,%.3f\n", ref_rays);
    const int depths[] = {0, 1, 2, 3, 4, 6, 8, 11, 16, 23, 32, 45, 64};
    for (int k = 0; k < (int)(sizeof depths / sizeof depths[0]); k++)
        row(&s, &img, &ref, "depth", depths[k], depths[k], 0);
    const double cutoffs[] = {0.5, 0.3, 0.2, 0.1, 0.05, 0.03, 0.02, 0.01, 0.005, 0.003, 0.002,
                              0.001, 3e-4, 1e-4};
    for (int k = 0; k < (int)(sizeof cutoffs / sizeof cutoffs[0]); k++)
        row(&s, &img, &ref, "cutoff", cutoffs[k], 100, cutoffs[k]);
    /* the defaults together */
    row(&s, &img, &ref, "default", 64, 64, 0.01);
    image_free(&ref), image_free(&img);
    scene_free(&s);
    return 0;
}
