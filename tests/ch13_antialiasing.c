/* ch13_antialiasing.c: more rays than one a pixel (chapter 13).
 *
 * Where the patterns put their rays (inside the pixel, one in each cell,
 * the same on every run), what the tent filter's rays add up to, what
 * Whitted's adaptive scheme costs on a flat image and along an edge, that
 * the default is chapter 12's picture byte for byte, that threads change
 * nothing, the two failures of the chapter, and bad pixel statements. */
#include <check.h>
#include <pthread.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "antialias.h"
#include "image.h"
#include "pixel_statement.h"
#include "render.h"
#include "scene_file.h"
#include "test_util.h"

/* Parses text into s, which the caller frees; the test fails on an error. */
static void parse_ok(scene *s, const char *text)
{
    scene_error err;
    ck_assert_msg(parse_named(s, text, strlen(text), "t.scene", &err),
                  "%d:%d: %s", err.line, err.col, err.message);
}

/* Renders s on `threads` threads into img. */
static render_stats render_scene(const scene *s, image *img, int threads)
{
    ck_assert(image_init(img, s->cam.width, s->cam.height));
    render_stats st = {0};
    render_in_bands(s, img, &(render_settings){.threads = threads}, &st);
    return st;
}

/* Renders s into img in one call of render: one band, the whole image. */
static render_stats render_whole(const scene *s, image *img)
{
    ck_assert(image_init(img, s->cam.width, s->cam.height));
    render_stats st = {0};
    render(s, img, &st);
    return st;
}

START_TEST(test_samples_lie_in_their_pixel_one_in_each_cell)
{
    for (int p = PIXEL_GRID; p <= PIXEL_JITTERED; p++) {
        pixel_sampling ps = {.pattern = (pixel_pattern)p, .side = 4};
        int cells[4][4] = {{0}};
        for (int k = 0; k < 16; k++) {
            double u, v;
            pixel_sample_at(&ps, 7, 3, k, &u, &v);
            ck_assert(u >= 7 && u < 8 && v >= 3 && v < 4);
            cells[(int)((v - 3) * 4)][(int)((u - 7) * 4)]++;
        }
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                ck_assert_msg(cells[a][b] == 1, "pattern %d, cell %d %d: %d",
                              p, a, b, cells[a][b]);
    }
}
END_TEST

START_TEST(test_jittered_samples_repeat_and_differ_between_pixels)
{
    pixel_sampling ps = {.pattern = PIXEL_JITTERED, .side = 4};
    int same_place = 0;
    for (int k = 0; k < 16; k++) {
        double u1, v1, u2, v2, u3, v3;
        pixel_sample_at(&ps, 7, 3, k, &u1, &v1);
        pixel_sample_at(&ps, 7, 3, k, &u2, &v2);
        pixel_sample_at(&ps, 8, 3, k, &u3, &v3);
        ck_assert(u1 == u2 && v1 == v2); /* the same pixel: the same rays */
        same_place += u3 - 1 == u1 || v3 == v1;
    }
    ck_assert_int_eq(same_place, 0); /* the neighbour's are elsewhere */
    /* A sample's x and y are not one number (its rays would all lie on
     * the cells' diagonals): unrelated numbers in [0, 1) agree to within
     * 1/1000 a thousandth of the time, a few of 4096 pairs. */
    int close = 0;
    for (int k = 0; k < 4096; k++)
        close += fabs(pixel_random(k % 64, k / 64, k % 16, 0) -
                      pixel_random(k % 64, k / 64, k % 16, 1)) < 1e-3;
    ck_assert_msg(close < 40,
                  "%d of 4096 samples have x and y within 1/1000: the axis "
                  "must change the number as much as the sample does",
                  close);
    /* and the numbers spread over [0, 1): their mean is 1/2 +- 0.01 */
    double sum = 0;
    for (int k = 0; k < 10000; k++) {
        double x = pixel_random(k % 100, k / 100, k, 0);
        ck_assert(x >= 0 && x < 1);
        sum += x;
    }
    ck_assert_double_eq_tol(sum / 10000, 0.5, 0.01); /* 3.5 sigma */
}
END_TEST

START_TEST(test_a_jittered_render_is_the_same_on_any_thread_count)
{
    /* Every pixel's rays depend on the pixel alone, not on the thread that
     * draws it, nor on what other threads draw meanwhile: the jittered
     * picture of one thread and of three is the same, bit for bit (and
     * ThreadSanitizer sees any state the threads share). */
    scene s;
    image one, three;
    /* 480 rows: 60 bands, enough that every thread takes some */
    parse_ok(&s, "image 64 480\n"
                 "sphere center 0 0 5 radius 1 color 0.9 0.3 0.2\n"
                 "pixel samples 4 pattern jittered\n");
    render_scene(&s, &one, 1);
    render_scene(&s, &three, 3);
    size_t n = (size_t)one.width * one.height;
    ck_assert_msg(memcmp(one.pixels, three.pixels, n * sizeof(vec3)) == 0,
                  "three threads draw another jittered picture than one");
    image_free(&one);
    image_free(&three);
    scene_free(&s);
}
END_TEST

