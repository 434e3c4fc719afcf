/* main.c: the command line of the renderer (chapter 1). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "render.h"
#include "scene_file.h"

/* The scene rendered when no scene file is given. */
static const char DEFAULT_SCENE[] =
    /* <<default scene>> ch05 */
    "# Chapter 5: one unit sphere, stretched, turned and sheared into\n"
    "# ellipsoids by transforms, seen by a placed camera.\n"
    "camera position -1.5 2.2 0.5 look_at 0 0.45 6 up 0 1 0 fov 45\n"
    "image 320 240\n"
    "background gradient 0.85 0.85 0.9  0.3 0.45 0.8\n"
    "ambient 0.3 0.3 0.35\n"
    "material floor diffuse 0.8 specular 0\n"
    "material glaze ambient 0.15 diffuse 0.6 specular 0.6 shininess 60\n"
    "sphere center 0 -1000 6 radius 1000 color 0.75 0.75 0.7 material floor\n"
    "sphere center 0 0 0 color 0.85 0.3 0.25 material glaze transform scale "
    "1.3 0.45 0.8 rotate y 30 translate 0 0.45 6.5\n"
    "sphere center 0 0 0 color 0.3 0.7 0.4 material glaze transform scale "
    "0.35 0.8 0.35 rotate z -20 translate -1.7 0.8 6\n"
    "sphere center 0 0 0 color 0.3 0.45 0.9 material glaze transform scale "
    "0.9 0.25 0.25 rotate y -50 rotate z 25 translate 1.6 0.7 5.2\n"
    "sphere center 0 0 0 color 0.95 0.8 0.3 material glaze transform scale "
    "0.5 0.5 0.5 shear xy 0.8 0 translate 0.2 0.5 4.2\n"
    "light directional direction 1 -1.5 1.2 intensity 0.5 0.5 0.5\n"
    "light point position -3 4 2 intensity 0.9 0.85 0.8\n"
    ;

/* <<printing errors>> ch01 */
/* The length of the UTF-8 sequence at s if it encodes a printable
 * character beyond ASCII (U+00A0 and up), else 0. */
static int printable_utf8(const unsigned char *s)
{
    static const unsigned long least[] = {0, 0, 0xA0, 0x800, 0x10000};
    int n = s[0] >= 0xF0 ? 4 : s[0] >= 0xE0 ? 3 : s[0] >= 0xC2 ? 2 : 0;
    if (n == 0 || s[0] > 0xF4)
        return 0;
    unsigned long c = s[0] & (0x7Fu >> n);
    for (int k = 1; k < n; k++) {
        if ((s[k] & 0xC0) != 0x80) /* also stops at the NUL */
            return 0;
        c = c << 6 | (s[k] & 0x3Fu);
    }
    bool surrogate = c >= 0xD800 && c <= 0xDFFF;
    return c >= least[n] && c <= 0x10FFFF && !surrogate ? n : 0;
}

/* text on stderr, with every byte a terminal could obey shown as \xHH. */
static void print_escaped(const char *text)
{
    for (const unsigned char *c = (const unsigned char *)text; *c != '\0';) {
        int n = *c >= 0x20 && *c < 0x7F ? 1 : printable_utf8(c);
        if (n == 0)
            fprintf(stderr, "\\x%02x", *c++);
        else
            fwrite(c, 1, (size_t)n, stderr), c += n;
    }
}

/* "NAME: error: MESSAGE", or with ":LINE:COL" after NAME when line > 0. */
static void print_error(const char *name, int line, int col,
                        const char *message)
{
    print_escaped(name);
    if (line > 0)
        fprintf(stderr, ":%d:%d", line, col);
    fputs(": error: ", stderr);
    print_escaped(message);
    fputc('\n', stderr);
}

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
        "  -o FILE      where to write the PNG; - for standard output\n"
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
    char text[512];
    snprintf(text, sizeof text, "%s%s%.400s%s", message,
             found ? ", found '" : "", found ? found : "", found ? "'" : "");
    print_error(program, 0, 0, text);
    fputs("Try '", stderr);
    print_escaped(program);
    fputs(" --help'.\n", stderr);
    return false;
}

