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

#include "test_util.h"

/* The scenes of chapter 8's tie test (tests/ch08_kdtree.c): cones whose
 * apexes lie exactly on pixel rays, as an OBJ mesh and as lone triangles. */
void tie_scene_texts(char *obj, size_t obj_size, char *lone, size_t lone_size);

/* Writes a scene with the teapot, and a link to meshes/ beside it. */
static const char *teapot_scene(void)
{
    char target[4096];
    ck_assert_ptr_nonnull(getcwd(target, sizeof target - 16));
    strcat(target, "/meshes");
    ck_assert_int_eq(symlink(target, tmp_path("meshes")), 0);
    return write_file("teapot.scene",
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
static char *render_on(const char *scene_path, const char *threads, size_t *length)
{
    char errors[4096];
    const char *out = tmp_path("threads.png");
    const char *args[] = {scene_path, "--threads", threads, "-o", out, NULL};
    ck_assert_msg(run_bin(args, errors, sizeof errors) == 0, "%s", errors);
    return read_all(out, length);
}

/* scene_path drawn on 1 thread and on each of others[0..n): the same bytes. */
static void expect_same_on_threads(const char *scene_path, const char *const *others, int n)
{
    size_t n1, nk;
    char *one = render_on(scene_path, "1", &n1);
    for (int k = 0; k < n; k++) {
        char *other = render_on(scene_path, others[k], &nk);
        ck_assert_msg(nk == n1 && memcmp(one, other, n1) == 0, "%s: --threads %s differs",
                      scene_path, others[k]);
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
             write_file("mesh.scene", "image 48 36\nmesh file fans.obj color 0.9 0.7 0.4\n"));
    snprintf(lone_path, sizeof lone_path, "%s", write_file("lone.scene", lone));
    const char *others[] = {"3"};
    expect_same_on_threads(mesh_path, others, 1);
    expect_same_on_threads(lone_path, others, 1);
}
END_TEST

/* The counts --stats prints (no times, no rates: "time", "rays/s") for
 * --threads n. */
static void stats_counts(const char *scene_path, const char *n, char *counts, size_t size)
{
    char errors[4096];
    const char *args[] = {scene_path, "--threads", n, "--stats", "-o", tmp_path("s.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    counts[0] = '\0';
    for (char *line = strtok(errors, "\n"); line; line = strtok(NULL, "\n"))
        if (!strstr(line, "time") && !strstr(line, "rays/s") && !strstr(line, "built in"))
            strncat(counts, line, size - strlen(counts) - 2), strcat(counts, "\n");
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

START_TEST(test_bad_thread_counts_are_usage_errors)
{
    const char *bad[] = {"0", "-1", "abc", "2x", "257", "", "1e3"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        char errors[1024];
        const char *out = tmp_path("never.png");
        const char *args[] = {"--threads", bad[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "--threads expects a whole number") != NULL, "%s", errors);
        ck_assert(!file_exists(out));
    }
    char errors[1024];
    const char *args[] = {"--threads", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_ptr_nonnull(strstr(errors, "needs a value"));
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
    suite_add_tcase(s, threads);
    return s;
}
