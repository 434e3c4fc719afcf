/* main.c: the command line of the renderer (chapter 1). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "render.h"
#include "scene_file.h"

/* The scene rendered when no scene file is given. */
static const char DEFAULT_SCENE[] =
    /* <<default scene>> ch07 */
    "# Chapter 7: glass, water and a mirror over a checkered floor.\n"
        "camera fov 50 position 0 1.1 0 look_at 0.4 -0.6 6\n"
        "image 320 240\n"
        "background gradient 0.9 0.9 0.95  0.35 0.5 0.85\n"
        "ambient 0.3 0.3 0.32\n"
        "material floor diffuse 0.8 specular 0\n"
        "material glass ambient 0 diffuse 0 specular 0.8 shininess 300 "
        "transparency 1 ior 1.5\n"
        "material water ambient 0.3 diffuse 0.6 specular 0.5 shininess 120 "
        "transparency 0.85 ior 1.33\n"
        "material mirror ambient 0.02 diffuse 0.05 specular 0.5 shininess 200 "
        "reflect 0.85\n"
        "triangle a -40 -1 0  b 40 -1 0  c -40 -1 60 color 0.9 0.88 0.8 "
        "checker 0.25 0.3 0.45 tile 0.5 material floor\n"
        "triangle a 40 -1 0  b 40 -1 60  c -40 -1 60 color 0.9 0.88 0.8 "
        "checker 0.25 0.3 0.45 tile 0.5 material floor\n"
        "sphere center -1 -0.15 5.2 radius 0.85 material glass\n"
        "triangle a -1.5 -1 9.5  b 3.5 -1 7.5  c 3.5 2.3 7.5 color 0.9 0.9 0.9 "
        "material mirror\n"
        "triangle a -1.5 -1 9.5  b 3.5 2.3 7.5  c -1.5 2.3 9.5 color 0.9 0.9 0.9 "
        "material mirror\n"
        "triangle a 0.2 -0.35 4.2  b 0.2 -0.35 5.6  c 2.2 -0.35 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.35 4.2  b 2.2 -0.35 5.6  c 2.2 -0.35 4.2"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 2.2 -0.99 4.2  c 2.2 -0.99 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 2.2 -0.99 5.6  c 0.2 -0.99 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 0.2 -0.35 4.2  c 2.2 -0.35 4.2"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 2.2 -0.35 4.2  c 2.2 -0.99 4.2"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 5.6  b 2.2 -0.99 5.6  c 2.2 -0.35 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 5.6  b 2.2 -0.35 5.6  c 0.2 -0.35 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 0.2 -0.99 5.6  c 0.2 -0.35 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 0.2 -0.99 4.2  b 0.2 -0.35 5.6  c 0.2 -0.35 4.2"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 2.2 -0.99 4.2  b 2.2 -0.35 4.2  c 2.2 -0.35 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "triangle a 2.2 -0.99 4.2  b 2.2 -0.35 5.6  c 2.2 -0.99 5.6"
        " color 0.25 0.55 0.75 material water\n"
        "light point position -3 4 2 intensity 0.9 0.85 0.8\n"
        "light directional direction 1 -1.5 0.8 intensity 0.3 0.3 0.35\n"
    ;

/* <<command-line options>> ch01 */
typedef struct {
    const char *scene_path; /* NULL: the built-in scene */
    const char *output;
    int width, height;      /* 0: as the scene says */
    bool stats, help;
} options;

static void usage(FILE *out, const char *program)
{
    fprintf(
        out,
        "usage: %s [SCENE] [-o OUT.png] [--size WxH] [--stats] [--help]\n"
        "Renders SCENE (default: this chapter's built-in scene) to OUT.png\n"
        "(default: out.png) as 8-bit sRGB.\n"
        "  -o FILE      where to write the PNG\n"
        "  --size WxH   image size in pixels, overriding the scene's\n"
        "  --stats      print rays traced and time per phase on stderr\n"
        "  --help       this text\n",
        program);
    /* <<more help>> ch05 */
    fprintf(out, "\nObject transforms apply in the order written: 'transform "
                 "scale 2 1 1\nrotate z 30 translate 0 0 5' scales, then "
                 "rotates, then moves (T R S).\n");
}

static bool option_error(const char *program, const char *message,
                         const char *found)
{
    fprintf(stderr, "%s: error: %s%s%s%s\n", program, message,
            found ? ", found '" : "", found ? found : "", found ? "'" : "");
    fprintf(stderr, "Try '%s --help'.\n", program);
    return false;
}

/* <<parse a size>> ch01 */
static bool parse_size(const char *text, int *width, int *height)
{
    char *x, *end;
    long w = strtol(text, &x, 10);
    if (x == text || *x != 'x' || x[1] < '0' || x[1] > '9')
        return false;
    long h = strtol(x + 1, &end, 10);
    if (*end != '\0' || w < 1 || h < 1 || w > IMAGE_MAX_SIDE ||
        h > IMAGE_MAX_SIDE || w * h > IMAGE_MAX_PIXELS)
        return false;
    *width = (int)w;
    *height = (int)h;
    return true;
}

/* <<parse the arguments>> ch01 */
static bool parse_options(int argc, char **argv, options *opt)
{
    *opt = (options){.output = "out.png"};
    for (int k = 1; k < argc; k++) {
        const char *arg = argv[k];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            opt->help = true;
        } else if (strcmp(arg, "--stats") == 0) {
            opt->stats = true;
        } else if (strcmp(arg, "-o") == 0 || strcmp(arg, "--size") == 0) {
            if (k + 1 == argc)
                return option_error(argv[0], "this option needs a value", arg);
            const char *value = argv[++k];
            if (strcmp(arg, "-o") == 0)
                opt->output = value;
            else if (!parse_size(value, &opt->width, &opt->height))
                return option_error(
                    argv[0],
                    "--size expects WIDTHxHEIGHT within the image limits",
                    value);
        }
        else if (arg[0] == '-' && arg[1] != '\0') {
            return option_error(argv[0], "unknown option", arg);
        } else if (opt->scene_path == NULL) {
            opt->scene_path = arg;
        } else {
            return option_error(argv[0], "only one scene file can be rendered",
                                arg);
        }
    }
    return true;
}