/* <<parse a size>> ch01 */
static bool parse_size(const char *text, int *width, int *height)
{
    char *x, *end;
    if (text[0] < '0' || text[0] > '9')
        return false; /* strtol would take blanks and a sign */
    long w = strtol(text, &x, 10);
    if (*x != 'x' || x[1] < '0' || x[1] > '9')
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
            if (strcmp(arg, "-o") == 0 && value[0] == '\0')
                return option_error(argv[0], "-o expects a file name, or - "
                                             "for standard output", NULL);
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
        print_error(err.file, err.line, err.col, err.message);
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
    print_escaped(s->meshes[first].source.path);
    fputs(": warning: no face in this OBJ file: it shows nothing", stderr);
    if (empty > 1)
        fprintf(stderr, " (nor %d more meshes like it)", empty - 1);
    fputc('\n', stderr);
}

/* <<the output file>> ch01 */
/* The output's temporary file, while there is one. */
static char temporary[PARSE_MAX_NAME + 16];
static volatile sig_atomic_t has_temporary;

static void remove_temporary_and_stop(int sig)
{
    if (has_temporary)
        unlink(temporary);
    raise(sig); /* SA_RESETHAND restored the default action: it stops */
}

static const int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};
enum { STOP_SIGNALS = sizeof stop_signals / sizeof stop_signals[0] };

static void catch_stop_signals(void)
{
    struct sigaction action = {.sa_handler = remove_temporary_and_stop,
                               .sa_flags = SA_RESETHAND},
                     before;
    sigemptyset(&action.sa_mask);
    for (int k = 0; k < STOP_SIGNALS; k++)
        if (sigaction(stop_signals[k], NULL, &before) == 0 &&
            before.sa_handler != SIG_IGN) /* nohup's choice stands */
            sigaction(stop_signals[k], &action, NULL);
}

/* png_output_open with the stop signals held, so that the handler knows
 * of a temporary file as soon as it exists. */
static bool open_output(const char *path, png_output *out, char *why,
                        size_t why_size)
{
    sigset_t stops, before;
    sigemptyset(&stops);
    for (int k = 0; k < STOP_SIGNALS; k++)
        sigaddset(&stops, stop_signals[k]);
    sigprocmask(SIG_BLOCK, &stops, &before);
    bool ok = png_output_open(out, path, why, why_size);
    if (out->temporary && strlen(out->temporary) < sizeof temporary) {
        strcpy(temporary, out->temporary);
        has_temporary = 1;
    }
    sigprocmask(SIG_SETMASK, &before, NULL);
    return ok;
}

/* Removes an unfinished temporary, then tells the handler it is gone. */
static void close_output(png_output *out)
{
    png_output_free(out);
    has_temporary = 0;
}

/* <<the output may not be an input>> ch01 */
/* Does path name the file whose status is out? */
static bool is_same_file(const char *path, const struct stat *out)
{
    struct stat in;
    return path != NULL && stat(path, &in) == 0 &&
           in.st_dev == out->st_dev && in.st_ino == out->st_ino;
}

/* The file the scene was read from that -o names too, or NULL. */
static const char *input_named_by_output(const options *opt, const scene *s)
{
    struct stat out;
    (void)s; /* its files are named from chapter 4 on */
    if (strcmp(opt->output, "-") == 0 || stat(opt->output, &out) != 0)
        return NULL; /* standard output, or a new file */
    if (is_same_file(opt->scene_path, &out))
        return opt->scene_path;
    /* <<other files the scene read>> ch04 */
    for (int k = 0; k < s->mesh_count; k++)
        if (is_same_file(s->meshes[k].source.path, &out))
            return s->meshes[k].source.path;
    return NULL;
}

/* <<timing>> ch01 */
static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The processor time this process has used, on every core, in seconds. */
static double cpu_seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One moment on both clocks; the phases are the spans between moments. */
typedef struct {
    double wall, cpu;
} moment;

