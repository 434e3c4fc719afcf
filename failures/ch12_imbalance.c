/* ch12_imbalance.c: chapter 8's bunny scene shared among four threads,
 * by a fixed share of the rows (left) and by bands taken by the next
 * thread free (right), with each thread's work measured in rays.
 *
 *   build/rel/failures/ch12_imbalance figures/ch12-failure-imbalance.png
 *
 * No clock is read: the rays that each row of the scene costs (primary,
 * shadow and secondary, from render_stats) are counted once, on one
 * thread, and the threads' work is computed from them. Left, thread k
 * of T draws rows [k h / T, (k + 1) h / T). Right, chapter 12's bands of
 * eight rows are handed out in order, each to the thread that is free
 * first, which is the one that has traced the fewest rays so far when a
 * band's time is taken to be its rays (ties: the lowest thread). Each
 * row is tinted with the colour of its thread; under each half, a bar
 * for each thread as long as its rays, and a black mark at the even
 * share, the total over T. Prints the longest thread's rays over the
 * even share for both, and exits 1 unless the fixed share's is at least
 * 1.2 and the bands' smaller: then the figure no longer shows the
 * failure.
 *
 * Built by `make failures` against the objects of chapter 12's program
 * but main.o; `make test` checks the committed PNG. */
#include <stdlib.h>
#include <string.h>

#include "failure_util.h"
#include "render.h"
#include "scene_file.h"

#define SCENE "build/tangle/ch12/scenes/ch08-bunny.scene"
#define WIDTH 400
#define HEIGHT 300
#define THREADS 4
#define BAR 10       /* rows of a thread's bar */
#define BAR_GAP 4    /* rows between two bars */
#define SCALE 2      /* pixels magnified */
#define TINT 0.45    /* of the thread's colour in a tinted pixel */

static const vec3 COLOURS[THREADS] = {
    {0.90, 0.30, 0.15}, {0.15, 0.40, 0.90}, {0.20, 0.70, 0.25},
    {0.85, 0.70, 0.10}};

/* Every ray a render has traced: primary, shadow and secondary. */
static long long rays_of(const render_stats *st)
{
    return st->primary_rays + st->shadow_rays + st->reflection_rays +
           st->refraction_rays;
}

/* The rays of each row of s, drawn into img. */
static void rays_by_row(const scene *s, image *img, long long *rays)
{
    for (int j = 0; j < img->height; j++) {
        render_stats st = {0};
        render_rows(s, img, j, j + 1, &st);
        rays[j] = rays_of(&st);
    }
}

/* Thread k of THREADS's rows under the fixed share: owner[j] = k. */
static void fixed_share(int height, int *owner)
{
    for (int k = 0; k < THREADS; k++)
        for (int j = k * height / THREADS; j < (k + 1) * height / THREADS;
             j++)
            owner[j] = k;
}

/* The bands of band_rows rows, each to the thread with the fewest rays
 * so far (the first free when time is rays): owner[j] for every row. */
static void dynamic_bands(const long long *rays, int height, int band_rows,
                          int *owner)
{
    long long done[THREADS] = {0};
    for (int first = 0; first < height; first += band_rows) {
        int last = first + band_rows < height ? first + band_rows : height;
        int free_first = 0;
        for (int k = 1; k < THREADS; k++)
            if (done[k] < done[free_first])
                free_first = k;
        for (int j = first; j < last; j++)
            owner[j] = free_first, done[free_first] += rays[j];
    }
}

/* Each thread's rays under owner, into work; the largest. */
static long long work_of(const long long *rays, const int *owner,
                         int height, long long *work)
{
    long long most = 0;
    memset(work, 0, THREADS * sizeof *work);
    for (int j = 0; j < height; j++)
        work[owner[j]] += rays[j];
    for (int k = 0; k < THREADS; k++)
        most = work[k] > most ? work[k] : most;
    return most;
}

/* out: the render, each row tinted by its thread, and under it a bar
 * for each thread's rays (scale: longest rays across the width), the
 * black mark at the even share. */
static void draw_half(const image *render, const int *owner,
                      const long long *work, long long longest,
                      long long total, image *out)
{
    for (int j = 0; j < out->height; j++)
        for (int i = 0; i < out->width; i++)
            image_set(out, i, j, (vec3){1, 1, 1});
    for (int j = 0; j < render->height; j++)
        for (int i = 0; i < render->width; i++) {
            vec3 c = render->pixels[(size_t)j * render->width + i];
            image_set(out, i, j,
                      vec3_add(vec3_scale(c, 1 - TINT),
                               vec3_scale(COLOURS[owner[j]], TINT)));
        }
    int even = (int)((double)total / THREADS / (double)longest *
                     (out->width - 1));
    for (int k = 0; k < THREADS; k++) {
        int top = render->height + BAR_GAP + k * (BAR + BAR_GAP);
        int length = (int)((double)work[k] / (double)longest *
                           (out->width - 1));
        for (int j = top; j < top + BAR; j++) {
            for (int i = 0; i <= length; i++)
                image_set(out, i, j, COLOURS[k]);
            image_set(out, even, j, (vec3){0, 0, 0});
        }
    }
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    scene_error err;
    scene_init(&s);
    if (!scene_load(&s, SCENE, &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line,
                err.col, err.message);
        return 2;
    }
    s.cam.width = WIDTH, s.cam.height = HEIGHT;
    image render, left, right;
    int extra = BAR_GAP + THREADS * (BAR + BAR_GAP);
    long long rays[HEIGHT], fixed[THREADS], bands[THREADS], total = 0;
    int fixed_owner[HEIGHT], band_owner[HEIGHT];
    if (!image_init(&render, WIDTH, HEIGHT) ||
        !image_init(&left, WIDTH, HEIGHT + extra) ||
        !image_init(&right, WIDTH, HEIGHT + extra)) {
        fprintf(stderr, "%s: error: out of memory\n", path);
        return 2;
    }
    rays_by_row(&s, &render, rays);
    for (int j = 0; j < HEIGHT; j++)
        total += rays[j];
    fixed_share(HEIGHT, fixed_owner);
    dynamic_bands(rays, HEIGHT, BAND_ROWS, band_owner);
    long long most_fixed = work_of(rays, fixed_owner, HEIGHT, fixed);
    long long most_bands = work_of(rays, band_owner, HEIGHT, bands);
    long long longest = most_fixed > most_bands ? most_fixed : most_bands;
    draw_half(&render, fixed_owner, fixed, longest, total, &left);
    draw_half(&render, band_owner, bands, longest, total, &right);
    double even = (double)total / THREADS;
    printf("%s: %lld rays on %d threads; the longest thread traces %.2f "
           "times the even share with a fixed share of the rows, %.2f "
           "with bands\n", path, total, THREADS, most_fixed / even,
           most_bands / even);
    bool ok = write_side_by_side(&left, &right, SCALE, path);
    bool shows = most_fixed >= 1.2 * even && most_bands < most_fixed;
    if (ok && !shows)
        fprintf(stderr, "%s: error: the fixed share is no longer uneven\n",
                path);
    image_free(&render), image_free(&left), image_free(&right);
    scene_free(&s);
    return ok && shows ? 0 : 1;
}
