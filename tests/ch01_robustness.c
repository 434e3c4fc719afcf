/* ch01_robustness.c: degenerate scenes and failed writes, for every chapter.
 *
 * Part of chapter 01's suites, so it runs against the program of every
 * chapter. A scene may use statements that an early chapter does not know:
 * that chapter must then reject it cleanly (status 1, a located error, no
 * output file). A chapter that accepts it must render it with every pixel
 * finite; image_set asserts that, so a NaN would abort the binary. */
#include <check.h>
#include <errno.h>
#include <math.h>
#include <png.h>
#include <string.h>

#include "image.h"
#include "render.h"
#include "scene.h"
#include "test_util.h"

/* Scenes where methods break: 9 x 7 pixels, so the centre ray is exact. */
static const char *const degenerate_scenes[] = {
    /* the eye on a sphere's surface */
    "image 9 7\nsphere center 0 0 1 radius 1\n",
    /* spheres far too small and far too large to model */
    "image 9 7\nsphere center 0 0 5 radius 1e-300\n",
    "image 9 7\nsphere center 0 0 5 radius 1e300\n",
    /* the smallest and largest allowed, the small one on the centre ray */
    "image 9 7\nsphere center 0 0 5 radius 1e-50\nsphere center 0 0 0 radius 1e50\n",
    /* a triangle with three equal corners, on the centre ray */
    "image 9 7\ntriangle a 0 0 5 b 0 0 5 c 0 0 5\n",
    /* a light exactly at the point the centre ray hits */
    "image 9 7\nsphere center 0 0 5 radius 1\nlight point position 0 0 4\n",
    /* the eye inside a sphere, lit from inside and outside */
    "image 9 7\nsphere center 0 0 0 radius 10\nlight point position 1 1 1\n"
    "light spot position 0 0 20 direction 0 0 -1 angle 179.999 exponent 0\n",
    /* the brightest lights and the most extreme tone map allowed */
    "image 9 7\ntonemap alpha 1e300 beta 1e-300\nsphere center 0 0 5 radius 1 color 1e6 1e6 1e6\n"
    "light point position 0 0 0 intensity 1e6 1e6 1e6 attenuation 1e-6 0 0\n",
    /* a nearly flat field of view and a nearly 180-degree one */
    "image 9 7\ncamera fov 179.999\nsphere center 0 0 5 radius 1\n",
    "image 9 7\ncamera fov 1e-10\nsphere center 0 0 5 radius 1\n",
};
#define N_SCENES (int)(sizeof degenerate_scenes / sizeof degenerate_scenes[0])

START_TEST(test_degenerate_scenes_render_finite_or_are_rejected)
{
    for (int k = 0; k < N_SCENES; k++) {
        char scene_path[192], out[192], errors[2048];
        snprintf(scene_path, sizeof scene_path, "%s", write_file("degenerate.scene",
                                                                 degenerate_scenes[k]));
        snprintf(out, sizeof out, "%s", tmp_path("out.png"));
        unlink(out);
        const char *args[] = {scene_path, "-o", out, NULL};
        int status = run_bin(args, errors, sizeof errors);
        ck_assert_msg(status == 0 || status == 1, "scene %d: status %d, stderr: %s", k, status,
                      errors);
        if (status == 1) {
            ck_assert_msg(strstr(errors, "degenerate.scene:") && strstr(errors, ": error: "),
                          "scene %d: no located error: %s", k, errors);
            ck_assert(!file_exists(out));
        } else {
            ck_assert(file_exists(out));
        }
    }
}
END_TEST

START_TEST(test_degenerate_scenes_have_only_finite_pixels)
{
    for (int k = 0; k < N_SCENES; k++) {
        scene s;
        scene_error err;
        if (parse_text(&s, degenerate_scenes[k], &err)) {
            image img;
            render_stats stats = {0};
            ck_assert(image_init(&img, s.cam.width, s.cam.height));
            render(&s, &img, &stats);
            for (int p = 0; p < img.width * img.height; p++)
                ck_assert_msg(isfinite(img.pixels[p].x) && isfinite(img.pixels[p].y) &&
                                  isfinite(img.pixels[p].z),
                              "scene %d, pixel %d", k, p);
            image_free(&img);
        }
        scene_free(&s);
    }
}
END_TEST

/* ------------------------------------------------------------ output safety */

/* The bytes of a file, or "" if it cannot be read. */
static size_t read_bytes(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, size, f) : 0;
    if (f)
        fclose(f);
    return n;
}

