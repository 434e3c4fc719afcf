/* render.c: rendering a scene into an image, band by band (chapter 1). */
#include "render.h"

#include <assert.h>
/* <<render includes>> ch03 */
#include "shade.h"
/* <<render includes>> += ch08 */
#include "search.h"
/* <<render includes>> += ch12 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "memory.h"
#include "moment.h"
#include "pool.h"
/* <<render includes>> += ch13 */
#include "antialias.h"

/* What the pixel whose primary ray is r shows. */
static vec3 pixel_color(const scene *s, ray r, render_stats *stats)
{
    /* <<show something other than light>> ch08 */
    if (s->heatmap > 0) { /* the kdtree statement's heat map: work, not light */
        long long before = stats->kd_nodes;
        hit h;
        scene_intersect(s, r, 0, INFINITY, &h, stats);
        double x = fmin((double)(stats->kd_nodes - before) / s->heatmap, 1);
        return (vec3){fmin(3 * x, 1), fmin(fmax(3 * x - 1, 0), 1),
                      fmax(3 * x - 2, 0)}; /* black, red, yellow, white */
    }
    vec3 c = trace(s, r, 0, stats);
    /* <<map the pixel's light for display>> ch03 */
    if (s->tone.alpha != 1 || s->tone.beta != 1) /* the defaults only clip */
        c = (vec3){tone_map(c.x, s->tone.alpha, s->tone.beta),
                   tone_map(c.y, s->tone.alpha, s->tone.beta),
                   tone_map(c.z, s->tone.alpha, s->tone.beta)};
    return c;
}
/* <<ways to draw a pixel>> ch13 */
_Static_assert(sizeof(((render_stats *)0)->pixel_rays) ==
                       (PIXEL_MAX_RAYS + 1) * sizeof(long long) &&
                   sizeof(((render_stats *)0)->pixel_depths) ==
                       (PIXEL_MAX_DEPTH + 1) * sizeof(long long),
               "the counters of stats.h have room for every count");

/* What the image shows at the point (u, v), and the ray counted. */
static vec3 color_at(const scene *s, const camera_view *view, double u,
                     double v, render_stats *stats)
{
    stats->primary_rays++;
    return pixel_color(s, camera_view_ray_at(view, u, v), stats);
}

/* The grid or jittered rays of pixel (i, j), averaged: weights 1/N. */
static vec3 sampled_pixel(const scene *s, const camera_view *view, int i,
                          int j, render_stats *stats, int *rays)
{
    int n = pixel_sample_count(&s->pixels);
    vec3 sum = {0, 0, 0};
    for (int k = 0; k < n; k++) {
        double u, v;
        pixel_sample_at(&s->pixels, i, j, k, &u, &v);
        sum = vec3_add(sum, color_at(s, view, u, v, stats));
    }
    *rays = n;
    return vec3_scale(sum, 1.0 / n);
}

/* rays against the heat map's white: black, red, yellow, white. */
static vec3 rays_heat(int rays, int white)
{
    double x = fmin((double)rays / white, 1);
    return (vec3){fmin(3 * x, 1), fmin(fmax(3 * x - 1, 0), 1),
                  fmax(3 * x - 2, 0)};
}
/* <<the corners of a band>> ch13 */

enum { STRIP = 256 }; /* columns of corners a band keeps at a time */

/* The corners (i, j) of corner row j, i0 <= i <= i1, into row. */
static void corner_row(const scene *s, const camera_view *view, int i0,
                       int i1, int j, vec3 *row, render_stats *stats)
{
    for (int i = i0; i <= i1; i++) {
        double u, v;
        pixel_point_at(&s->pixels, i, j, 0, 0, &u, &v);
        row[i - i0] = color_at(s, view, u, v, stats);
    }
}
/* <<the points of a pixel>> ch13 */

enum { FINEST = 1 << PIXEL_MAX_DEPTH }; /* squares a side, at most */

/* Pixel (i, j)'s points (i + a/cells, j + b/cells), traced when needed. */
typedef struct {
    const scene *s;
    const camera_view *view;
    render_stats *stats;
    int i, j, cells;   /* cells = 2^depth squares a side */
    int rays, deepest; /* traced for this pixel; the depth reached */
    bool traced[FINEST + 1][FINEST + 1];
    vec3 color[FINEST + 1][FINEST + 1];
} pixel_points;

