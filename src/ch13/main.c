/* main.c: the renderer's phases in order: options, scene, output, render,
 * report (chapter 1). */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include "message.h"
#include "moment.h"
#include "options.h"
#include "output.h"
#include "progress.h"
#include "render.h"
#include "report.h"
#include "scene_file.h"

/* The scene rendered when no scene file is given. */
static const char DEFAULT_SCENE[] =
    /* <<default scene>> ch08 */
    "# Chapter 8: twenty spheres on a floor, too few to pay for a tree.\n"
        "camera fov 45\n"
        "image 320 240\n"
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
        "light point position -3 3 2 intensity 0.8 0.8 0.8\n"
    /* <<default scene>> += ch13 */
    "pixel pattern adaptive\n"
    ;

/* <<loading the scene>> ch01 */
/* The scene file (or the built-in scene) with --size applied, its phases
 * told to shown; on bad input prints the located error and returns
 * false. */
static bool load_scene(const options *opt, scene *s, progress *shown)
{
    scene_error err;
    scene_init(s);
    s->on_phase = progress_phase, s->phase_context = shown;
    /* <<what the command line tells the scene>> ch09 */
    s->accelerator_option = (mesh_accelerator)opt->accelerator;
    /* <<what the command line tells the scene>> += ch12 */
    s->bvh_settings.threads = opt->threads; /* its reading and build too */
    /* <<what the command line tells the scene>> += ch13 */
    s->pixel_option = opt->pixel;
    s->width_option = opt->width, s->height_option = opt->height;
    bool ok = opt->scene_path != NULL
                  ? scene_load(s, opt->scene_path, &err)
                  : scene_parse(s, DEFAULT_SCENE, sizeof DEFAULT_SCENE - 1,
                                "(built-in scene)", &err);
    progress_phase(shown, NULL); /* loaded or not: what follows is ours */
    s->on_phase = NULL;
    if (!ok) {
        message_print_error(err.file, err.line, err.col, err.message);
        return false;
    }
    if (opt->width > 0) {
        s->cam.width = opt->width;
        s->cam.height = opt->height;
    }
    return true;
}
/* <<loading the scene>> += ch04 */

/* "FILE: warning: ..." for the first mesh with no triangle, and how many
 * more there are: a file with no face is valid but most likely wrong. */
static void warn_of_empty_meshes(const scene *s)
{
    int empty = 0, first = -1;
    for (int k = 0; k < s->mesh_count; k++)
        if (s->meshes[k].triangle_count == 0 && empty++ == 0)
            first = k;
    if (empty == 0 || s->meshes[first].source.path == NULL)
        return;
    char more[48] = "", text[128];
    if (empty > 1)
        snprintf(more, sizeof more, " (nor %d more meshes like it)",
                 empty - 1);
    snprintf(text, sizeof text, "no face in this OBJ file: it shows "
                                "nothing%s", more);
    message_print_warning(s->meshes[first].source.path, text);
}

/* <<the output may not be an input>> ch01 */
/* Does output name the file at path, by any name? Never when output is
 * standard output or a file that does not exist yet. */
static bool output_is(const char *output, const char *path)
{
    struct stat out, in;
    return path != NULL && strcmp(output, "-") != 0 &&
           stat(output, &out) == 0 && stat(path, &in) == 0 &&
           in.st_dev == out.st_dev && in.st_ino == out.st_ino;
}

/* <<main>> ch01 */
int main(int argc, char **argv)
{
    options opt;
    if (!options_parse(argc, argv, &opt))
        return 1;
    if (opt.help) {
        options_usage(stdout, argv[0]);
        return 0;
    }
    output_catch_stop_signals();
    moment at[4] = {moment_now()};
    scene s;
    image img = {0};
    png_output out = {0};
    render_stats stats = {0};
    progress shown;
    progress_begin(&shown);
    render_settings how = {.progress = progress_show,
                           .progress_context = &shown};
    char why[PARSE_MAX_NAME + 256], size[80];
    int status = 1;
    if (!load_scene(&opt, &s, &shown))
        goto done;
    /* <<once the scene is loaded>> ch04 */
    warn_of_empty_meshes(&s);
    /* <<once the scene is loaded>> += ch08 */
    if (opt.stats)
        report_trees(&s);
    if (opt.stats)
        report_mesh_hints(&s);
    /* <<once the scene is loaded>> += ch09 */
    if (opt.stats)
        report_bvhs(&s);
    /* <<once the scene is loaded>> += ch12 */
    how.threads = opt.threads;
    how.progress_redrawn = shown.watching; /* below */
    if (opt.stats)
        report_loading(&s);
    const char *input =
        output_is(opt.output, opt.scene_path) ? opt.scene_path : NULL;
    /* <<other files the scene read>> ch04 */
    for (int k = 0; input == NULL && k < s.mesh_count; k++)
        if (output_is(opt.output, s.meshes[k].source.path))
            input = s.meshes[k].source.path;
    if (input != NULL) {
        snprintf(why, sizeof why, "the output is an input: %s", input);
        message_print_error(opt.output, 0, 0, why);
        goto done;
    }
    if (!output_open(opt.output, &out, why, sizeof why)) {
        message_print_error(opt.output, 0, 0, why);
        goto done;
    }
    progress_render(&shown); /* the image is made, then drawn */
    if (!image_init(&img, s.cam.width, s.cam.height) ||
        !png_output_reserve(&out, s.cam.width, s.cam.height)) {
        snprintf(size, sizeof size, "no memory for a %dx%d image and its "
                 "PNG", s.cam.width, s.cam.height);
        message_print_error(argv[0], 0, 0, size);
        goto done;
    }
    /* <<count what the scene holds>> ch05 */
    scene_count_triangles(&s, &stats.triangles_stored,
                          &stats.triangles_instanced);
    at[1] = moment_now();
    render_in_bands(&s, &img, &how, &stats);
    at[2] = moment_now();
    if (!png_output_finish(&out, &img, why, sizeof why)) {
        message_print_error(opt.output, 0, 0, why);
        goto done;
    }
    at[3] = moment_now();
    if (opt.stats)
        report_stats(&stats, at);
    status = 0;
done:
    progress_end(&shown);
    output_close(&out);
    image_free(&img);
    scene_free(&s);
    return status;
}