/* <<loading the scene>> ch01 */
static void print_scene_error(const scene_error *err)
{
    if (err->line > 0)
        fprintf(stderr, "%s:%d:%d: error: %s\n", err->file, err->line, err->col,
                err->message);
    else
        fprintf(stderr, "%s: error: %s\n", err->file, err->message);
}

/* The scene file (or the built-in scene) with --size applied; on bad input
 * prints the located error and returns false. */
static bool load_scene(const options *opt, scene *s)
{
    scene_error err;
    scene_init(s);
    bool ok = opt->scene_path != NULL
                  ? scene_load(s, opt->scene_path, &err)
                  : scene_parse(s, DEFAULT_SCENE, sizeof DEFAULT_SCENE - 1,
                                "(built-in scene)", &err);
    if (!ok) {
        print_scene_error(&err);
        return false;
    }
    if (opt->width > 0) {
        s->cam.width = opt->width;
        s->cam.height = opt->height;
    }
    return true;
}

/* <<timing>> ch01 */
static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void print_stats(const render_stats *st, double load_s, double render_s,
                        double write_s)
{
    fprintf(stderr, "primary rays       %lld\n", st->primary_rays);
    /* <<print statistics>> ch02 */
    fprintf(stderr, "sphere tests       %lld\n", st->sphere_tests);
    /* <<print statistics>> += ch04 */
    fprintf(stderr, "triangle tests     %lld\n", st->triangle_tests);
    fprintf(stderr, "box tests          %lld\n", st->box_tests);
    /* <<print statistics>> += ch05 */
    fprintf(stderr, "object-space rays  %lld\n", st->object_space_rays);
    fprintf(stderr, "triangles          %lld stored, %lld instanced\n",
            st->triangles_stored, st->triangles_instanced);
    /* <<print statistics>> += ch06 */
    long long facing = st->shadow_rays + st->shadow_skipped_dark +
                       st->shadow_skipped_alone;
    fprintf(stderr, "shadow rays        %lld (%lld blocked)\n", st->shadow_rays,
            st->shadow_rays_blocked);
    fprintf(stderr,
            "  not cast         %lld light behind the surface, %lld no light "
            "to block,\n                   %lld nothing that could block\n",
            st->light_tests - facing, st->shadow_skipped_dark,
            st->shadow_skipped_alone);
    fprintf(stderr, "reflection rays    %lld\n", st->reflection_rays);
    fprintf(stderr, "  not traced       %lld at the depth limit, %lld below "
                    "the cutoff\n",
            st->reflection_skipped_depth, st->reflection_skipped_weight);
    /* <<print statistics>> += ch07 */
    fprintf(stderr, "refraction rays    %lld\n", st->refraction_rays);
    fprintf(stderr,
            "  not traced       %lld at the depth limit, %lld below the "
            "cutoff,\n                   %lld totally reflected\n",
            st->refraction_skipped_depth, st->refraction_skipped_weight,
            st->total_reflections);
    fprintf(stderr,
            "time               scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * load_s, 1e3 * render_s, 1e3 * write_s);
}

/* <<rendering in bands>> ch01 */
enum { BAND_ROWS = 8 }; /* small enough for smooth progress, large enough to
                           cost nothing */

/* "rendering: row j of h" on a terminal, once the render has taken 1 s. */
static void show_progress(double start, int rows_done, int rows)
{
    if (seconds_now() - start < 1.0 || !isatty(STDERR_FILENO))
        return;
    fprintf(stderr, "\rrendering: row %d of %d", rows_done, rows);
    if (rows_done == rows)
        fputc('\n', stderr);
}

static void render_in_bands(const scene *s, image *img, render_stats *stats)
{
    double start = seconds_now();
    for (int first = 0; first < img->height; first += BAND_ROWS) {
        int last = first + BAND_ROWS < img->height ? first + BAND_ROWS
                                                   : img->height;
        render_rows(s, img, first, last, stats);
        show_progress(start, last, img->height);
    }
}

/* <<main>> ch01 */
int main(int argc, char **argv)
{
    options opt;
    if (!parse_options(argc, argv, &opt))
        return 1;
    if (opt.help) {
        usage(stdout, argv[0]);
        return 0;
    }
    double start = seconds_now();
    scene s;
    image img = {0};
    render_stats stats = {0};
    char why[512];
    int status = 1;
    if (!load_scene(&opt, &s))
        goto done;
    if (!image_init(&img, s.cam.width, s.cam.height)) {
        fprintf(stderr, "%s: error: no memory for a %dx%d image\n", argv[0],
                s.cam.width, s.cam.height);
        goto done;
    }
    /* <<count what the scene holds>> ch05 */
    scene_count_triangles(&s, &stats.triangles_stored,
                          &stats.triangles_instanced);
    double loaded = seconds_now();
    render_in_bands(&s, &img, &stats);
    double rendered = seconds_now();
    if (!image_write_png(&img, opt.output, why, sizeof why)) {
        fprintf(stderr, "%s: error: %s\n", opt.output, why);
        goto done;
    }
    if (opt.stats)
        print_stats(&stats, loaded - start, rendered - loaded,
                    seconds_now() - rendered);
    status = 0;
done:
    image_free(&img);
    scene_free(&s);
    return status;
}