START_TEST(test_tent_samples_fall_as_the_tent_weighs)
{
    /* the tent's mass within half a pixel of the centre is 3/4 an axis:
     * of 16 x 16 stratified rays, 12 x 12 = 144 inside the pixel */
    pixel_sampling ps = {.pattern = PIXEL_JITTERED, .side = 16,
                         .filter = FILTER_TENT};
    int inside = 0;
    for (int k = 0; k < 256; k++) {
        double u, v;
        pixel_sample_at(&ps, 5, 6, k, &u, &v);
        ck_assert(fabs(u - 5.5) < 1 && fabs(v - 6.5) < 1);
        inside += fabs(u - 5.5) < 0.5 && fabs(v - 6.5) < 0.5;
    }
    ck_assert_int_eq(inside, 144);
    /* the warp is the tent's inverse integral: F(-1/2) = 1/8 */
    ck_assert_double_eq_tol(tent_warp(0.125), -0.5, 1e-15);
    ck_assert_double_eq_tol(tent_warp(0.875), 0.5, 1e-15);
}
END_TEST

/* A scene of nothing but a solid background, with these pixel settings. */
static void flat_scene(scene *s, const char *settings)
{
    char text[256];
    snprintf(text, sizeof text,
             "image 40 30\nbackground 0.3 0.5 0.7\npixel %s\n",
             settings);
    parse_ok(s, text);
}

START_TEST(test_a_flat_image_costs_one_ray_per_corner)
{
    /* threads 0: one call of render, one band: (W + 1)(H + 1) corners;
     * in bands of 3 rows (8 bands at least), each band traces its rows
     * of corners, and the row between two bands is traced by both:
     * (W + 1)(H + b) */
    for (int threads = 0; threads <= 3; threads += threads == 0 ? 1 : 2) {
        scene s;
        image img;
        flat_scene(&s, "pattern adaptive threshold 0 depth 4");
        render_stats st = threads == 0 ? render_whole(&s, &img)
                                       : render_scene(&s, &img, threads);
        int rows = 30 / BAND_ROWS; /* 30 rows: fewer than 8 bands of 8 */
        int bands = threads == 0 ? 1 : (30 + rows - 1) / rows;
        ck_assert_int_eq(st.primary_rays, 41 * (30 + bands));
        ck_assert_int_eq(st.pixel_depths[0], 40 * 30);
        for (int k = 0; k < 40 * 30; k++) /* four equal corners: exact */
            ck_assert(img.pixels[k].x == 0.3 && img.pixels[k].z == 0.7);
        image_free(&img);
        scene_free(&s);
    }
}
END_TEST

START_TEST(test_filter_weights_sum_to_one)
{
    const char *settings[] = {"samples 9 pattern grid",
                              "samples 16 pattern jittered",
                              "samples 25 pattern jittered filter tent",
                              "samples 49 pattern grid filter tent"};
    for (int k = 0; k < 4; k++) {
        scene s;
        image img;
        flat_scene(&s, settings[k]);
        render_scene(&s, &img, 1);
        /* 49 additions and a product, each rounding by half an ulp */
        double tol = 50 * DBL_EPSILON;
        for (int p = 0; p < 40 * 30; p++)
            ck_assert_msg(fabs(img.pixels[p].y - 0.5) <= tol * 0.5,
                          "%s: %.17g", settings[k], img.pixels[p].y);
        image_free(&img);
        scene_free(&s);
    }
}
END_TEST

/* A white triangle whose left edge is the vertical line u = 20.3 of a 40
 * x 30 image (fov 90: a pixel is 0.05 of the plane z = 1, whose left edge
 * is at x = -1), on black. */
static const char EDGE_SCENE[] =
    "camera fov 90\nimage 40 30\nbackground 0 0 0\n"
    "material default ambient 0.3 diffuse 0.6 specular 0\n"
    "triangle a 0.075 -100 5  b 100 0 5  c 0.075 100 5 color 1 1 1\n"
    "light directional direction 0 0 1 intensity 1 1 1\n"
    "pixel pattern adaptive threshold 0 depth 3\n";

START_TEST(test_an_edge_is_divided_and_a_flat_region_is_not)
{
    scene s;
    image img;
    parse_ok(&s, EDGE_SCENE);
    render_stats st = render_whole(&s, &img);
    /* the 30 pixels of column 20 to depth 3, at 2^(3+2) - 4 + 3 = 31 rays
     * each besides the corners (the chapter's sum); no other pixel */
    ck_assert_int_eq(st.pixel_depths[3], 30);
    ck_assert_int_eq(st.pixel_depths[0], 40 * 30 - 30);
    ck_assert_int_eq(st.primary_rays, 41 * 31 + 30 * 31);
    ck_assert_int_eq(st.pixel_rays[32], 30); /* 31 and the corners' share */
    /* the edge's pixel is partly white: 0.7 of it lies right of u = 20.3 */
    double white = img.pixels[15 * 40 + 21].x;
    double edge = img.pixels[15 * 40 + 20].x / white;
    ck_assert_double_eq_tol(edge, 0.7, 1.0 / 16); /* the finest step */
    image_free(&img);
    scene_free(&s);
}
END_TEST

/* One render of a scene on a thread of its own. */
typedef struct {
    const scene *s;
    image img;
    render_stats st;
} concurrent_render;

static void *render_concurrently(void *job)
{
    concurrent_render *r = job;
    render_in_bands(r->s, &r->img, &(render_settings){.threads = 2}, &r->st);
    return NULL;
}

static void expect_same_render(const image *a, const render_stats *sa,
                               const image *b, const render_stats *sb)
{
    size_t bytes = (size_t)a->width * a->height * sizeof a->pixels[0];
    ck_assert(memcmp(a->pixels, b->pixels, bytes) == 0);
    ck_assert_int_eq(sa->primary_rays, sb->primary_rays);
    ck_assert(memcmp(sa->pixel_rays, sb->pixel_rays, sizeof sa->pixel_rays) ==
              0);
}

