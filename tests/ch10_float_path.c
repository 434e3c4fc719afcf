/* ch10_float_path.c: the float path draws what the exact path draws
 * (chapter 10).
 *
 * A mesh whose leaves are decided in float alone (accelerator bvh-float)
 * finds float's hits, and its shadow rays meet their own triangles again
 * in float: offset by chapter 6's bound, which is sized for double, they
 * would find their own surface and leave lit points in shadow (acne).
 * Each test renders scenes with $CHAPTER_BIN twice, --accelerator bvh and
 * bvh-float, and compares what --stats counts and the pictures. The
 * thresholds are the promise of the chapter: the float path's shadow rays
 * blocked as often as the exact path's to within a thousandth, and at most
 * a thousandth of the pixels more than 2 codes apart (2 codes: what the
 * book's figure check allows a figure; the few pixels past it are rays
 * that float sends to another triangle near an edge). */
#include <dirent.h>
#include <png.h>

#include "test_util.h"

/* The shadow rays that a --stats report counts, cast and blocked. */
typedef struct {
    long long cast, blocked;
} shadow_count;

static shadow_count shadow_rays_of(const char *report)
{
    shadow_count n = {-1, -1};
    const char *line = strstr(report, "shadow rays ");
    ck_assert_msg(line != NULL, "no shadow rays in: %s", report);
    ck_assert_int_eq(sscanf(line, "shadow rays %lld (%lld blocked)", &n.cast,
                            &n.blocked), 2);
    return n;
}

/* Renders scene at size with --accelerator accelerator into tmpdir/out;
 * its exit status, its stderr in errors. */
static int render_with(const char *scene, const char *size,
                       const char *accelerator, const char *out,
                       char *errors, size_t length)
{
    char path[200]; /* tmp_path's buffer is reused */
    snprintf(path, sizeof path, "%s", tmp_path(out));
    const char *args[] = {scene,  "--size", size, "--accelerator", accelerator,
                          "--stats", "-o", path, NULL};
    return run_bin(args, errors, length);
}

/* tmpdir/name as 8-bit RGB, its width and height in *width, *height. */
static unsigned char *read_picture(const char *name, int *width, int *height)
{
    png_image info = {.version = PNG_IMAGE_VERSION};
    ck_assert(png_image_begin_read_from_file(&info, tmp_path(name)));
    info.format = PNG_FORMAT_RGB;
    unsigned char *rgb = malloc(PNG_IMAGE_SIZE(info));
    ck_assert_ptr_nonnull(rgb);
    ck_assert(png_image_finish_read(&info, NULL, rgb, 0, NULL));
    *width = (int)info.width, *height = (int)info.height;
    return rgb;
}

/* The pixels of tmpdir/a and tmpdir/b, of one size, whose codes differ by
 * more than 2 in some channel; their number of pixels in *total. */
static int pixels_apart(const char *a, const char *b, int *total)
{
    int w[2], h[2];
    unsigned char *p = read_picture(a, &w[0], &h[0]);
    unsigned char *q = read_picture(b, &w[1], &h[1]);
    ck_assert(w[0] == w[1] && h[0] == h[1]);
    int apart = 0;
    for (int k = 0; k < w[0] * h[0]; k++) {
        int far = 0;
        for (int c = 0; c < 3; c++)
            far |= abs(p[3 * k + c] - q[3 * k + c]) > 2;
        apart += far;
    }
    free(p), free(q);
    *total = w[0] * h[0];
    return apart;
}

START_TEST(test_float_shadows_are_blocked_as_often_as_exact_ones)
{
    /* Offset by double's bound, 21,951 of these 63,590 shadow rays were
     * blocked in float against 11,970 exact: rays from lit points that
     * found their own triangle again. */
    const char *scene = chapter_scene("ch10", "ch08-bunny.scene");
    char errors[4096];
    shadow_count n[2];
    const char *accelerators[2] = {"bvh", "bvh-float"};
    for (int k = 0; k < 2; k++) {
        ck_assert_msg(render_with(scene, "240x180", accelerators[k],
                                  "bunny.png", errors, sizeof errors) == 0,
                      "%s", errors);
        n[k] = shadow_rays_of(errors);
    }
    ck_assert_int_eq(n[0].cast, n[1].cast); /* the same camera hits */
    ck_assert_int_gt(n[0].blocked, 10000);  /* the bunny's shadows are there */
    ck_assert_msg(1000 * n[1].blocked <= 1001 * n[0].blocked &&
                      1000 * n[1].blocked >= 999 * n[0].blocked,
                  "blocked: %lld in float, %lld exact, of %lld", n[1].blocked,
                  n[0].blocked, n[0].cast);
}
END_TEST

/* "chNN" of the binary under test, for the scenes of its chapter. */
static const char *chapter_of_bin(void)
{
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert_ptr_nonnull(bin);
    const char *name = strrchr(bin, '/');
    return name != NULL ? name + 1 : bin;
}

START_TEST(test_the_float_path_draws_every_scene_as_the_exact_path)
{
    char folder[128], scene[400], errors[4096];
    snprintf(folder, sizeof folder, "%s",
             chapter_scene_folder(chapter_of_bin()));
    DIR *dir = opendir(folder);
    ck_assert_msg(dir != NULL, "no folder %s", folder);
    int scenes = 0, drawn = 0;
    for (struct dirent *e; (e = readdir(dir)) != NULL;) {
        const char *dot = strrchr(e->d_name, '.');
        if (dot == NULL || strcmp(dot, ".scene") != 0)
            continue;
        snprintf(scene, sizeof scene, "%s/%s", folder, e->d_name);
        scenes++;
        int exact = render_with(scene, "64x48", "bvh", "exact.png", errors,
                                sizeof errors);
        int fast = render_with(scene, "64x48", "bvh-float", "float.png",
                               errors, sizeof errors);
        ck_assert_msg(fast == exact, "%s: exit %d with bvh, %d with "
                      "bvh-float: %s", scene, exact, fast, errors);
        if (exact != 0)
            continue; /* a scene that refuses a BVH refuses both */
        drawn++;
        int total, apart = pixels_apart("exact.png", "float.png", &total);
        ck_assert_msg(1000 * apart <= total, "%s: %d of %d pixels more than "
                      "2 codes apart", scene, apart, total);
    }
    closedir(dir);
    ck_assert_int_ge(scenes, 11); /* chapter 10's scenes at least */
    ck_assert_int_ge(drawn, scenes - 1);
}
END_TEST

Suite *ch10_float_path_suite(void)
{
    Suite *s = suite_create("ch10 float path");
    TCase *renders = tcase_create("renders");
    tcase_add_checked_fixture(renders, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(renders, 300);
    tcase_add_slow_test(
        renders, test_float_shadows_are_blocked_as_often_as_exact_ones);
    tcase_add_slow_test(
        renders, test_the_float_path_draws_every_scene_as_the_exact_path);
    suite_add_tcase(s, renders);
    return s;
}
