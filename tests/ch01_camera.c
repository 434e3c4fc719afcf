/* ch01_camera.c: the formulas and the inputs of chapter 01.
 *
 * Reference values come from closed forms evaluated in long double or from
 * hand computation (stated next to each), never from the code under test.
 * The command-line tests run the binary named by $CHAPTER_BIN. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <png.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "camera.h"
#include "image.h"
#include "render.h"
#include "scene.h"
#include "test_util.h"

#define DEG (3.14159265358979323846L / 180.0L)

/* Angle between two vectors in degrees, by atan2 (accurate for small angles
 * too). */
static long double angle_deg(vec3 a, vec3 b)
{
    long double cx = (long double)a.y * b.z - (long double)a.z * b.y;
    long double cy = (long double)a.z * b.x - (long double)a.x * b.z;
    long double cz = (long double)a.x * b.y - (long double)a.y * b.x;
    long double dot = (long double)a.x * b.x + (long double)a.y * b.y +
                      (long double)a.z * b.z;
    return atan2l(sqrtl(cx * cx + cy * cy + cz * cz), dot) / DEG;
}

static camera make_camera(double fov, int w, int h)
{
    camera cam;
    memset(&cam, 0, sizeof cam);
    cam.fov_deg = fov;
    cam.width = w;
    cam.height = h;
    return cam;
}

/* ------------------------------------------------------------ pixel rays */

START_TEST(test_pixel_size_is_image_width_over_pixel_count)
{
    /* fov 90: the image is 2 tan 45 = 2 wide, so 100 pixels are 0.02 each. */
    camera cam = make_camera(90, 100, 50);
    ck_assert_double_eq_tol(camera_pixel_size(&cam), 0.02, 1e-16);
}
END_TEST

START_TEST(test_centre_pixel_of_odd_image_looks_down_z)
{
    camera cam = make_camera(60, 101, 51);
    ray r = camera_ray(&cam, 50, 25);
    ck_assert_double_eq_tol(r.dir.x, 0.0, 1e-15);
    ck_assert_double_eq_tol(r.dir.y, 0.0, 1e-15);
    ck_assert_double_eq_tol(r.dir.z, 1.0, 1e-15);
    ck_assert(r.origin.x == 0 && r.origin.y == 0 && r.origin.z == 0);
}
END_TEST

START_TEST(test_corner_pixel_rays_match_the_derivation)
{
    /* At 60 degrees on 320 x 240, a pixel is 2 tan 30 / 320 wide, so the
     * centres of the corner pixels lie at (-+319, +-239, 320 sqrt 3) / 320
     * sqrt 3 on the image plane z = 1: the rays point along those vectors,
     * a table worked out by hand. */
    const int corners[4][2] = {{0, 0}, {319, 0}, {0, 239}, {319, 239}};
    const long double along[4][2] = {
        {-319, 239}, {319, 239}, {-319, -239}, {319, -239}};
    camera cam = make_camera(60, 320, 240);
    for (int k = 0; k < 4; k++) {
        long double x = along[k][0], y = along[k][1], z = 320 * sqrtl(3.0L);
        long double len = sqrtl(x * x + y * y + z * z);
        ray r = camera_ray(&cam, corners[k][0], corners[k][1]);
        /* A few ulps of 1: tan, a product, a sum and a square root. */
        ck_assert_double_eq_tol(r.dir.x, (double)(x / len), 8 * DBL_EPSILON);
        ck_assert_double_eq_tol(r.dir.y, (double)(y / len), 8 * DBL_EPSILON);
        ck_assert_double_eq_tol(r.dir.z, (double)(z / len), 8 * DBL_EPSILON);
    }
    /* Top-left looks left and up; bottom-right looks right and down. */
    ck_assert(camera_ray(&cam, 0, 0).dir.x < 0 &&
              camera_ray(&cam, 0, 0).dir.y > 0);
    ck_assert(camera_ray(&cam, 319, 239).dir.x > 0 &&
              camera_ray(&cam, 319, 239).dir.y < 0);
}
END_TEST