static vec3 point_color(pixel_points *p, int a, int b)
{
    if (!p->traced[b][a]) {
        double u, v;
        pixel_point_at(&p->s->pixels, p->i, p->j, a, b, &u, &v);
        p->color[b][a] = color_at(p->s, p->view, u, v, p->stats);
        p->traced[b][a] = true;
        p->rays++;
    }
    return p->color[b][a];
}
/* <<a square's mean>> ch13 */

/* The mean colour of the square of size x size steps whose top left
 * point is (a, b), at depth. */
static vec3 square_mean(pixel_points *p, int a, int b, int size, int depth)
{
    const pixel_sampling *ps = &p->s->pixels;
    vec3 c[4] = {point_color(p, a, b), point_color(p, a + size, b),
                 point_color(p, a, b + size),
                 point_color(p, a + size, b + size)};
    bool divide = depth < ps->depth &&
                  (depth < ps->min_depth || pixel_corners_differ(ps, c));
    if (!divide) {
        p->deepest = depth > p->deepest ? depth : p->deepest;
        return vec3_scale(vec3_add(vec3_add(c[0], c[1]),
                                   vec3_add(c[2], c[3])), 0.25);
    }
    int h = size / 2;
    vec3 top = vec3_add(square_mean(p, a, b, h, depth + 1),
                        square_mean(p, a + h, b, h, depth + 1));
    vec3 bottom = vec3_add(square_mean(p, a, b + h, h, depth + 1),
                           square_mean(p, a + h, b + h, h, depth + 1));
    return vec3_scale(vec3_add(top, bottom), 0.25);
}
/* <<an adaptive pixel>> ch13 */

/* Pixel (i, j) by Whitted's scheme; top[0], top[1] are its upper corners,
 * bottom[0], bottom[1] its lower ones. */
static vec3 adaptive_pixel(const scene *s, const camera_view *view, int i,
                           int j, const vec3 *top, const vec3 *bottom,
                           render_stats *stats, int *rays)
{
    pixel_points p; /* only the marks of this depth's points are cleared */
    int n = 1 << s->pixels.depth;
    p.s = s, p.view = view, p.stats = stats, p.i = i, p.j = j, p.cells = n;
    p.rays = 0, p.deepest = 0;
    for (int b = 0; b <= n; b++)
        memset(p.traced[b], 0, (size_t)(n + 1) * sizeof p.traced[b][0]);
    p.color[0][0] = top[0], p.color[0][n] = top[1];
    p.color[n][0] = bottom[0], p.color[n][n] = bottom[1];
    p.traced[0][0] = p.traced[0][n] = p.traced[n][0] = p.traced[n][n] =
        true;
    vec3 c = square_mean(&p, 0, 0, n, 0);
    stats->pixel_depths[p.deepest]++;
    *rays = p.rays + 1; /* and its share of the corners: one */
    return c;
}
/* <<rows of sampled pixels>> ch13 */

/* Pixel (i, j) into img: its colour c, or its rays on the heat map. */
static void show_pixel(const scene *s, image *img, int i, int j, vec3 c,
                       int rays, render_stats *stats)
{
    stats->pixel_rays[rays]++;
    if (s->pixels.heatmap > 0)
        c = rays_heat(rays, s->pixels.heatmap);
    image_set(img, i, j, c);
}

/* Pixels i0 <= i < i1 of rows [first, last), adaptive: the corners kept
 * two rows at a time, the row above and the row below. */
static void adaptive_strip(const scene *s, image *img,
                           const camera_view *view, int i0, int i1,
                           int first, int last, render_stats *stats)
{
    vec3 rows[2][STRIP + 1], *top = rows[0], *bottom = rows[1];
    corner_row(s, view, i0, i1, first, top, stats);
    for (int j = first; j < last; j++) {
        corner_row(s, view, i0, i1, j + 1, bottom, stats);
        for (int i = i0; i < i1; i++) {
            int rays;
            vec3 c = adaptive_pixel(s, view, i, j, &top[i - i0],
                                    &bottom[i - i0], stats, &rays);
            show_pixel(s, img, i, j, c, rays, stats);
        }
        vec3 *above = top;
        top = bottom, bottom = above; /* this row's bottom is the next top */
    }
}