START_TEST(test_a_scene_is_left_as_it_was_by_its_renders)
{
    /* The adaptive pattern's corners belong to the render: a second
     * render of the scene, and two at once, trace and draw what the first
     * did (were the corners kept in the scene, the second would find
     * them traced, or half traced by the other). */
    scene s;
    parse_ok(&s, EDGE_SCENE);
    const scene *cs = &s;
    image first, again;
    render_stats st_first = render_scene(cs, &first, 2);
    render_stats st_again = render_scene(cs, &again, 2);
    expect_same_render(&first, &st_first, &again, &st_again);
    concurrent_render r[2] = {{.s = cs}, {.s = cs}};
    pthread_t thread[2];
    for (int k = 0; k < 2; k++) {
        ck_assert(image_init(&r[k].img, s.cam.width, s.cam.height));
        ck_assert_int_eq(
            pthread_create(&thread[k], NULL, render_concurrently, &r[k]), 0);
    }
    for (int k = 0; k < 2; k++) {
        ck_assert_int_eq(pthread_join(thread[k], NULL), 0);
        expect_same_render(&first, &st_first, &r[k].img, &r[k].st);
        image_free(&r[k].img);
    }
    image_free(&first), image_free(&again);
    scene_free(&s);
}
END_TEST

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

/* What bin (NULL: $CHAPTER_BIN) draws with args (NULL-ended, at most 8)
 * followed by -o OUT. */
static char *draw(const char *bin, const char *const *args, size_t *length)
{
    char errors[4096], saved[256];
    const char *all[12];
    int n = 0;
    for (; args[n] != NULL; n++)
        all[n] = args[n];
    all[n] = "-o", all[n + 1] = tmp_path("drawn.png"), all[n + 2] = NULL;
    snprintf(saved, sizeof saved, "%s", getenv("CHAPTER_BIN"));
    if (bin != NULL)
        setenv("CHAPTER_BIN", bin, 1);
    int status = run_bin(all, errors, sizeof errors);
    setenv("CHAPTER_BIN", saved, 1);
    ck_assert_msg(status == 0, "%s", errors);
    return read_all(tmp_path("drawn.png"), length);
}

/* $CHAPTER_BIN with its chapter's number lowered by one. */
static const char *previous_bin(void)
{
    static char path[256];
    snprintf(path, sizeof path, "%s", getenv("CHAPTER_BIN"));
    char *number = strrchr(path, 'h'); /* ...chNN */
    ck_assert(number != NULL && strlen(number) == 3);
    unsigned n = (unsigned)atoi(number + 1) - 1;
    snprintf(number + 1, 3, "%02u", n % 100); /* two digits, as chNN has */
    return path;
}

static void expect_same(char *a, size_t na, char *b, size_t nb,
                        const char *what)
{
    ck_assert_msg(na == nb && memcmp(a, b, na) == 0, "%s differ", what);
    free(a), free(b);
}

/* Spheres, a triangle and a checker: edges of every kind, small. */
static const char *small_scene(const char *pixel_line)
{
    char text[1024];
    snprintf(text, sizeof text,
             "image 64 48\n%s\n"
             "sphere center 0 -1001 6 radius 1000 checker 0.2 0.2 0.2 "
             "tile 0.5\n"
             "sphere center 0.3 0 5 radius 0.8 color 0.9 0.3 0.2\n"
             "triangle a -2 -1 7  b -0.5 1.5 7  c -1 -1 6 color 0.2 0.4 1\n"
             "light point position -3 3 1 intensity 1 1 1\n",
             pixel_line);
    return write_file("small.scene", text);
}

START_TEST(test_the_default_is_the_previous_chapters_picture)
{
    char path[192];
    size_t n_before, n_now, n;
    snprintf(path, sizeof path, "%s", small_scene("# no pixel statement"));
    const char *args[] = {path, NULL};
    char *before = draw(previous_bin(), args, &n_before);
    char *now = draw(NULL, args, &n_now);
    expect_same(before, n_before, now, n_now,
                "this program and the previous chapter's");
    const char *centre[] = {path, "--pixel", "pattern center", NULL};
    before = draw(previous_bin(), args, &n_before);
    now = draw(NULL, centre, &n);
    expect_same(before, n_before, now, n, "--pixel center");
}
END_TEST

START_TEST(test_thread_counts_give_the_same_image)
{
    const char *settings[] = {"pixel samples 16 pattern jittered",
                              "pixel pattern adaptive threshold 0.02",
                              "pixel samples 9 pattern grid filter tent"};
    for (int k = 0; k < 3; k++) {
        char path[192];
        size_t n1, n3;
        snprintf(path, sizeof path, "%s", small_scene(settings[k]));
        const char *one[] = {path, "--threads", "1", NULL};
        const char *three[] = {path, "--threads", "3", NULL};
        char *a = draw(NULL, one, &n1), *b = draw(NULL, three, &n3);
        expect_same(a, n1, b, n3, settings[k]);
    }
}
END_TEST

START_TEST(test_stats_report_rays_per_pixel_and_depths)
{
    /* the edge scene, 30 rows in 10 bands of 3 (a small image: 8 bands at
     * least), whose 40 rows of corners are 41 rays each: 41 x 40 + 30 x 31
     * = 2570 rays. Each pixel owns one corner, and the 30 on the edge 31
     * rays more: (1200 + 30 x 31) / 1200 = 1.775 rays a pixel, the edge's
     * 31 and a corner the largest, and 2570 - 2130 = 440 corners no pixel
     * owns; 30 of 1200 pixels (2.5%) at depth 3, the rest at 0 */
    char errors[4096], path[192];
    snprintf(path, sizeof path, "%s", write_file("edge.scene", EDGE_SCENE));
    const char *args[] = {path, "--stats", "-o", tmp_path("e.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, "rays per pixel     1.77 mean, 32 largest, "
                                 "and 440 at corners no pixel owns") ||
                      strstr(errors, "rays per pixel     1.78 mean, 32 "
                                     "largest, and 440 at corners no pixel "
                                     "owns"),
                  "%s", errors);
    ck_assert_msg(strstr(errors, "pixels by depth    0       1170  97.5%"),
                  "%s", errors);
    ck_assert_msg(strstr(errors, "                   3         30   2.5%"),
                  "%s", errors);
}
END_TEST