START_TEST(test_pixel_rays_span_the_field_of_view)
{
    const double fovs[] = {1, 30, 60, 90, 120, 179};
    const int widths[] = {1, 2, 320, 1001};
    for (size_t f = 0; f < sizeof fovs / sizeof fovs[0]; f++) {
        for (size_t k = 0; k < sizeof widths / sizeof widths[0]; k++) {
            camera cam = make_camera(fovs[f], widths[k], 7);
            vec3 left = camera_image_point(&cam, 0, 3.5);
            vec3 right = camera_image_point(&cam, widths[k], 3.5);
            /* 1e-9 degrees: far below a pixel, far above rounding. */
            ck_assert_msg(fabsl(angle_deg(left, right) - fovs[f]) < 1e-9L,
                          "fov %g, width %d: edges %Lg degrees apart", fovs[f],
                          widths[k], angle_deg(left, right));
        }
    }
}
END_TEST

START_TEST(test_sheet_pixel_size_does_not_span_the_field_of_view)
{
    /* The sheet: s = (2 tan(a/2)) / 2, left edge X = -w s / 2. For a 640-pixel
     * image at 60 degrees its edges are 2 atan(320 tan 30) = 179.38 degrees
     * apart. */
    double w = 640, s = 2 * tan(30 * (double)DEG) / 2;
    vec3 left = {-w * s / 2, 0, 1}, right = {w * s / 2, 0, 1};
    long double span = angle_deg(left, right);
    ck_assert_msg(span > 179.3L && span < 179.4L, "sheet's span %Lg", span);
    camera cam = make_camera(60, 640, 480);
    ck_assert_double_eq_tol(camera_pixel_size(&cam), s * 2 / w, 1e-15);
}
END_TEST

START_TEST(test_pixel_directions_are_unit_length)
{
    const double fovs[] = {0.001, 60, 179, 179.999};
    for (size_t f = 0; f < sizeof fovs / sizeof fovs[0]; f++) {
        camera cam = make_camera(fovs[f], 64, 48);
        for (int j = 0; j < 48; j++)
            for (int i = 0; i < 64; i++) {
                vec3 d = camera_ray(&cam, i, j).dir;
                /* normalize: one division and one sqrt, a few ulps at most. */
                ck_assert_double_eq_tol(vec3_length(d), 1.0, 4 * DBL_EPSILON);
            }
    }
}
END_TEST

/* The ray through a point of the image: at a pixel's centre it is that
 * pixel's ray, and at the top left corner it points at (left, top, 1). */
START_TEST(test_a_ray_at_any_point_of_the_image)
{
    camera cam = make_camera(90, 4, 2);
    camera_view view = camera_view_of(&cam);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 4; i++) {
            vec3 at = camera_view_ray_at(&view, i + 0.5, j + 0.5).dir,
                 pixel = camera_view_ray(&view, i, j).dir;
            ck_assert(at.x == pixel.x && at.y == pixel.y && at.z == pixel.z);
        }
    /* fov 90 over 4 pixels: s = 0.5, left = -1, top = 0.5 */
    vec3 corner = camera_view_ray_at(&view, 0, 0).dir,
         want = vec3_normalize((vec3){-1, 0.5, 1});
    ck_assert_msg(vec3_length(vec3_sub(corner, want)) <= 2 * DBL_EPSILON,
                  "(%g, %g, %g)", corner.x, corner.y, corner.z);
}
END_TEST

START_TEST(test_pixels_are_square)
{
    camera cam = make_camera(75, 33, 17);
    double s = camera_pixel_size(&cam);
    for (int j = 0; j + 1 < 17; j += 4)
        for (int i = 0; i + 1 < 33; i += 4) {
            vec3 p = camera_image_point(&cam, i + 0.5, j + 0.5);
            vec3 right = camera_image_point(&cam, i + 1.5, j + 0.5);
            vec3 below = camera_image_point(&cam, i + 0.5, j + 1.5);
            ck_assert_double_eq_tol(right.x - p.x, s, 1e-12 * s);
            ck_assert_double_eq_tol(p.y - below.y, s, 1e-12 * s);
            ck_assert(right.y == p.y && below.x == p.x && p.z == 1.0);
        }
}
END_TEST

START_TEST(test_even_image_is_symmetric_about_the_axis)
{
    camera cam = make_camera(50, 40, 30);
    vec3 a = camera_ray(&cam, 19, 14).dir, b = camera_ray(&cam, 20, 15).dir;
    ck_assert_double_eq_tol(a.x, -b.x, 1e-15);
    ck_assert_double_eq_tol(a.y, -b.y, 1e-15);
    ck_assert(a.x < 0 && a.y > 0);
}
END_TEST

