/* ch09_speed.c: rendering on all cores (chapter 09).
 *
 * A pixel depends only on its ray, so the number of threads may change how
 * soon the picture is done, never what it is: every test here renders the
 * same scene on several thread counts and compares the outputs byte for
 * byte, or the counts of --stats line for line. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image.h"
#include "render.h"
#include "scene_file.h"
#include "test_util.h"

/* The scenes of chapter 8's tie test (tests/ch08_kdtree.c): cones whose
 * apexes lie exactly on pixel rays, as an OBJ mesh and as lone triangles. */
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size);

/* Writes a scene with the teapot, and a link to meshes/ beside it. */
static const char *teapot_scene(void)
{
    link_meshes();
    return write_file(
        "teapot.scene",
        "image 96 72\n"
        "sphere center 0 -1001 6 radius 1000\n"
        "mesh file meshes/teapot-8.obj scale 0.5 offset 0 -1 6 smooth\n"
        "sphere center 1.5 0 7 radius 0.5\n");
}

static char *read_all(const char *path, size_t *length)
{
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    char *data = malloc(1 << 20);
    ck_assert_ptr_nonnull(data);
    *length = fread(data, 1, 1 << 20, f);
    fclose(f);
    return data;
}

/* What the chapter's program renders of scene_path on `threads` threads. */
static char *render_on(const char *scene_path, const char *threads,
                       size_t *length)
{
    char errors[4096];
    const char *out = tmp_path("threads.png");
    const char *args[] = {scene_path, "--threads", threads, "-o", out, NULL};
    ck_assert_msg(run_bin(args, errors, sizeof errors) == 0, "%s", errors);
    return read_all(out, length);
}

/* scene_path drawn on 1 thread and on each of others[0..n): the same bytes. */
static void expect_same_on_threads(const char *scene_path,
                                   const char *const *others, int n)
{
    size_t n1, nk;
    char *one = render_on(scene_path, "1", &n1);
    for (int k = 0; k < n; k++) {
        char *other = render_on(scene_path, others[k], &nk);
        ck_assert_msg(nk == n1 && memcmp(one, other, n1) == 0,
                      "%s: --threads %s differs", scene_path, others[k]);
        free(other);
    }
    free(one);
}

START_TEST(test_thread_count_does_not_change_the_image)
{
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s", teapot_scene());
    const char *others[] = {"2", "3"};
    expect_same_on_threads(scene_path, others, 2);
}
END_TEST

START_TEST(test_ties_come_out_alike_on_any_number_of_threads)
{
    static char obj[1 << 18], lone[1 << 19];
    tie_scene_texts(obj, sizeof obj, lone, sizeof lone);
    write_file("fans.obj", obj);
    char mesh_path[192], lone_path[192];
    snprintf(mesh_path, sizeof mesh_path, "%s",
             write_file("mesh.scene",
                        "image 48 36\nmesh file fans.obj color 0.9 0.7 0.4\n"));
    snprintf(lone_path, sizeof lone_path, "%s", write_file("lone.scene", lone));
    const char *others[] = {"3"};
    expect_same_on_threads(mesh_path, others, 1);
    expect_same_on_threads(lone_path, others, 1);
}
END_TEST

/* The counts --stats prints (no times, no rates: "time", "rays/s") for
 * --threads n. */
