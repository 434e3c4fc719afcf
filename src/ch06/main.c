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
    /* <<default scene>> ch06 */
    "# Chapter 6: mirror spheres and hard shadows on a floor.\n"
        "camera fov 50\n"
        "image 320 240\n"
        "background gradient 0.85 0.85 0.9  0.3 0.45 0.8\n"
        "ambient 0.25 0.25 0.3\n"
        "material floor  ambient 0.3 diffuse 0.8 specular 0\n"
        "material mirror ambient 0.05 diffuse 0.1 specular 0.8 shininess 200 "
        "reflect 0.85\n"
        "material chrome ambient 0.05 diffuse 0.2 specular 0.6 shininess 80 "
        "reflect 0.5\n"
        "material matte  ambient 0.2 diffuse 0.8 specular 0.1\n"
        "triangle a -40 -1 0  b 40 -1 0  c -40 -1 60 color 0.8 0.78 0.72 "
        "material floor\n"
        "triangle a 40 -1 0  b 40 -1 60  c -40 -1 60 color 0.8 0.78 0.72 "
        "material floor\n"
        "sphere center -1.1 0 6.5  radius 1    color 0.9 0.9 0.9 material "
        "mirror\n"
        "sphere center 1.2 -0.3 5.6 radius 0.7 color 0.9 0.7 0.5 material "
        "chrome\n"
        "sphere center 0.2 -0.65 4.4 radius 0.35 color 0.85 0.2 0.15 material "
        "matte\n"
        "sphere center -2.2 -0.6 4.8 radius 0.4 color 0.2 0.5 0.85 material "
        "matte\n"
        "light point position -3 4 2 intensity 0.9 0.85 0.8\n"
        "light directional direction 1 -1.5 0.8 intensity 0.35 0.35 0.4\n"
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