/* ------------------------------------------------------------ sRGB */

START_TEST(test_srgb_known_values)
{
    /* Hand values: 12.92 * 0.0031308 = 0.040449936 exactly in decimal;
     * 1.055 * 0.18^(1/2.4) - 0.055 = 0.4613561295004416 (50-digit decimal). */
    ck_assert(srgb_encode(0.0) == 0.0);
    ck_assert_double_eq_tol(srgb_encode(0.0031308), 0.040449936,
                            4e-17); /* 3 roundings */
    ck_assert_double_eq_tol(srgb_encode(0.18), 0.46135612950044165, 4e-16);
    ck_assert(srgb_encode(1.0) == 1.0);
    ck_assert_int_eq(srgb_to_byte(0.0), 0);
    ck_assert_int_eq(srgb_to_byte(0.0031308), 10);  /* 10.31 */
    ck_assert_int_eq(srgb_to_byte(0.18), 118);      /* 117.65 */
    ck_assert_int_eq(srgb_to_byte(1.0), 255);
}
END_TEST

START_TEST(test_srgb_pieces_meet_at_the_knee)
{
    long double knee = 0.0031308L;
    long double line = 12.92L * knee,
                curve = 1.055L * powl(knee, 1 / 2.4L) - 0.055L;
    /* The standard rounds its constants: the pieces differ by 2.85e-8. */
    ck_assert(fabsl(line - curve) < 3e-8L);
    ck_assert_double_eq_tol(srgb_encode(nextafter(0.0031308, 1)), (double)curve,
                            1e-15);
}
END_TEST

START_TEST(test_srgb_clamps_out_of_range_and_nan)
{
    ck_assert(srgb_encode(-0.5) == 0.0);
    ck_assert(srgb_encode(NAN) == 0.0);
    ck_assert(srgb_encode(7.0) == 1.0);
    ck_assert(srgb_encode(INFINITY) == 1.0);
    ck_assert_int_eq(srgb_to_byte(NAN), 0);
    ck_assert_int_eq(srgb_to_byte(1e300), 255);
}
END_TEST

START_TEST(test_srgb_bytes_never_decrease)
{
    int previous = 0;
    for (int k = 0; k <= 100000; k++) {
        int code = srgb_to_byte(k / 100000.0);
        ck_assert_int_ge(code, previous);
        previous = code;
    }
    ck_assert_int_eq(previous, 255);
}
END_TEST

START_TEST(test_gamma_22_differs_from_srgb_by_8_5_codes_in_the_shadows)
{
    /* The chapter's claims, from the closed forms (evaluated independently to
     * 50 digits): max |sRGB - L^(1/2.2)| is 8.549 codes, near L = 0.00216;
     * for L >= 0.1 at most 1.489 codes, near L = 0.413. */
    double shadows = 0, rest = 0;
    for (int k = 1; k <= 100000; k++) {
        double L = k * 1e-7; /* (0, 0.01] */
        shadows =
            fmax(shadows, 255 * fabs(srgb_encode(L) - gamma_encode(L, 2.2)));
        L = 0.1 + k * 9e-6; /* (0.1, 1] */
        rest = fmax(rest, 255 * fabs(srgb_encode(L) - gamma_encode(L, 2.2)));
    }
    ck_assert_msg(shadows > 8.5 && shadows < 8.6, "shadows: %g codes", shadows);
    ck_assert_msg(rest > 1.4 && rest < 1.5, "L >= 0.1: %g codes", rest);
}
END_TEST

/* ------------------------------------------------------------ PNG */

/* The 8-bit sRGB codes of k/6 and k/4, from the standard's formula
 * (IEC 61966-2-1), rounded: a table, so that the test holds no encoder. */
static const int SRGB_SIXTHS[7] = {0, 113, 156, 188, 213, 235, 255};
static const int SRGB_QUARTERS[5] = {0, 137, 188, 225, 255};