/* A sphere of 0.4 pixel across at the centre of pixel (10, 7) of a 20 x
 * 15 image: between the corners of its pixel. */
static void small_sphere_scene(scene *s, int min_depth)
{
    scene probe;
    scene_init(&probe);
    probe.cam.width = 20, probe.cam.height = 15;
    vec3 c = vec3_scale(camera_ray(&probe.cam, 10, 7).dir, 10);
    double across = 10 * camera_pixel_size(&probe.cam); /* a pixel at 10 */
    scene_free(&probe);
    char text[512];
    snprintf(text, sizeof text,
             "image 20 15\nbackground 0.1 0.1 0.1\n"
             "sphere center %.17g %.17g %.17g radius %.17g color 1 1 1\n"
             "pixel pattern adaptive min_depth %d\n",
             c.x, c.y, c.z, 0.2 * across, min_depth);
    parse_ok(s, text);
}

START_TEST(test_a_sphere_between_corners_is_missed_without_a_minimum_depth)
{
    for (int min_depth = 0; min_depth <= 1; min_depth++) {
        scene s;
        image img;
        small_sphere_scene(&s, min_depth);
        render_scene(&s, &img, 1);
        vec3 c = img.pixels[7 * 20 + 10];
        bool missed = c.x == 0.1 && c.y == 0.1 && c.z == 0.1;
        ck_assert_msg(missed == (min_depth == 0), "min_depth %d: %s",
                      min_depth, missed ? "missed" : "found");
        image_free(&img);
        scene_free(&s);
    }
}
END_TEST

/* The spacing, in pixels, of the coarsest division of a pixel (into
 * 2^d x 2^d squares, d = 0 to depth) that has point (a, b) of the finest,
 * 2^depth steps a side, for a corner. */
static double spacing_of(int a, int b, int depth)
{
    int n = 1 << depth;
    for (int d = 0; d < depth; d++) {
        int step = n >> d; /* finest steps in a square of depth d */
        if (a % step == 0 && b % step == 0)
            return 1.0 / (1 << d);
    }
    return 1.0 / n;
}

START_TEST(test_jittered_points_are_shared_and_stay_near_their_place)
{
    pixel_sampling grid = {.pattern = PIXEL_ADAPTIVE, .depth = 3};
    pixel_sampling jittered = grid;
    jittered.jittered_corners = true;
    double widest = 0; /* the largest move, in halves of the spacing */
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    double u, v, u0, v0, un, vn;
                    pixel_point_at(&grid, i, j, a, b, &u0, &v0);
                    ck_assert(u0 == i + a / 8.0 && v0 == j + b / 8.0);
                    pixel_point_at(&jittered, i, j, a, b, &u, &v);
                    double half = spacing_of(a, b, 3) / 2;
                    ck_assert_msg(fabs(u - u0) < half && fabs(v - v0) < half,
                                  "(%d, %d) of (%d, %d) moved too far", a, b,
                                  i, j);
                    widest = fmax(widest, fmax(fabs(u - u0), fabs(v - v0)) /
                                              half);
                    if (a == 8) { /* the right neighbour's left side */
                        pixel_point_at(&jittered, i + 1, j, 0, b, &un, &vn);
                        ck_assert(un == u && vn == v);
                    }
                    if (b == 8) { /* the lower neighbour's top */
                        pixel_point_at(&jittered, i, j + 1, a, 0, &un, &vn);
                        ck_assert(un == u && vn == v);
                    }
                }
    ck_assert_msg(widest > 0.9, "the points keep to %.2f of their room",
                  widest);
}
END_TEST

/* A sphere of 0.4 pixel across at the centre of every pixel of a 20 x 15
 * image: a pattern with the period of the corners, all of which miss it;
 * the adaptive pattern's corners on the grid or jittered. */
static void spheres_at_every_centre(scene *s, bool jittered)
{
    scene probe;
    scene_init(&probe);
    probe.cam.width = 20, probe.cam.height = 15;
    double across = 10 * camera_pixel_size(&probe.cam); /* a pixel at 10 */
    size_t size = 20 * 15 * 160 + 256, used = 0;
    char *text = malloc(size);
    ck_assert(text != NULL);
    used += (size_t)snprintf(text, size,
                             "image 20 15\nbackground 0.1 0.1 0.1\n"
                             "pixel pattern adaptive corners %s\n",
                             jittered ? "jittered" : "grid");
    for (int j = 0; j < 15; j++)
        for (int i = 0; i < 20; i++) {
            vec3 c = vec3_scale(camera_ray(&probe.cam, i, j).dir, 10);
            used += (size_t)snprintf(text + used, size - used,
                                     "sphere center %.17g %.17g %.17g "
                                     "radius %.17g color 1 1 1\n",
                                     c.x, c.y, c.z, 0.2 * across);
            ck_assert(used < size);
        }
    scene_free(&probe);
    parse_ok(s, text);
    free(text);
}

