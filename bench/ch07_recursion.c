/* ch07_recursion.c: a depth limit against a contribution cutoff, in the
 * tree of rays that glass makes.
 *
 *   build/rel/bench/ch07_recursion > figures/ch07-recursion.csv
 *
 * The scene: two glass balls (eta 1.5) and one of water (1.33) in front of
 * a mirror (0.85), with a mirror behind the eye too, over a checkered
 * floor; 96 x 72 pixels.
 * At every glass and water surface a ray splits in two, so without a
 * cutoff the rays per pixel grow with the depth limit as fast as the tree
 * does. The reference is the render with depth limit 100 and cutoff 1e-9;
 * the row reference-check gives its own distance from the render with
 * cutoff 1e-10, a bound on how far the reference is from the full tree.
 * Series (method,param,,error,error_kind,,,,rays_per_pixel):
 *   depth,D           depth limit D from 0 to 32, no cutoff
 *   cutoff,W          cutoff W from 0.5 down to 1e-6, depth limit 100
 *   default,64        the program's defaults, depth 64 and cutoff 0.01
 *   *-rays            the same rays per pixel in the error column, so that
 *                     the chapter's quotes can be checked
 * rms is over every pixel and channel of the linear image; rays per pixel
 * counts primary, shadow, reflection and refraction rays. Cost is counted
 * in rays, which do not depend on the machine, so nothing here is timed
 * (the time columns are empty). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render.h"
#include "scene_file.h"
#include "render_util.h"
#include "timing.h"

#define WIDTH 96
#define HEIGHT 72

static const char SCENE[] =
    "image 96 72\n"
    "camera fov 55\n"
    "background gradient 0.9 0.9 0.95  0.35 0.5 0.85\n"
    "ambient 0.3 0.3 0.32\n"
    "material floor diffuse 0.8 specular 0\n"
    "material glass ambient 0 diffuse 0 specular 0 transparency 1 ior 1.5\n"
    "material water ambient 0 diffuse 0 specular 0 transparency 1 ior 1.33\n"
    "material mirror ambient 0.02 diffuse 0.05 specular 0 reflect 0.85\n"
    "triangle a -40 -1 -5  b 40 -1 -5  c -40 -1 60 color 0.9 0.88 0.8 "
    "checker 0.25 0.3 0.45 tile 0.5 material floor\n"
    "triangle a 40 -1 -5  b 40 -1 60  c -40 -1 60 color 0.9 0.88 0.8 "
    "checker 0.25 0.3 0.45 tile 0.5 material floor\n"
    "triangle a -6 -1 8  b 6 -1 8  c 6 4 8 color 1 1 1 material mirror\n"
    "triangle a -6 -1 8  b 6 4 8  c -6 4 8 color 1 1 1 material mirror\n"
    "triangle a -6 -1 -1  b 6 4 -1  c 6 -1 -1 color 1 1 1 material mirror\n"
    "triangle a -6 -1 -1  b -6 4 -1  c 6 4 -1 color 1 1 1 material mirror\n"
    "sphere center -1 -0.2 4.5 radius 0.8 material glass\n"
    "sphere center 0.9 -0.4 5.5 radius 0.6 material glass\n"
    "sphere center 0.2 -0.7 3.6 radius 0.3 material water\n"
    "light point position -3 3 2 intensity 0.9 0.85 0.8\n";

/* Renders with the limits; returns the rays per pixel. */
static double render_with(scene *s, image *img, int depth, double cutoff)
{
    render_stats st = bench_render_with_limits(s, img, depth, cutoff);
    double rays = (double)(st.primary_rays + st.shadow_rays +
                           st.reflection_rays + st.refraction_rays);
    return rays / ((double)img->width * img->height);
}

/* Two rows: the error, and the rays per pixel; both end with the rays per
 * pixel as a ninth column (the chart plots it). */
static void row(scene *s, image *img, const image *ref, const char *name,
                double param, int depth, double cutoff)
{
    char p[32], rays_name[48];
    snprintf(p, sizeof p, "%g", param);
    snprintf(rays_name, sizeof rays_name, "%s-rays", name);
    double rays = render_with(s, img, depth, cutoff);
    printf("%s,%s,,%.6g,rms_error,,,,%.3f\n", name, p, image_rms(img, ref), rays);
    printf("%s,%s,,%.3f,rays_per_pixel,,,,%.3f\n", rays_name, p, rays, rays);
}

int main(void)
{
    scene s;
    bench_load_scene(&s, SCENE, sizeof SCENE - 1, "recursion");
    image ref, img;
    if (!image_init(&ref, WIDTH, HEIGHT) || !image_init(&img, WIDTH, HEIGHT))
        abort();
    double ref_rays = render_with(&s, &ref, 100, 1e-9);
    bench_print_machine();
    printf("method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns,"
           "rays_per_pixel\n");
    printf("reference,100,,0,rms_error,,,,%.3f\n", ref_rays);
    row(&s, &img, &ref, "reference-check", 1e-10, 100, 1e-10);
    const int depths[] = {0, 1, 2, 3, 4, 6, 8, 11, 16, 23, 32};
    for (int k = 0; k < (int)(sizeof depths / sizeof depths[0]); k++)
        row(&s, &img, &ref, "depth", depths[k], depths[k], 0);
    const double cutoffs[] = {0.5,   0.3,   0.2,   0.1,  0.05, 0.03,
                              0.02,  0.01,  0.005, 0.003, 0.002, 0.001,
                              3e-4, 1e-4,  1e-5,  1e-6};
    for (int k = 0; k < (int)(sizeof cutoffs / sizeof cutoffs[0]); k++)
        row(&s, &img, &ref, "cutoff", cutoffs[k], 100, cutoffs[k]);
    row(&s, &img, &ref, "default", 64, 64, 0.01); /* the program's */
    image_free(&ref), image_free(&img);
    scene_free(&s);
    return 0;
}