START_TEST(test_png_round_trip_through_libpng)
{
    image img;
    ck_assert(image_init(&img, 7, 5));
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 7; i++)
            image_set(&img, i, j, (vec3){i / 6.0, j / 4.0, 0.18});
    char path[128], why[256];
    snprintf(path, sizeof path, "%s/round.png", tmpdir);
    ck_assert_msg(image_write_png(&img, path, why, sizeof why), "%s", why);

    png_image info;
    memset(&info, 0, sizeof info);
    info.version = PNG_IMAGE_VERSION;
    ck_assert(png_image_begin_read_from_file(&info, path));
    ck_assert_int_eq(info.width, 7);
    ck_assert_int_eq(info.height, 5);
    info.format = PNG_FORMAT_RGB;
    unsigned char bytes[7 * 5 * 3];
    ck_assert(png_image_finish_read(&info, NULL, bytes, 0, NULL));
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 7; i++) {
            const unsigned char *px = bytes + 3 * (7 * j + i);
            ck_assert_int_eq(px[0], SRGB_SIXTHS[i]);
            ck_assert_int_eq(px[1], SRGB_QUARTERS[j]);
            ck_assert_int_eq(px[2], 118);
        }
    image_free(&img);
}
END_TEST

START_TEST(test_failed_write_leaves_no_file_behind)
{
    image img;
    ck_assert(image_init(&img, 2, 2));
    char path[128], why[256] = "";
    /* A folder takes the target's place while the output is open: the
     * rename must fail after the PNG was written. */
    snprintf(path, sizeof path, "%s/occupied", tmpdir);
    png_output out;
    ck_assert_msg(png_output_open(&out, path, why, sizeof why), "%s", why);
    ck_assert_int_eq(mkdir(path, 0755), 0);
    ck_assert(!png_output_finish(&out, &img, why, sizeof why));
    png_output_free(&out);
    ck_assert(strstr(why, "rename") != NULL);
    ck_assert_int_eq(count_entries(tmpdir), 1); /* the temporary is gone */
    snprintf(path, sizeof path, "%s/no/such/dir.png", tmpdir);
    ck_assert(!image_write_png(&img, path, why, sizeof why));
    ck_assert(strstr(why, "cannot create") != NULL);
    image_free(&img);
}
END_TEST

START_TEST(test_image_init_enforces_the_limits)
{
    image img;
    ck_assert(!image_init(&img, 0, 10));
    ck_assert(!image_init(&img, 10, -1));
    ck_assert(!image_init(&img, IMAGE_MAX_SIDE + 1, 1));
    ck_assert(!image_init(&img, IMAGE_MAX_SIDE,
                          IMAGE_MAX_SIDE)); /* 2^28 > 2^24 pixels */
    ck_assert(img.pixels == NULL);
    ck_assert(image_init(&img, 4096, 4096));
    image_free(&img);
}
END_TEST

/* ------------------------------------------------------------ scene files */

START_TEST(test_scene_defaults)
{
    scene s;
    scene_error err;
    ck_assert(parse_text(&s, "", &err));
    ck_assert(s.cam.fov_deg == 60 && s.cam.width == 320 && s.cam.height == 240);
    ck_assert(s.bg.kind == BACKGROUND_GRADIENT);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_reads_every_statement)
{
    scene s;
    scene_error err;
    const char *text = "# a comment line\n"
                       "\n"
                       "camera fov 45.5   # trailing comment\r\n"
                       "\timage 64 32\n"
                       "background 0.25 0.5 2\n"
                       "camera fov 1e1"; /* no final newline; later wins */
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d: %s", err.line, err.col,
                  err.message);
    ck_assert(s.cam.fov_deg == 10.0);
    ck_assert(s.cam.width == 64 && s.cam.height == 32);
    ck_assert(s.bg.kind == BACKGROUND_SOLID);
    ck_assert(s.bg.bottom.x == 0.25 && s.bg.bottom.y == 0.5 &&
              s.bg.bottom.z == 2);
    ck_assert(parse_text(&s, "background gradient 0 0 0 1 1 1", &err));
    ck_assert(s.bg.kind == BACKGROUND_GRADIENT && s.bg.top.y == 1 &&
              s.bg.bottom.x == 0);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_rejects_unknown_keywords)
{
    expect_parse_error("camera fov 60\n  bogus 1\n", 2, 3,
                       "expected a statement keyword, found 'bogus'");
    expect_parse_error("camera zoom 2", 1, 8, "found 'zoom'");
    expect_parse_error("camera", 1, 7, "found end of line");
}
END_TEST