START_TEST(test_jittered_corners_see_a_pattern_the_grid_corners_alias_away)
{
    for (int jittered = 0; jittered <= 1; jittered++) {
        scene s;
        image img;
        spheres_at_every_centre(&s, jittered);
        render_scene(&s, &img, 1);
        int seen = 0; /* pixels where some sphere shows */
        for (int k = 0; k < 20 * 15; k++)
            seen += img.pixels[k].x != 0.1;
        /* on the grid, no corner meets a sphere, and no pixel is divided;
         * a corner jittered by up to half a pixel meets one an eighth of
         * the time, and then its four pixels are divided */
        if (jittered)
            ck_assert_msg(seen > 20 * 15 / 4, "%d pixels of 300", seen);
        else
            ck_assert_int_eq(seen, 0);
        image_free(&img);
        scene_free(&s);
    }
}
END_TEST

/* The sRGB encodings of the four levels below, from the standard's
 * formula (IEC 61966-2-1), to 17 digits: a table, so that the test holds
 * no encoder of its own. */
#define SRGB_OF_0_02 0.15170371931624205
#define SRGB_OF_0_04 0.22091636254849623
#define SRGB_OF_0_80 0.90633175334405940
#define SRGB_OF_0_86 0.93574102693368210

START_TEST(test_dark_edges_differ_in_srgb_not_in_linear_light)
{
    vec3 dark = {0.02, 0.02, 0.02}, darker = {0.04, 0.04, 0.04};
    vec3 c[4] = {dark, dark, darker, darker};
    /* 0.02 of linear light apart, but 0.069 apart on the display */
    ck_assert(SRGB_OF_0_04 - SRGB_OF_0_02 > 0.05);
    pixel_sampling ps = {.threshold = 0.05};
    ck_assert(pixel_corners_differ(&ps, c));
    ps.linear = true;
    ck_assert(!pixel_corners_differ(&ps, c));
    /* and in the light, where the display compresses: the other way */
    vec3 bright = {0.8, 0.8, 0.8}, brighter = {0.86, 0.86, 0.86};
    vec3 d[4] = {bright, brighter, bright, brighter};
    ck_assert(SRGB_OF_0_86 - SRGB_OF_0_80 < 0.05);
    ck_assert(pixel_corners_differ(&ps, d));
    ps.linear = false;
    ck_assert(!pixel_corners_differ(&ps, d));
}
END_TEST

/* A bad statement: the text, the word the error points at (on the last
 * line), and a piece of the message. */
typedef struct {
    const char *text, *at, *says;
} bad_case;

static const bad_case BAD[] = {
    {"pixel samples 0 pattern grid", "0", "from 1 to 256"},
    {"pixel samples -4 pattern grid", "-4", "from 1 to 256"},
    {"pixel samples 2.5 pattern grid", "2.5", "whole number"},
    {"pixel samples 1000 pattern grid", "1000", "from 1 to 256"},
    {"pixel samples 12 pattern grid", "12", "square number"},
    {"pixel pattern adaptive threshold nan", "nan", "threshold"},
    {"pixel pattern adaptive threshold -0.1", "-0.1", "from 0 to 1"},
    {"pixel pattern adaptive depth 0", "0", "depth"},
    {"pixel pattern adaptive depth 9", "9", "depth"},
    {"pixel pattern adaptive depth 2.5", "2.5", "whole number"},
    {"pixel pattern adaptive min_depth 3 depth 2", "min_depth",
     "no deeper"},
    {"pixel pattern grid pattern jittered", "pattern jittered", "twice"},
    {"pixel pattern spiral", "spiral", "expected a pattern"},
    {"pixel pattern grid sample 4", "sample 4", "expected a pixel setting"},
    {"pixel pattern grid threshold 0.1", "threshold", "adaptive"},
    {"pixel pattern adaptive samples 16", "samples", "grid and jittered"},
    {"pixel samples 16", "samples", "grid and jittered"},
    {"pixel pattern adaptive filter tent", "filter", "grid and jittered"},
    {"pixel pattern grid filter gauss", "gauss", "expected a filter"},
    {"pixel heatmap 0", "0", "number of rays"},
    {"pixel pattern adaptive corners random", "random", "expected corners"},
    {"pixel pattern jittered corners jittered", "corners", "adaptive"},
    {"pixel pattern grid\npixel pattern jittered", "pixel",
     "second pixel statement"},
};

START_TEST(test_bad_pixel_statements_are_located)
{
    for (size_t k = 0; k < sizeof BAD / sizeof BAD[0]; k++) {
        scene s;
        scene_error err;
        const char *text = BAD[k].text, *last = strrchr(text, '\n');
        last = last ? last + 1 : text;
        int line = last == text ? 1 : 2;
        int col = (int)(strstr(last, BAD[k].at) - last) + 1;
        ck_assert_msg(!parse_named(&s, text, strlen(text), "t", &err),
                      "accepted: %s", text);
        ck_assert_msg(err.line == line && err.col == col &&
                          strstr(err.message, BAD[k].says) != NULL,
                      "%s: %d:%d: %s", text, err.line, err.col, err.message);
        scene_free(&s);
    }
}
END_TEST

START_TEST(test_a_budget_passed_is_an_error)
{
    const char *texts[] = {"image 16384 1024\n"
                           "pixel samples 256 pattern jittered\n",
                           "pixel pattern adaptive depth 4\n"
                           "image 4096 4096\n"};
    int lines[] = {2, 1};
    for (int k = 0; k < 2; k++) {
        scene s;
        scene_error err;
        ck_assert(!parse_named(&s, texts[k], strlen(texts[k]), "t", &err));
        ck_assert_msg(err.line == lines[k] &&
                          strstr(err.message, "budget") != NULL,
                      "%d: %s", err.line, err.message);
        scene_free(&s);
    }
}
END_TEST