static moment moment_now(void)
{
    return (moment){seconds_now(), cpu_seconds_now()};
}

/* at[0..3]: the start, and the ends of loading, rendering and writing. */
static void print_stats(const render_stats *st, const moment at[4])
{
    fprintf(stderr, "primary rays       %lld\n", st->primary_rays);
    /* <<print statistics>> ch02 */
    fprintf(stderr, "hits               %lld\n", st->hits);
    fprintf(stderr, "sphere tests       %lld\n", st->sphere_tests);
    /* <<print statistics>> += ch04 */
    fprintf(stderr, "triangle tests     %lld\n", st->triangle_tests);
    fprintf(stderr, "box tests          %lld\n", st->box_tests);
    /* <<print statistics>> += ch05 */
    fprintf(stderr, "object-space rays  %lld\n", st->object_space_rays);
    fprintf(stderr, "triangles          %lld stored, %lld instanced\n",
            st->triangles_stored, st->triangles_instanced);
    double render_s = at[2].wall - at[1].wall;
    if (render_s > 0)
        fprintf(stderr, "primary rays/s     %.3g\n",
                st->primary_rays / render_s);
    fprintf(stderr,
            "time               scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * (at[1].wall - at[0].wall), 1e3 * render_s,
            1e3 * (at[3].wall - at[2].wall));
    fprintf(stderr,
            "processor time     scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * (at[1].cpu - at[0].cpu), 1e3 * (at[2].cpu - at[1].cpu),
            1e3 * (at[3].cpu - at[2].cpu));
}

/* <<rendering in bands>> ch01 */
enum { BAND_ROWS = 8 }; /* small enough for smooth progress, large enough to
                           cost nothing */

/* "rendering: row j of h" once the render has taken 1 s: redrawn on a
 * terminal, elsewhere a line of its own every 10 s at most. */
static void show_progress(double start, int rows_done, int rows)
{
    static double next_line = 1.0; /* not a terminal: the next line's time */
    double elapsed = seconds_now() - start;
    if (elapsed < 1.0)
        return;
    if (isatty(STDERR_FILENO)) {
        fprintf(stderr, "\rrendering: row %d of %d", rows_done, rows);
        if (rows_done == rows)
            fputc('\n', stderr);
    } else if (elapsed >= next_line && rows_done < rows) {
        fprintf(stderr, "rendering: row %d of %d, %.0f s\n", rows_done, rows,
                elapsed);
        next_line = elapsed + 10;
    }
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
    catch_stop_signals();
    moment at[4] = {moment_now()};
    scene s;
    image img = {0};
    png_output out = {0};
    render_stats stats = {0};
    char why[PARSE_MAX_NAME + 256], size[64];
    int status = 1;
    if (!load_scene(&opt, &s))
        goto done;
    /* <<once the scene is loaded>> ch04 */
    warn_of_empty_meshes(&s);
    const char *input = input_named_by_output(&opt, &s);
    if (input != NULL) {
        snprintf(why, sizeof why, "the output is an input: %s", input);
        print_error(opt.output, 0, 0, why);
        goto done;
    }
    if (!open_output(opt.output, &out, why, sizeof why)) {
        print_error(opt.output, 0, 0, why);
        goto done;
    }
    if (!image_init(&img, s.cam.width, s.cam.height)) {
        snprintf(size, sizeof size, "no memory for a %dx%d image",
                 s.cam.width, s.cam.height);
        print_error(argv[0], 0, 0, size);
        goto done;
    }
    /* <<count what the scene holds>> ch05 */
    scene_count_triangles(&s, &stats.triangles_stored,
                          &stats.triangles_instanced);
    at[1] = moment_now();
    render_in_bands(&s, &img, &stats);
    at[2] = moment_now();
    if (!png_output_finish(&out, &img, why, sizeof why)) {
        print_error(opt.output, 0, 0, why);
        goto done;
    }
    at[3] = moment_now();
    if (opt.stats)
        print_stats(&stats, at);
    status = 0;
done:
    close_output(&out);
    image_free(&img);
    scene_free(&s);
    return status;
}