START_TEST(test_scene_rejects_missing_and_non_numeric_values)
{
    expect_parse_error("camera fov", 1, 11, "found end of line");
    expect_parse_error("camera fov abc", 1, 12, "found 'abc'");
    expect_parse_error("camera fov 12abc", 1, 12, "found '12abc'");
    expect_parse_error("image 320", 1, 10,
                       "expected an image height, found end of line");
    expect_parse_error("image 320.5 240", 1, 7, "whole number");
    expect_parse_error("background 1 1", 1, 15, "found end of line");
    expect_parse_error("background gradient 1 1 1 0 0", 1, 30,
                       "found end of line");
    expect_parse_error("background 1 1 1 # ok\nbackground 1 x 1", 2, 14,
                       "found 'x'");
    expect_parse_error("camera fov "
                       "1234567890123456789012345678901234567890123456789012345"
                       "678901234567890",
                       1, 12, "...'");
}
END_TEST

START_TEST(test_scene_rejects_non_finite_numbers)
{
    expect_parse_error("camera fov nan", 1, 12, "finite");
    expect_parse_error("camera fov inf", 1, 12, "finite");
    expect_parse_error("camera fov -INFINITY", 1, 12, "finite");
    expect_parse_error("background 1 1e999 1", 1, 14, "finite");
    expect_parse_error("image nan 4", 1, 7, "finite");
}
END_TEST

START_TEST(test_scene_rejects_field_of_view_outside_0_180)
{
    expect_parse_error("camera fov 0", 1, 12, "between 0 and 180");
    expect_parse_error("camera fov 180", 1, 12, "between 0 and 180");
    expect_parse_error("camera fov -5", 1, 12, "between 0 and 180");
    expect_parse_error("camera fov 720", 1, 12, "between 0 and 180");
}
END_TEST

START_TEST(test_scene_rejects_bad_image_sizes)
{
    expect_parse_error("image 0 240", 1, 7, "from 1 to 16384");
    expect_parse_error("image 320 -240", 1, 11, "from 1 to 16384");
    expect_parse_error("image 100000 100000", 1, 7, "from 1 to 16384");
    expect_parse_error("image 1e15 1", 1, 7, "from 1 to 16384");
    expect_parse_error("image 1e16 1", 1, 7, "from 1 to 16384"); /* whole */
    expect_parse_error("image 16384 16384", 1, 13, "at most 16777216 pixels");
}
END_TEST

START_TEST(test_scene_rejects_leftovers_and_negative_colours)
{
    expect_parse_error("image 320 240 1", 1, 15,
                       "expected end of line, found '1'");
    expect_parse_error("background -1 0 0", 1, 12, "from 0 to 1e6");
    expect_parse_error("background 0 2e6 0", 1, 14, "from 0 to 1e6");
    static const char with_nul[] = "camera\0 fov 30";
    expect_parse_error_named("bad.scene", with_nul, sizeof with_nul - 1, 1, 7,
                             "NUL");
}
END_TEST

START_TEST(test_scene_load_reports_unreadable_files)
{
    scene s;
    scene_error err;
    scene_init(&s);
    ck_assert(!scene_load(&s, "/nonexistent/ch01.scene", &err));
    ck_assert_int_eq(err.line, 0);
    ck_assert_str_eq(err.file, "/nonexistent/ch01.scene");
    ck_assert(strstr(err.message, "No such file") != NULL);
    ck_assert(!scene_load(&s, tmpdir, &err)); /* a directory */
    ck_assert_int_eq(err.line, 0);
    char path[128];
    snprintf(path, sizeof path, "%s/huge.scene", tmpdir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, SCENE_MAX_BYTES, SEEK_SET),
                     0); /* sparse: 16 MiB + 1 */
    fputc('\n', f);
    fclose(f);
    ck_assert(!scene_load(&s, path, &err));
    ck_assert(strstr(err.message, "larger than") != NULL);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ command line */