/* 10 x 6 flat pixels on three threads: six bands of one row, not one of
 * six, each tracing its two rows of corners. */
START_TEST(test_a_small_image_is_cut_into_short_bands)
{
    scene s;
    image img;
    parse_ok(&s, "image 10 6\nbackground 0.3 0.5 0.7\n"
                 "pixel pattern adaptive threshold 0 depth 4\n");
    render_stats st = render_scene(&s, &img, 3);
    ck_assert_int_eq(st.primary_rays, 11 * (6 + 6));
    image_free(&img);
    scene_free(&s);
}
END_TEST

START_TEST(test_an_image_shares_its_ray_budget_among_its_trees)
{
    scene s;
    parse_ok(&s, "image 64 48\nsphere center 0 0 5 radius 1\n");
    ck_assert_int_eq(s.ray_budget, (1LL << 36) / (64 * 48) - 1);
    ck_assert(s.ray_budget > 65536); /* chapter 6's is the less */
    scene_free(&s);
    parse_ok(&s, "image 2048 2048\npixel pattern adaptive\n"
                 "sphere center 0 0 5 radius 1\n");
    long long worst = pixel_worst_rays(&s.pixels, 2048, 2048);
    long long share = (1LL << 36) / worst - 1; /* rays besides the primary */
    ck_assert(share < 65536);
    ck_assert_int_eq(s.ray_budget, share);
    scene_free(&s);
    /* a billion primary rays leave 63 rays each: fewer than the 100
     * shadow rays of their own hits */
    const char *text = "image 4096 4096\n"
                       "pixel samples 64 pattern grid\n"
                       "light area position 0 5 0 direction 0 -1 0 "
                       "radius 1 samples 100\n"
                       "sphere center 0 0 5 radius 1\n";
    scene_error err;
    ck_assert(!parse_named(&s, text, strlen(text), "t", &err));
    ck_assert_msg(err.line == 2 && strstr(err.message, "rays an image"),
                  "%d: %s", err.line, err.message);
    scene_free(&s);
}
END_TEST

/* Glass spheres around the eye with no cutoff: every tree would run to
 * chapter 6's budget; with a share of 40 rays, the image casts at most 41
 * rays a primary ray, shadow rays counted. */
START_TEST(test_a_tree_keeps_to_its_share_of_the_image)
{
    scene s;
    image img;
    parse_ok(&s, "image 4 3\nrecursion depth 100 cutoff 0\n"
                 "material g ambient 0 diffuse 0.5 specular 0 "
                 "transparency 1 ior 1.5\n"
                 "light area position 0 0 0 direction 0 0 1 radius 1 "
                 "samples 4\n"
                 "sphere center 0 0 0 radius 10 material g\n"
                 "sphere center 0 0 0 radius 20 material g\n");
    s.ray_budget = 40; /* lowered for the test */
    render_stats st = render_scene(&s, &img, 1);
    long long rays = st.primary_rays + st.shadow_rays + st.reflection_rays +
                     st.refraction_rays;
    ck_assert_msg(rays <= st.primary_rays * 41, "%lld rays for %lld", rays,
                  st.primary_rays);
    ck_assert_int_gt(st.ray_trees_cut, 0); /* the share did bind */
    image_free(&img);
    scene_free(&s);
}
END_TEST

/* A file over the budget (as above) is drawn when the command line asks
 * for less: the budget is checked on the size and settings of the picture
 * that will be drawn, not on those that --size and --pixel replace. */
START_TEST(test_the_budget_follows_size_and_pixel)
{
    const char *text = "image 16384 1024\n"
                       "pixel samples 256 pattern jittered\n"
                       "sphere center 0 0 5 radius 1\n";
    struct {
        const char *pixel;
        int width, height;
    } asks[] = {{NULL, 8, 6}, {"pattern center", 0, 0}};
    for (int k = 0; k < 2; k++) {
        scene s;
        scene_error err;
        scene_init(&s);
        s.pixel_option = asks[k].pixel;
        s.width_option = asks[k].width, s.height_option = asks[k].height;
        ck_assert_msg(scene_parse(&s, text, strlen(text), "t", &err),
                      "%d: %d:%d: %s", k, err.line, err.col, err.message);
        scene_free(&s);
    }
    char scene_path[192], out[192];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("big.scene", text));
    snprintf(out, sizeof out, "%s", tmp_path("small.png"));
    const char *args[] = {scene_path, "--size", "8x6", "-o", out, NULL};
    char errors[4096];
    ck_assert_msg(run_bin(args, errors, sizeof errors) == 0, "%s", errors);
    ck_assert(file_exists(out));
}
END_TEST

/* The binary with args fails, says `says` on stderr, and writes nothing. */
static void expect_usage_error(const char *const *args, const char *says)
{
    char errors[4096];
    const char *all[12];
    int n = 0;
    for (; args[n] != NULL; n++)
        all[n] = args[n];
    all[n] = "-o", all[n + 1] = tmp_path("never.png"), all[n + 2] = NULL;
    ck_assert_int_ne(run_bin(all, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, says) != NULL, "%s", errors);
    ck_assert(!file_exists(tmp_path("never.png")));
}