static void stats_counts(const char *scene_path, const char *n, char *counts,
                         size_t size)
{
    char errors[4096];
    const char *args[] = {scene_path, "--threads",       n,   "--stats",
                          "-o",       tmp_path("s.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    counts[0] = '\0';
    for (char *line = strtok(errors, "\n"); line; line = strtok(NULL, "\n"))
        if (!strstr(line, "time") && !strstr(line, "rays/s") &&
            !strstr(line, "built in"))
            strncat(counts, line, size - strlen(counts) - 2),
                strcat(counts, "\n");
}

START_TEST(test_statistics_add_up_whatever_the_thread_count)
{
    char scene_path[192], one[2048], three[2048];
    snprintf(scene_path, sizeof scene_path, "%s", teapot_scene());
    stats_counts(scene_path, "1", one, sizeof one);
    stats_counts(scene_path, "3", three, sizeof three);
    ck_assert_str_eq(one, three);
    ck_assert_ptr_nonnull(strstr(one, "kd-tree nodes"));
}
END_TEST

/* The teapot's mesh gets a BVH (the default): the kd-trees' line of
 * --stats must not carry the build time, which is the BVH's. */
START_TEST(test_the_kd_trees_line_holds_no_bvh_build_time)
{
    char errors[4096], scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s", teapot_scene());
    const char *args[] = {scene_path, "--stats", "-o", tmp_path("s.png"),
                          NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    const char *kd = strstr(errors, "kd-trees ");
    ck_assert_ptr_nonnull(kd);
    ck_assert_ptr_nonnull(strstr(kd, " 0: 0 nodes")); /* no kd-tree built */
    char line[256];
    snprintf(line, sizeof line, "%.*s", (int)strcspn(kd, "\n"), kd);
    ck_assert_msg(strstr(line, " ms") == NULL,
                  "the kd-trees' line gives a time: %s", line);
    ck_assert_ptr_nonnull(strstr(errors, "\ntrees built in "));
    ck_assert_ptr_nonnull(strstr(errors, "\nbvhs "));
}
END_TEST

START_TEST(test_bad_thread_counts_are_usage_errors)
{
    const char *bad[] = {"0", "-1", "abc", "2x", "257", "", "1e3"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        char errors[1024];
        const char *out = tmp_path("never.png");
        const char *args[] = {"--threads", bad[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "--threads expects a whole number") !=
                          NULL,
                      "%s", errors);
        ck_assert(!file_exists(out));
    }
    char errors[1024];
    const char *args[] = {"--threads", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_ptr_nonnull(strstr(errors, "needs a value"));
}
END_TEST

/* A small scene of the book's kinds of things, parsed here. */
static void small_scene(scene *s)
{
    static const char text[] =
        "image 37 23\n"
        "sphere center 0 -1001 6 radius 1000 color 0.7 0.7 0.6\n"
        "sphere center 0 0 6 radius 1 color 0.9 0.3 0.2\n"
        "triangle a -2 -1 8  b 2 -1 8  c 0 2 8\n"
        "light point position 3 4 0\n";
    scene_error err;
    scene_init(s);
    ck_assert_msg(scene_parse(s, text, sizeof text - 1, "small", &err), "%s",
                  err.message);
}

/* The small scene, and what chapter 1's render draws of it in one go. */
static void small_scene_drawn_whole(scene *s, image *img, render_stats *stats)
{
    small_scene(s);
    ck_assert(image_init(img, s->cam.width, s->cam.height));
    *stats = (render_stats){0};
    render(s, img, stats);
}

/* img and stats drawn by render_in_bands on `threads` threads. */
static void draw_on(const scene *s, int threads, image *img,
                    render_stats *stats)
{
    ck_assert(image_init(img, s->cam.width, s->cam.height));
    *stats = (render_stats){0};
    render_in_bands(s, img, &(render_settings){.threads = threads}, stats);
}

START_TEST(test_bands_on_threads_draw_what_one_render_draws)
{
    /* The bands, on one thread or three (23 rows: the last band is short),
     * draw every pixel that chapter 1's render draws, the same. */
    scene s;
    image whole, banded;
    render_stats whole_stats, stats;
    small_scene_drawn_whole(&s, &whole, &whole_stats);
    const int counts[] = {1, 3};
    for (int k = 0; k < 2; k++) {
        draw_on(&s, counts[k], &banded, &stats);
        size_t n = (size_t)whole.width * whole.height;
        ck_assert_msg(memcmp(whole.pixels, banded.pixels, n * sizeof(vec3)) ==
                          0,
                      "%d threads draw another picture", counts[k]);
        image_free(&banded);
    }
    image_free(&whole);
    scene_free(&s);
}
END_TEST

START_TEST(test_a_tall_image_on_four_threads_is_one_renders)
{
    /* 600 rows: 75 bands of 8, enough that every thread takes some while
     * the others draw theirs. Whatever the threads share is shared at the
     * same time: the picture is one render's, bit for bit (and
     * ThreadSanitizer sees state they share without a lock). */
    scene s;
    image whole, banded;
    render_stats whole_stats, stats;
    static const char text[] =
        "image 96 600\n"
        "sphere center 0 -1001 6 radius 1000 color 0.7 0.7 0.6\n"
        "sphere center 0 0 6 radius 1 color 0.9 0.3 0.2\n"
        "light point position 3 4 0\n";
    scene_error err;
    scene_init(&s);
    ck_assert_msg(scene_parse(&s, text, sizeof text - 1, "tall", &err), "%s",
                  err.message);
    ck_assert(image_init(&whole, 96, 600));
    whole_stats = (render_stats){0};
    render(&s, &whole, &whole_stats);
    draw_on(&s, 4, &banded, &stats);
    ck_assert_msg(memcmp(whole.pixels, banded.pixels,
                         (size_t)96 * 600 * sizeof(vec3)) == 0,
                  "four threads draw another picture of 600 rows");
    ck_assert_int_eq(stats.primary_rays, whole_stats.primary_rays);
    image_free(&banded);
    image_free(&whole);
    scene_free(&s);
}
END_TEST

START_TEST(test_the_threads_counts_add_up_to_one_renders)
{
    /* Each thread counts on its own; added up, the counts are those of one
     * render of the whole image, member by member. */
    scene s;
    image whole, banded;
    render_stats whole_stats, stats;
    small_scene_drawn_whole(&s, &whole, &whole_stats);
    ck_assert_int_eq(whole_stats.primary_rays, 37 * 23);
    draw_on(&s, 3, &banded, &stats);
    ck_assert_int_eq(stats.primary_rays, whole_stats.primary_rays);
    ck_assert_int_eq(stats.shadow_rays, whole_stats.shadow_rays);
    ck_assert(memcmp(&stats, &whole_stats, sizeof stats) == 0);
    image_free(&banded);
    image_free(&whole);
    scene_free(&s);
}
END_TEST

Suite *ch09_speed_suite(void)
{
    Suite *s = suite_create("ch09 speed");
    TCase *threads = tcase_create("threads");
    tcase_add_checked_fixture(threads, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(threads, 120);
    tcase_add_test(threads, test_thread_count_does_not_change_the_image);
    tcase_add_test(threads, test_ties_come_out_alike_on_any_number_of_threads);
    tcase_add_test(threads, test_statistics_add_up_whatever_the_thread_count);
    tcase_add_test(threads, test_bad_thread_counts_are_usage_errors);
    tcase_add_test(threads, test_the_kd_trees_line_holds_no_bvh_build_time);
    tcase_add_threaded_test(threads,
                            test_bands_on_threads_draw_what_one_render_draws);
    tcase_add_threaded_test(threads,
                            test_the_threads_counts_add_up_to_one_renders);
    tcase_add_threaded_test(threads,
                            test_a_tall_image_on_four_threads_is_one_renders);
    suite_add_tcase(s, threads);
    return s;
}