START_TEST(test_cli_renders_the_built_in_scene)
{
    char out[128], errors[2048];
    snprintf(out, sizeof out, "%s/out.png", tmpdir);
    const char *args[] = {"-o", out, "--size", "8x6", "--stats", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert(strstr(errors, "primary rays") != NULL);
    png_image info;
    memset(&info, 0, sizeof info);
    info.version = PNG_IMAGE_VERSION;
    ck_assert(png_image_begin_read_from_file(&info, out));
    ck_assert(info.width == 8 && info.height == 6);
    png_image_free(&info);
}
END_TEST

/* A failing run: status 1, the message, and the old output untouched. */
static void expect_cli_error(const char *const *args, const char *message_part)
{
    char out[128], errors[2048];
    snprintf(out, sizeof out, "%s/keep.png", tmpdir);
    FILE *f = fopen(out, "w");
    fputs("old picture", f);
    fclose(f);
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, message_part) != NULL,
                  "stderr '%s' lacks '%s'", errors, message_part);
    char buf[32] = "";
    f = fopen(out, "r");
    ck_assert(fgets(buf, sizeof buf, f) != NULL);
    fclose(f);
    ck_assert_str_eq(buf, "old picture");
    ck_assert_int_eq(count_entries(tmpdir),
                     2); /* keep.png, stderr.txt: no temporary */
}

START_TEST(test_cli_rejects_bad_arguments)
{
    char out[128];
    snprintf(out, sizeof out, "%s/keep.png", tmpdir);
    const char *size0[] = {"-o", out, "--size", "0x0", NULL};
    expect_cli_error(size0, "error: --size expects WIDTHxHEIGHT");
    const char *size_text[] = {"-o", out, "--size", "axb", NULL};
    expect_cli_error(size_text, "found 'axb'");
    const char *size_huge[] = {"-o", out, "--size", "99999999999x99999999999",
                               NULL};
    expect_cli_error(size_huge, "--size expects");
    const char *size_half[] = {"-o", out, "--size", "640", NULL};
    expect_cli_error(size_half, "--size expects");
    const char *unknown[] = {"-o", out, "--frobnicate", NULL};
    expect_cli_error(unknown, "unknown option, found '--frobnicate'");
    const char *no_value[] = {"--size", NULL};
    expect_cli_error(no_value, "needs a value");
    const char *two[] = {"a.scene", "b.scene", "-o", out, NULL};
    expect_cli_error(two, "only one scene file");
}
END_TEST

START_TEST(test_cli_reports_scene_errors_with_location)
{
    char out[128], scene_path[128];
    snprintf(out, sizeof out, "%s/keep.png", tmpdir);
    snprintf(scene_path, sizeof scene_path, "%s/bad.scene", tmpdir);
    const char *missing[] = {scene_path, "-o", out, NULL};
    expect_cli_error(missing, "bad.scene: error: No such file");
    FILE *f = fopen(scene_path, "w");
    fputs("image 32 32\ncamera fov 200\n", f);
    fclose(f);
    char expected[200];
    snprintf(expected, sizeof expected,
             "%s:2:12: error: expected a field of view", scene_path);
    char errors[2048];
    const char *bad[] = {scene_path, "-o", out, NULL};
    ck_assert_int_eq(run_bin(bad, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, expected) != NULL, "stderr: %s", errors);
    ck_assert(!file_exists(out) || unlink(out) == 0);
}
END_TEST