START_TEST(test_bad_pixel_options_are_usage_errors)
{
    char path[192];
    snprintf(path, sizeof path, "%s",
             small_scene("pixel samples 256 pattern jittered"));
    const char *zero[] = {"--pixel", "samples 0 pattern grid", NULL};
    const char *word[] = {"--pixel", "pattern adaptive depht 2", NULL};
    const char *lines[] = {"--pixel", "pattern grid\npattern grid", NULL};
    const char *big[] = {"--size", "16384x1024", "--pixel",
                         "samples 256 pattern grid", NULL};
    const char *sized[] = {path, "--size", "16384x1024", NULL};
    expect_usage_error(zero, "--pixel:1:9: error:");
    expect_usage_error(word, "--pixel:1:18: error:");
    expect_usage_error(lines, "one line");
    char errors[4096];
    const char *missing[] = {"--pixel", NULL}; /* its value missing */
    ck_assert_int_ne(run_bin(missing, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, "needs a value") != NULL, "%s", errors);
    expect_usage_error(big, "--pixel: error: 16384x1024 pixels");
    expect_usage_error(sized, "--size: error: 16384x1024 pixels");
}
END_TEST

/* Whether tmpdir/stderr.txt holds a whole line yet. */
static bool stderr_has_a_line(void)
{
    FILE *f = fopen(tmp_path("stderr.txt"), "r");
    bool line = false;
    for (int c; f != NULL && !line && (c = fgetc(f)) != EOF;)
        line = c == '\n';
    if (f)
        fclose(f);
    return line;
}

/* Waits for the line of progress of the program pid, writing into the
 * test's stderr.txt, for as long as its threads (one a core) may use four
 * CPU seconds each, or until it ends; then stops it and returns its
 * standard error in errors. The first line is due after one second. */
static void first_progress_line(pid_t pid, char *errors, size_t size)
{
    double most = 4.0 * (double)sysconf(_SC_NPROCESSORS_ONLN);
    struct timespec ms = {0, 1000000};
    for (int waited = 0; !stderr_has_a_line() && waited < 100000 &&
                         !has_exited(pid) && cpu_seconds_of(pid) < most;
         waited++)
        nanosleep(&ms, NULL);
    kill(pid, SIGTERM);
    int status = finish_bin(pid, errors, size);
    ck_assert_msg(status == 128 + SIGTERM, "status %d: %s", status, errors);
}

START_TEST(test_the_progress_line_gives_a_rate_of_rays)
{
    const char *args[] = {"-o",        tmp_path("big.png"),
                          "--size",    "4096x4096",
                          "--pixel",   "pattern grid samples 16",
                          NULL};
    char errors[4096];
    first_progress_line(start_bin(args, (run_limits){.alarm_seconds = 120}),
                        errors, sizeof errors);
    ck_assert_msg(strstr(errors, "rays/s ") != NULL, "%s", errors);
}
END_TEST

/* One band of 8 x 6 pixels that takes minutes: 256 rays a pixel through
 * nested glass with no cutoff, under four area lights. No band ends for
 * minutes, and the line must come all the same, a second in. */
START_TEST(test_a_slow_band_still_shows_its_progress)
{
    const char *text =
        "image 8 6\npixel samples 256 pattern grid\n"
        "recursion depth 100 cutoff 0\n"
        "material g ambient 0 diffuse 0.5 specular 0 transparency 1 "
        "ior 1.5\n"
        "light area position 0 0 0 direction 0 0 1 radius 1 samples 1024\n"
        "light area position 0 0 0 direction 0 0 -1 radius 1 samples 1024\n"
        "light area position 0 0 0 direction 0 1 0 radius 1 samples 1024\n"
        "light area position 0 0 0 direction 0 -1 0 radius 1 samples 1024\n"
        "sphere center 0 0 0 radius 10 material g\n"
        "sphere center 0 0 0 radius 20 material g\n";
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("slow.scene", text));
    const char *args[] = {scene_path, "-o", tmp_path("slow.png"), NULL};
    char errors[4096];
    first_progress_line(start_bin(args, (run_limits){.alarm_seconds = 120}),
                        errors, sizeof errors);
    ck_assert_msg(strstr(errors, "time left not known yet") != NULL, "%s",
                  errors);
}
END_TEST

/* What a render tells its progress, last. */
typedef struct {
    int rows_done, rows;
    long long rays_done;
} progress_seen;

static void remember_progress(void *context, int rows_done, int rows,
                              long long rays_done)
{
    *(progress_seen *)context = (progress_seen){rows_done, rows, rays_done};
}

START_TEST(test_the_progress_counts_every_ray)
{
    scene s;
    parse_ok(&s, "image 32 24\npixel samples 16 pattern grid\n"
                 "light point position 0 5 0\n"
                 "material m reflect 0.5\n"
                 "sphere center 0 0 5 radius 1 material m\n"
                 "sphere center 1 0 7 radius 1\n");
    image img;
    ck_assert(image_init(&img, 32, 24));
    progress_seen seen = {0};
    render_stats st = {0};
    render_in_bands(&s,
                    &img,
                    &(render_settings){.threads = 2,
                                       .progress = remember_progress,
                                       .progress_context = &seen},
                    &st);
    ck_assert_int_eq(seen.rows_done, 24);
    ck_assert_int_eq(seen.rows, 24);
    ck_assert_int_eq(seen.rays_done, st.primary_rays + st.shadow_rays +
                                         st.reflection_rays +
                                         st.refraction_rays);
    ck_assert(st.primary_rays == 16 * 32 * 24 && st.shadow_rays > 0 &&
              st.reflection_rays > 0);
    image_free(&img);
    scene_free(&s);
}
END_TEST

/* One pixel, divided to depth 4 everywhere: 17 x 17 = 289 rays, of which
 * the pixel owns 286 (its 285 inner points and one corner); the other
 * three corners are no pixel's. The mean and the largest count the same
 * rays, and the three are said apart. */
