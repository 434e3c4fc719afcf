/* main.c: the command line of the renderer (chapter 01). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "render.h"
#include "scene_file.h"

/* The scene rendered when no scene file is given. */
static const char DEFAULT_SCENE[] =
    "# Chapter 08: twenty spheres on a floor, searched through a kd-tree.\n"
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
    ;

typedef struct {
    const char *scene_path; /* NULL: the built-in scene */
    const char *output;
    int width, height;      /* 0: as the scene says */
    bool stats, help;
    int threads; /* 0: one per core */
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
        "  --threads N  render on N threads, 1 to 256 (default: one per core)\n"
        "  --help       this text\n",
        program);
}

static bool option_error(const char *program, const char *message,
                         const char *found)
{
    fprintf(stderr, "%s: error: %s%s%s%s\n", program, message,
            found ? ", found '" : "", found ? found : "", found ? "'" : "");
    fprintf(stderr, "Try '%s --help'.\n", program);
    return false;
}

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
        else if (strcmp(arg, "--threads") == 0) {
            if (k + 1 == argc)
                return option_error(argv[0], "this option needs a value", arg);
            char *end;
            const char *value = argv[++k];
            long n = strtol(value, &end, 10);
            if (end == value || *end != '\0' || n < 1 || n > 256)
                return option_error(argv[0], "--threads expects a whole number "
                                             "from 1 to 256", value);
            opt->threads = (int)n;
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
    fprintf(stderr, "sphere tests       %lld\n", st->sphere_tests);
    fprintf(stderr, "triangle tests     %lld\n", st->triangle_tests);
    fprintf(stderr, "box tests          %lld\n", st->box_tests);
    fprintf(stderr, "kd-tree nodes      %lld (%.1f a primary ray)\n", st->kd_nodes,
            (double)st->kd_nodes / (st->primary_rays ? st->primary_rays : 1));
    fprintf(stderr, "rays per second    %.2f million (primary rays)\n",
            st->primary_rays / (render_s > 0 ? render_s : 1e-9) / 1e6);
    fprintf(stderr,
            "time               scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * load_s, 1e3 * render_s, 1e3 * write_s);
}

static void print_trees(const scene *s)
{
    scene_tree_summary t = scene_trees(s);
    fprintf(stderr, "kd-trees           %d: %lld nodes, %lld leaves, depth "
                    "%d, %.2f references an item, built in %.1f ms\n",
            t.trees, t.nodes, t.leaves, t.depth,
            t.items ? (double)t.references / t.items : 0.0,
            1e3 * s->tree_seconds);
}

/* The densest need of the chapter's chart: triangles per covered pixel. */
#define MESH_HINT_TRIANGLES_PER_PIXEL 42

static void print_mesh_hints(const scene *s)
{
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind != SHAPE_MESH)
            continue;
        double pixels = scene_object_pixels(s, o);
        int triangles = s->meshes[o->mesh].triangle_count;
        if (pixels > 0 && triangles > MESH_HINT_TRIANGLES_PER_PIXEL * pixels)
            fprintf(stderr, "hint: object %d, a mesh of %d triangles, covers "
                            "at most %.0f pixels: %.0f triangles a pixel, "
                            "finer than the image can show\n",
                    k + 1, triangles, pixels, triangles / pixels);
    }
}

#include <pthread.h>
#include <stdatomic.h>

enum { BAND_ROWS = 8 }; /* small enough for smooth progress and a fair
                           share of the work, large enough to cost
                           nothing */

static int band_threads = 1; /* from --threads, once the scene is loaded */

/* What every thread shares: the image, handed out band by band. */
typedef struct {
    const scene *s;
    image *img;
    atomic_int next_band, rows_done;
} band_queue;

/* A thread's part: its own counts, on a cache line of their own. */
typedef struct {
    _Alignas(64) render_stats stats;
    band_queue *queue;
    pthread_t thread;
} band_worker;

static int cores_online(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

/* The next band of rows [*first, *last); false when none is left. */
static bool take_band(band_queue *q, int *first, int *last)
{
    int band = atomic_fetch_add(&q->next_band, 1);
    if (band >= (q->img->height + BAND_ROWS - 1) / BAND_ROWS)
        return false;
    *first = band * BAND_ROWS;
    *last = *first + BAND_ROWS < q->img->height ? *first + BAND_ROWS
                                                : q->img->height;
    return true;
}

static void render_band(band_worker *w, int first, int last)
{
    render_rows(w->queue->s, w->queue->img, first, last, &w->stats);
    atomic_fetch_add(&w->queue->rows_done, last - first);
}

static void *band_thread(void *worker)
{
    band_worker *w = worker;
    int first, last;
    while (take_band(w->queue, &first, &last))
        render_band(w, first, last);
    return NULL;
}

/* "[#####     ]  50%  2.31 Mrays/s  3 s left" on a terminal, once the
 * render has taken a second. */
static void show_progress(double start, int rows_done, int rows, int width)
{
    double elapsed = seconds_now() - start;
    if (elapsed < 1.0 || !isatty(STDERR_FILENO))
        return;
    static const char bar[] = "##############################"; /* 30 */
    int filled = 30 * rows_done / rows;
    double left = rows_done ? elapsed * (rows - rows_done) / rows_done : 0;
    fprintf(stderr, "\r[%.*s%*s] %3d%%  %.2f Mrays/s  %.0f s left ", filled,
            bar, 30 - filled, "", 100 * rows_done / rows,
            1e-6 * rows_done * (double)width / elapsed, left);
    if (rows_done == rows)
        fputc('\n', stderr);
}

/* Adds the counts of part to sum: render_stats holds counts only. */
static void add_stats(render_stats *sum, const render_stats *part)
{
    enum { N = sizeof(render_stats) / sizeof(long long) };
    long long a[N], b[N];
    memcpy(a, sum, sizeof a), memcpy(b, part, sizeof b);
    for (int k = 0; k < N; k++)
        a[k] += b[k];
    memcpy(sum, a, sizeof a);
}

static void render_in_bands(const scene *s, image *img, render_stats *stats)
{
    double start = seconds_now();
    band_queue q = {.s = s, .img = img};
    atomic_init(&q.next_band, 0), atomic_init(&q.rows_done, 0);
    band_worker one, *w = NULL;
    int n = band_threads, started = 1, first, last;
    if (n > 1)
        w = aligned_alloc(64, (size_t)n * sizeof *w);
    if (w == NULL)
        w = &one, n = 1; /* out of memory: this thread alone */
    for (int k = 0; k < n; k++)
        w[k] = (band_worker){.queue = &q};
    while (started < n &&
           pthread_create(&w[started].thread, NULL, band_thread,
                          &w[started]) == 0)
        started++; /* a thread that cannot start leaves its share to us */
    while (take_band(&q, &first, &last)) { /* this thread is worker 0 */
        render_band(&w[0], first, last);
        show_progress(start, atomic_load(&q.rows_done), img->height,
                      img->width);
    }
    for (int k = 1; k < started; k++)
        pthread_join(w[k].thread, NULL);
    for (int k = 0; k < started; k++)
        add_stats(stats, &w[k].stats);
    if (w != &one)
        free(w);
}

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
    band_threads = opt.threads > 0 ? opt.threads : cores_online();
    if (opt.stats)
        print_trees(&s);
    if (opt.stats)
        print_mesh_hints(&s);
    if (!image_init(&img, s.cam.width, s.cam.height)) {
        fprintf(stderr, "%s: error: no memory for a %dx%d image\n", argv[0],
                s.cam.width, s.cam.height);
        goto done;
    }
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
