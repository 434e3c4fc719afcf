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

void render_rows(const scene *s, image *img, int first, int last,
                 render_stats *stats)
{
    /* the contract, checked: a caller's mistake, not bad input */
    assert(img->width == s->cam.width && img->height == s->cam.height);
    assert(0 <= first && first <= last && last <= img->height);
    camera_view view = camera_view_of(&s->cam);
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