START_TEST(test_rays_per_pixel_mean_and_largest_count_the_same_rays)
{
    char errors[4096], path[192];
    snprintf(path, sizeof path, "%s",
             write_file("one.scene", "image 1 1\n"
                                     "pixel pattern adaptive depth 4 "
                                     "min_depth 4\n"));
    const char *args[] = {path, "--stats", "-o", tmp_path("one.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, "primary rays       289\n"), "%s", errors);
    ck_assert_msg(strstr(errors, "rays per pixel     286.00 mean, 286 "
                                 "largest, and 3 at corners no pixel owns"),
                  "%s", errors);
}
END_TEST

/* The budget of an image's rays is passed by its size and its lights;
 * the error points at the image statement (or --size), whatever pixel
 * statement there is that asks for a ray a pixel, and names the lights'
 * share: 4 area lights of 1024 samples, 4096 shadow rays a primary ray. */
START_TEST(test_a_budget_error_points_at_its_cause)
{
    const char *lights =
        "light area position 0 5 5 direction 0 -1 0 radius 1 samples 1024\n"
        "light area position 1 5 5 direction 0 -1 0 radius 1 samples 1024\n"
        "light area position 2 5 5 direction 0 -1 0 radius 1 samples 1024\n"
        "light area position 3 5 5 direction 0 -1 0 radius 1 samples 1024\n";
    const char *heads[] = {"# four lights\nimage 4096 4096\n",
                           "# four lights\nimage 4096 4096\n"
                           "pixel pattern center\n"};
    for (int k = 0; k < 2; k++) {
        char text[1024];
        snprintf(text, sizeof text, "%s%s", heads[k], lights);
        scene s;
        scene_error err;
        ck_assert(!parse_named(&s, text, strlen(text), "t", &err));
        ck_assert_msg(err.line == 2 && err.col == 1 &&
                          strstr(err.message, "4096x4096 pixels") &&
                          strstr(err.message, "lights' 4096 shadow rays"),
                      "%d: %d:%d: %s", k, err.line, err.col, err.message);
        scene_free(&s);
    }
    /* --size asked for the pixels: the error is the option's */
    char text[1024];
    snprintf(text, sizeof text, "image 64 48\n%s", lights);
    scene s;
    scene_error err;
    scene_init(&s);
    s.width_option = 4096, s.height_option = 4096;
    ck_assert(!scene_parse(&s, text, strlen(text), "t", &err));
    ck_assert_msg(strcmp(err.file, "--size") == 0 && err.line == 0 &&
                      strstr(err.message, "lights' 4096 shadow rays"),
                  "%s:%d: %s", err.file, err.line, err.message);
    scene_free(&s);
}
END_TEST

Suite *ch13_antialiasing_suite(void)
{
    Suite *s = suite_create("ch13 antialiasing");
    TCase *patterns = tcase_create("patterns");
    tcase_add_test(patterns, test_samples_lie_in_their_pixel_one_in_each_cell);
    tcase_add_test(patterns,
                   test_jittered_samples_repeat_and_differ_between_pixels);
    tcase_add_threaded_test(
        patterns, test_a_jittered_render_is_the_same_on_any_thread_count);
    tcase_add_test(patterns, test_tent_samples_fall_as_the_tent_weighs);
    tcase_add_test(patterns, test_a_flat_image_costs_one_ray_per_corner);
    tcase_add_test(patterns, test_a_small_image_is_cut_into_short_bands);
    tcase_add_test(patterns, test_filter_weights_sum_to_one);
    tcase_add_test(patterns, test_an_edge_is_divided_and_a_flat_region_is_not);
    suite_add_tcase(s, patterns);
    TCase *renders = tcase_create("renders");
    tcase_add_checked_fixture(renders, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(renders, 120);
    tcase_add_test(renders, test_the_default_is_the_previous_chapters_picture);
    tcase_add_test(renders, test_thread_counts_give_the_same_image);
    tcase_add_test(renders, test_stats_report_rays_per_pixel_and_depths);
    tcase_add_slow_test(renders, test_the_progress_line_gives_a_rate_of_rays);
    tcase_add_slow_test(renders, test_a_slow_band_still_shows_its_progress);
    tcase_add_test(renders, test_the_progress_counts_every_ray);
    tcase_add_test(renders, test_a_scene_is_left_as_it_was_by_its_renders);
    suite_add_tcase(s, renders);
    TCase *failures = tcase_create("where it fails");
    tcase_add_test(
        failures,
        test_a_sphere_between_corners_is_missed_without_a_minimum_depth);
    tcase_add_test(failures,
                   test_dark_edges_differ_in_srgb_not_in_linear_light);
    tcase_add_test(failures,
                   test_jittered_points_are_shared_and_stay_near_their_place);
    tcase_add_test(
        failures,
        test_jittered_corners_see_a_pattern_the_grid_corners_alias_away);
    suite_add_tcase(s, failures);
    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_add_test(bad, test_bad_pixel_statements_are_located);
    tcase_add_test(bad, test_a_budget_passed_is_an_error);
    tcase_add_test(bad, test_an_image_shares_its_ray_budget_among_its_trees);
    tcase_add_test(bad, test_a_tree_keeps_to_its_share_of_the_image);
    tcase_add_test(bad, test_the_budget_follows_size_and_pixel);
    tcase_add_test(bad, test_a_budget_error_points_at_its_cause);
    tcase_add_test(bad,
                   test_rays_per_pixel_mean_and_largest_count_the_same_rays);
    tcase_add_test(bad, test_bad_pixel_options_are_usage_errors);
    suite_add_tcase(s, bad);
    return s;
}