static void render_rows_sampled(const scene *s, image *img,
                                const camera_view *view, int first,
                                int last, render_stats *stats)
{
    if (s->pixels.pattern == PIXEL_ADAPTIVE) {
        for (int i0 = 0; i0 < img->width && first < last; i0 += STRIP)
            adaptive_strip(s, img, view, i0,
                           img->width - i0 < STRIP ? img->width : i0 + STRIP,
                           first, last, stats);
        return;
    }
    for (int j = first; j < last; j++)
        for (int i = 0; i < img->width; i++) {
            int rays;
            vec3 c = sampled_pixel(s, view, i, j, stats, &rays);
            show_pixel(s, img, i, j, c, rays, stats);
        }
}

void render_rows(const scene *s, image *img, int first, int last,
                 render_stats *stats)
{
    /* the contract, checked: a caller's mistake, not bad input */
    assert(img->width == s->cam.width && img->height == s->cam.height);
    assert(0 <= first && first <= last && last <= img->height);
    camera_view view = camera_view_of(&s->cam);
    /* <<draw the rows another way>> ch13 */
    if (s->pixels.pattern != PIXEL_CENTER || s->pixels.heatmap > 0) {
        render_rows_sampled(s, img, &view, first, last, stats);
        return;
    }
    for (int j = first; j < last; j++) {
        for (int i = 0; i < img->width; i++) {
            ray r = camera_view_ray(&view, i, j);
            stats->primary_rays++;
            image_set(img, i, j, pixel_color(s, r, stats));
        }
    }
}

void render(const scene *s, image *img, render_stats *stats)
{
    render_rows(s, img, 0, img->height, stats);
}

/* <<rendering in bands>> ch12 */
/* <<the bands' shared work>> ch12 */
/* A band's counts, on cache lines of their own. */
typedef struct {
    _Alignas(64) render_stats stats;
} band_counts;

/* What every band shares: the image, its bands' counts, and how far it
 * has come, which the reporter reads. */
typedef struct {
    const scene *s;
    image *img;
    int band_rows;       /* rows_per_band of the image */
    band_counts *counts; /* one a band */
    atomic_int rows_done;
    atomic_llong rays_done;
    const render_settings *how;
    bool reporting;       /* a reporter thread shows the progress */
    pthread_mutex_t lock; /* one report at a time; guards finished */
    pthread_cond_t wake;  /* the reporter's, when the image is done */
    bool finished;
} band_queue;

/* Rows a band: BAND_ROWS, or fewer in a picture of fewer than BAND_ROWS
 * bands, so that several threads share even a small one. A function of
 * the height alone: the bands, and what they count, are the same on any
 * number of threads. */
static int rows_per_band(int height)
{
    int rows = height / BAND_ROWS; /* for BAND_ROWS bands at least */
    return rows < 1 ? 1 : rows < BAND_ROWS ? rows : BAND_ROWS;
}

static long long greatest_common_divisor(long long a, long long b)
{
    while (b != 0) {
        long long r = a % b;
        a = b, b = r;
    }
    return a;
}

/* The band drawn at turn t of n: each turn steps about 0.618 of the image
 * down from the last, wrapping around (a step that shares no factor with
 * n, so that n turns draw every band once), which spreads the bands done
 * at any moment evenly over the image. */
static int band_of_turn(int t, int n)
{
    long long step = (long long)(0.6180339887 * n);
    while (greatest_common_divisor(step, n) != 1)
        step++; /* 1 and n share none: it ends */
    return (int)((long long)t * step % n);
}

/* Every ray a render has traced: primary, shadow and secondary. */
static long long rays_of(const render_stats *st)
{
    return st->primary_rays + st->shadow_rays + st->reflection_rays +
           st->refraction_rays;
}

/* <<the reporter>> ch12 */
/* The progress so far, shown by one thread at a time. */
static void report(band_queue *q)
{
    pthread_mutex_lock(&q->lock);
    q->how->progress(q->how->progress_context, atomic_load(&q->rows_done),
                     q->img->height, atomic_load(&q->rays_done));
    pthread_mutex_unlock(&q->lock);
}