START_TEST(test_cli_help_succeeds)
{
    /* The help goes to standard output, whole, and nothing to stderr. */
    char errors[256], text[4096] = "";
    char out[192];
    snprintf(out, sizeof out, "%s", tmp_path("help.txt"));
    const char *help[] = {"--help", NULL};
    ck_assert_int_eq(run_bin_limited(help, errors, sizeof errors,
                                     (run_limits){.stdout_path = out}),
                     0);
    FILE *f = fopen(out, "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    ck_assert_msg(strncmp(text, "usage: ", 7) == 0, "stdout: %s", text);
    const char *options[] = {"-o FILE", "--size WxH", "--stats", "--help"};
    for (int k = 0; k < 4; k++)
        ck_assert_msg(strstr(text, options[k]) != NULL, "no %s in: %s",
                      options[k], text);
    ck_assert_str_eq(errors, "");
}
END_TEST

#ifndef NDEBUG
/* The checked preconditions: a wrong call stops the program at once
 * instead of writing beside the image. */
START_TEST(test_a_pixel_outside_the_image_is_a_checked_mistake)
{
    image img;
    ck_assert(image_init(&img, 4, 3));
    ck_assert_ptr_nonnull(freopen("/dev/null", "w", stderr)); /* expected */
    image_set(&img, 4, 0, (vec3){0, 0, 0}); /* one past the last column */
}
END_TEST

START_TEST(test_rendering_into_an_image_of_another_size_is_a_checked_mistake)
{
    scene s;
    scene_init(&s);
    image img;
    ck_assert(image_init(&img, s.cam.width / 2, s.cam.height));
    render_stats stats = {0};
    ck_assert_ptr_nonnull(freopen("/dev/null", "w", stderr)); /* expected */
    render(&s, &img, &stats);
}
END_TEST
#endif

Suite *ch01_camera_suite(void)
{
    Suite *s = suite_create("ch01 camera");
    TCase *rays = tcase_create("pixel rays");
    tcase_add_test(rays, test_pixel_size_is_image_width_over_pixel_count);
    tcase_add_test(rays, test_centre_pixel_of_odd_image_looks_down_z);
    tcase_add_test(rays, test_corner_pixel_rays_match_the_derivation);
    tcase_add_test(rays, test_pixel_rays_span_the_field_of_view);
    tcase_add_test(rays, test_sheet_pixel_size_does_not_span_the_field_of_view);
    tcase_add_test(rays, test_pixel_directions_are_unit_length);
    tcase_add_test(rays, test_pixels_are_square);
    tcase_add_test(rays, test_a_ray_at_any_point_of_the_image);
    tcase_add_test(rays, test_even_image_is_symmetric_about_the_axis);
    suite_add_tcase(s, rays);

    TCase *srgb = tcase_create("sRGB");
    tcase_add_test(srgb, test_srgb_known_values);
    tcase_add_test(srgb, test_srgb_pieces_meet_at_the_knee);
    tcase_add_test(srgb, test_srgb_clamps_out_of_range_and_nan);
    tcase_add_test(srgb, test_srgb_bytes_never_decrease);
    tcase_add_test(srgb,
                   test_gamma_22_differs_from_srgb_by_8_5_codes_in_the_shadows);
    suite_add_tcase(s, srgb);

    TCase *png = tcase_create("PNG output");
    tcase_add_checked_fixture(png, make_tmpdir, remove_tmpdir);
    tcase_add_test(png, test_png_round_trip_through_libpng);
    tcase_add_test(png, test_failed_write_leaves_no_file_behind);
    tcase_add_test(png, test_image_init_enforces_the_limits);
    suite_add_tcase(s, png);

    TCase *bad = tcase_create("scene files");
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_add_test(bad, test_scene_defaults);
    tcase_add_test(bad, test_scene_reads_every_statement);
    tcase_add_test(bad, test_scene_rejects_unknown_keywords);
    tcase_add_test(bad, test_scene_rejects_missing_and_non_numeric_values);
    tcase_add_test(bad, test_scene_rejects_non_finite_numbers);
    tcase_add_test(bad, test_scene_rejects_field_of_view_outside_0_180);
    tcase_add_test(bad, test_scene_rejects_bad_image_sizes);
    tcase_add_test(bad, test_scene_rejects_leftovers_and_negative_colours);
    tcase_add_test(bad, test_scene_load_reports_unreadable_files);
    suite_add_tcase(s, bad);

    TCase *cli = tcase_create("command line");
    tcase_add_checked_fixture(cli, make_tmpdir, remove_tmpdir);
    tcase_add_test(cli, test_cli_renders_the_built_in_scene);
    tcase_add_test(cli, test_cli_rejects_bad_arguments);
    tcase_add_test(cli, test_cli_reports_scene_errors_with_location);
    tcase_add_test(cli, test_cli_help_succeeds);
#ifndef NDEBUG
    TCase *contracts = tcase_create("contracts");
    tcase_add_test_raise_signal(
        contracts, test_a_pixel_outside_the_image_is_a_checked_mistake,
        SIGABRT);
    tcase_add_test_raise_signal(
        contracts,
        test_rendering_into_an_image_of_another_size_is_a_checked_mistake,
        SIGABRT);
    suite_add_tcase(s, contracts);
#endif
    suite_add_tcase(s, cli);
    return s;
}