/* Renders a first picture to tmpdir/keep/picture.png and returns its size. */
static size_t first_picture(char *path, size_t path_size, char *bytes, size_t size)
{
    char folder[192], errors[1024];
    snprintf(folder, sizeof folder, "%s", tmp_path("keep"));
    ck_assert_int_eq(mkdir(folder, 0755), 0);
    snprintf(path, path_size, "%.160s/picture.png", folder); /* tmpdir is 24 characters */
    const char *args[] = {"-o", path, "--size", "160x120", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    size_t n = read_bytes(path, bytes, size);
    ck_assert(n > 8 && memcmp(bytes, "\x89PNG", 4) == 0);
    return n;
}

/* The picture is byte for byte what it was, and nothing else is beside it. */
static void expect_picture_kept(const char *path, const char *bytes, size_t n)
{
    static char now[65536];
    ck_assert_int_eq(read_bytes(path, now, sizeof now), n);
    ck_assert(memcmp(now, bytes, n) == 0);
    ck_assert_int_eq(count_entries(tmp_path("keep")), 1); /* no temporary left */
}

START_TEST(test_a_bad_scene_keeps_the_old_picture)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s", write_file("bad.scene", "camera fov 400\n"));
    const char *args[] = {scene_path, "-o", path, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert(strstr(errors, "bad.scene:1:12: error:") != NULL);
    expect_picture_kept(path, bytes, n);
}
END_TEST

static void copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
    ck_assert(in != NULL && out != NULL);
    char block[65536];
    size_t n;
    while ((n = fread(block, 1, sizeof block, in)) > 0)
        ck_assert_int_eq(fwrite(block, 1, n, out), n);
    fclose(in);
    ck_assert_int_eq(fclose(out), 0);
}

START_TEST(test_an_unwritable_folder_keeps_the_old_picture)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    /* Root ignores permissions, so as root the binary runs as nobody, who
     * may read but not write the folder; otherwise the folder is made read
     * only. Nobody may not reach the build folder, so a copy of the binary
     * in the (world-readable) test folder is run. */
    ck_assert_int_eq(chmod(tmpdir, 0755), 0);
    if (geteuid() != 0)
        ck_assert_int_eq(chmod(tmp_path("keep"), 0555), 0);
    char *original = strdup(getenv("CHAPTER_BIN"));
    char copy[192];
    snprintf(copy, sizeof copy, "%s", tmp_path("chapter-bin"));
    copy_file(original, copy);
    ck_assert_int_eq(chmod(copy, 0755), 0);
    setenv("CHAPTER_BIN", copy, 1);
    const char *args[] = {"-o", path, "--size", "160x120", NULL};
    int status = run_bin_limited(args, errors, sizeof errors, (run_limits){.as_nobody = true});
    setenv("CHAPTER_BIN", original, 1); /* for the tests after this one */
    free(original);
    unlink(copy);
    ck_assert_int_eq(status, 1);
    ck_assert_msg(strstr(errors, "error: cannot create") != NULL, "stderr: %s", errors);
    chmod(tmp_path("keep"), 0755);
    expect_picture_kept(path, bytes, n);
}
END_TEST

START_TEST(test_a_full_disk_keeps_the_old_picture)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    /* Files may not grow past 256 bytes (the new PNG has over 1900): it cannot
     * be written whole. The limit also cuts stderr there, after the message. */
    const char *args[] = {"-o", path, "--size", "160x120", NULL};
    ck_assert_int_eq(
        run_bin_limited(args, errors, sizeof errors, (run_limits){.max_file_bytes = 256}), 1);
    ck_assert_msg(strstr(errors, "error: cannot write") != NULL, "stderr: %s", errors);
    expect_picture_kept(path, bytes, n);
}
END_TEST

START_TEST(test_writing_to_dev_full_is_reported)
{
    image img;
    ck_assert(image_init(&img, 40, 30));
    FILE *full = fopen("/dev/full", "wb");
    ck_assert_ptr_nonnull(full);
    char why[256] = "";
    bool ok = image_write_png_stream(&img, full, why, sizeof why);
    fclose(full);
    ck_assert(!ok);
    ck_assert_msg(strstr(why, strerror(ENOSPC)) != NULL, "why: %s", why);
    image_free(&img);
}
END_TEST

Suite *ch01_robustness_suite(void)
{
    Suite *s = suite_create("ch01 robustness");
    TCase *scenes = tcase_create("edge cases");
    tcase_add_checked_fixture(scenes, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(scenes, 120);
    tcase_add_test(scenes, test_degenerate_scenes_render_finite_or_are_rejected);
    tcase_add_test(scenes, test_degenerate_scenes_have_only_finite_pixels);
    suite_add_tcase(s, scenes);

    TCase *output = tcase_create("output safety");
    tcase_add_checked_fixture(output, make_tmpdir, remove_tmpdir);
    tcase_add_test(output, test_a_bad_scene_keeps_the_old_picture);
    tcase_add_test(output, test_an_unwritable_folder_keeps_the_old_picture);
    tcase_add_test(output, test_a_full_disk_keeps_the_old_picture);
    tcase_add_test(output, test_writing_to_dev_full_is_reported);
    suite_add_tcase(s, output);
    return s;
}