/* The reporter's life: the progress four times a second, until the image
 * is finished (the whole image's is the calling thread's to show). */
static void *report_thread(void *queue)
{
    band_queue *q = queue;
    pthread_mutex_lock(&q->lock);
    while (!q->finished) {
        struct timespec until = moment_deadline(0.25);
        pthread_cond_timedwait(&q->wake, &q->lock, &until);
        if (!q->finished && atomic_load(&q->rows_done) < q->img->height)
            q->how->progress(q->how->progress_context,
                             atomic_load(&q->rows_done), q->img->height,
                             atomic_load(&q->rays_done));
    }
    pthread_mutex_unlock(&q->lock);
    return NULL;
}

/* Tells the reporter that the image is done, and waits for it. */
static void stop_reporter(band_queue *q, pthread_t reporter)
{
    pthread_mutex_lock(&q->lock);
    q->finished = true;
    pthread_cond_signal(&q->wake);
    pthread_mutex_unlock(&q->lock);
    pthread_join(reporter, NULL);
}

/* <<a band's job>> ch12 */
/* Band k of the image: its rows drawn, its work counted in its own
 * record, and how far the image has come. */
static void draw_band(void *queue, int k)
{
    band_queue *q = queue;
    int height = q->img->height;
    int bands = (height + q->band_rows - 1) / q->band_rows;
    int first = band_of_turn(k, bands) * q->band_rows;
    int last = first + q->band_rows < height ? first + q->band_rows
                                             : height;
    render_stats *counts = &q->counts[k].stats;
    render_rows(q->s, q->img, first, last, counts);
    atomic_fetch_add(&q->rays_done, rays_of(counts));
    int done = atomic_fetch_add(&q->rows_done, last - first) + last - first;
    if (q->how->progress != NULL && !q->reporting && done < height)
        report(q); /* no reporter: between bands */
}

/* <<adding up the bands' counts>> ch12 */
_Static_assert(sizeof(render_stats) % sizeof(long long) == 0,
               "render_stats holds counts (long long) only");

/* Adds the counts of part to sum. */
static void add_stats(render_stats *sum, const render_stats *part)
{
    enum { N = sizeof(render_stats) / sizeof(long long) };
    long long a[N], b[N];
    memcpy(a, sum, sizeof a), memcpy(b, part, sizeof b);
    for (int k = 0; k < N; k++)
        a[k] += b[k];
    memcpy(sum, a, sizeof a);
}

/* <<the bands on the pool>> ch12 */
void render_in_bands(const scene *s, image *img, const render_settings *how,
                     render_stats *stats)
{
    band_queue q = {.s = s, .img = img, .how = how,
                    .band_rows = rows_per_band(img->height)};
    atomic_init(&q.rows_done, 0), atomic_init(&q.rays_done, 0);
    pthread_mutex_init(&q.lock, NULL), moment_condition_init(&q.wake);
    int bands = (img->height + q.band_rows - 1) / q.band_rows;
    band_counts one = {0};
    q.counts = memory_alloc_aligned(64, (size_t)bands, sizeof *q.counts);
    if (q.counts != NULL)
        memset(q.counts, 0, (size_t)bands * sizeof *q.counts);
    else /* no memory: the whole image as one band */
        q.counts = &one, q.band_rows = img->height, bands = 1;
    pthread_t reporter; /* none: the bands show the progress */
    q.reporting = how->progress != NULL &&
                  !how->progress_redrawn &&
                  pthread_create(&reporter, NULL, report_thread, &q) == 0;
    if (how->progress != NULL)
        report(&q); /* nothing done yet: the rows to do are known */
    pool_for(bands, how->threads, draw_band, &q);
    if (q.reporting)
        stop_reporter(&q, reporter);
    if (how->progress != NULL)
        report(&q); /* the whole image: a terminal's bar ends */
    for (int k = 0; k < bands; k++)
        add_stats(stats, &q.counts[k].stats);
    pthread_mutex_destroy(&q.lock), pthread_cond_destroy(&q.wake);
    if (q.counts != &one)
        free(q.counts);
}
