/* ch12_pool.c: chapter 12's one pool of threads: every job of a loop
 * runs once, on no more threads than the loop asks for or has jobs; a
 * loop inside a job runs on the job's thread; and a run starts at most
 * the threads it asks for, less the calling thread, however many loops
 * it runs: loops by the thousand, and a scene read, built and drawn. */
#include <check.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pool.h"
#include "render.h"
#include "scene_file.h"
#include "test_util.h"

enum { MOST_JOBS = 1000 };

/* What the jobs of a loop write: how often each ran, on which thread,
 * and how many threads took part. */
typedef struct {
    atomic_int runs[MOST_JOBS];
    pthread_t thread[MOST_JOBS];
} job_record;

static void count_run(void *record, int k)
{
    job_record *r = record;
    atomic_fetch_add(&r->runs[k], 1);
    r->thread[k] = pthread_self();
}

/* The distinct threads among the first n jobs' threads. */
static int threads_seen(const job_record *r, int n)
{
    int distinct = 0;
    for (int k = 0; k < n; k++) {
        bool earlier = false;
        for (int j = 0; j < k && !earlier; j++)
            earlier = pthread_equal(r->thread[j], r->thread[k]) != 0;
        distinct += !earlier;
    }
    return distinct;
}

START_TEST(test_a_loop_runs_every_job_once)
{
    static job_record r;
    const int counts[] = {0, 1, 2, 7, 100, MOST_JOBS};
    const int threads[] = {1, 2, 3, 8, 0};
    for (size_t c = 0; c < sizeof counts / sizeof *counts; c++)
        for (size_t t = 0; t < sizeof threads / sizeof *threads; t++) {
            memset(&r, 0, sizeof r);
            int n = counts[c];
            int shared = pool_for(n, threads[t], count_run, &r);
            for (int k = 0; k < n; k++)
                ck_assert_msg(atomic_load(&r.runs[k]) == 1,
                              "%d jobs on %d threads: job %d ran %d times",
                              n, threads[t], k, atomic_load(&r.runs[k]));
            int most = pool_threads(threads[t]);
            int expected = n < 1 ? 1 : n < most ? n : most;
            ck_assert_msg(shared == expected,
                          "%d jobs on %d threads: shared among %d, not %d",
                          n, threads[t], shared, expected);
            ck_assert_int_le(threads_seen(&r, n), shared);
        }
}
END_TEST

/* A job that runs a loop of its own: every inner job must run on the
 * outer job's thread, and at once (a wait for the pool would never end:
 * the pool is this loop's). */
typedef struct {
    job_record outer;
    atomic_int inner_runs, inner_elsewhere;
    atomic_int inner_shared_by_more;
} nested_record;

typedef struct {
    nested_record *r;
    pthread_t thread;
} inner_context;

static void inner_job(void *context, int k)
{
    inner_context *c = context;
    (void)k;
    atomic_fetch_add(&c->r->inner_runs, 1);
    if (!pthread_equal(pthread_self(), c->thread))
        atomic_fetch_add(&c->r->inner_elsewhere, 1);
}

static void outer_job(void *record, int k)
{
    nested_record *r = record;
    count_run(&r->outer, k);
    inner_context c = {r, pthread_self()};
    if (pool_for(50, 4, inner_job, &c) != 1)
        atomic_fetch_add(&r->inner_shared_by_more, 1);
}

START_TEST(test_a_loop_inside_a_job_runs_on_its_thread)
{
    static nested_record r;
    const int threads[] = {2, 4, 8};
    for (int t = 0; t < 3; t++) {
        memset(&r, 0, sizeof r);
        pool_for(40, threads[t], outer_job, &r);
        for (int k = 0; k < 40; k++)
            ck_assert_int_eq(atomic_load(&r.outer.runs[k]), 1);
        ck_assert_int_eq(atomic_load(&r.inner_runs), 40 * 50);
        ck_assert_int_eq(atomic_load(&r.inner_elsewhere), 0);
        ck_assert_int_eq(atomic_load(&r.inner_shared_by_more), 0);
    }
}
END_TEST

static void nothing(void *context, int k)
{
    (void)context, (void)k;
}

/* A grid of 2 side^2 triangles in the xz plane, a little uneven, as OBJ
 * text in a file of tmpdir; its path. */
static const char *grid_obj(int side)
{
    size_t size = (size_t)(side + 1) * (side + 1) * 40 +
                  (size_t)side * side * 2 * 32;
    char *text = malloc(size);
    ck_assert_ptr_nonnull(text);
    size_t at = 0;
    for (int j = 0; j <= side; j++)
        for (int i = 0; i <= side; i++)
            at += (size_t)snprintf(text + at, size - at, "v %d %d %d\n", i,
                                   (i * 7 + j * 13) % 11, j);
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++) {
            int a = j * (side + 1) + i + 1, c = a + side + 1;
            at += (size_t)snprintf(text + at, size - at,
                                   "f %d %d %d\nf %d %d %d\n", a, a + 1,
                                   c + 1, a, c + 1, c);
        }
    const char *path = write_bytes("grid.obj", text, at);
    free(text);
    return path;
}

START_TEST(test_a_run_starts_at_most_its_threads)
{
    /* a thousand loops on four threads: three helpers at most, or none
     * more than an earlier test of this process started */
    int before = pool_started();
    for (int k = 0; k < 1000; k++)
        pool_for(1 + k % 9, 4, nothing, NULL);
    ck_assert_int_le(pool_started(), before > 3 ? before : 3);
    /* a mesh large enough for the build's top to share its passes (more
     * than twice BVH_SHARED_ITEMS triangles) and the reader its parts,
     * read, built and drawn on 256 threads */
    grid_obj(300);
    const char *scene_path =
        write_file("grid.scene", "camera fov 60\nimage 64 48\n"
                                 "accelerator bvh\n"
                                 "mesh file grid.obj scale 0.01 "
                                 "offset -1.5 -1 2\n"
                                 "light directional direction 1 -1 1\n");
    scene s;
    scene_error err;
    scene_init(&s);
    s.bvh_settings.threads = 256;
    ck_assert_msg(scene_load(&s, scene_path, &err), "%s", err.message);
    ck_assert_int_eq(s.meshes[0].triangle_count, 2 * 300 * 300);
    ck_assert_int_gt(s.meshes[0].parts, 1);
    image img;
    ck_assert(image_init(&img, s.cam.width, s.cam.height));
    render_stats stats = {0};
    render_in_bands(&s, &img, &(render_settings){.threads = 256}, &stats);
    ck_assert_int_eq(stats.primary_rays, 64 * 48);
    ck_assert_msg(pool_started() <= 255, "%d threads started",
                  pool_started());
    image_free(&img);
    scene_free(&s);
}
END_TEST

Suite *ch12_pool_suite(void)
{
    Suite *s = suite_create("ch12 pool");
    TCase *tc = tcase_create("loops");
    tcase_add_checked_fixture(tc, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(tc, 120);
    tcase_add_threaded_test(tc, test_a_loop_runs_every_job_once);
    tcase_add_threaded_test(tc, test_a_loop_inside_a_job_runs_on_its_thread);
    runner_next_test_is_threaded();
    tcase_add_slow_test(tc, test_a_run_starts_at_most_its_threads);
    suite_add_tcase(s, tc);
    return s;
}
