/* ch01_robustness.c: degenerate scenes, failed writes, hostile paths and
 * files, for every chapter.
 *
 * Part of chapter 01's suites, so it runs against the program of every
 * chapter. A scene may use statements that an early chapter does not know:
 * that chapter must then reject it cleanly (status 1, a located error, no
 * output file). A chapter that accepts it must render it with every pixel
 * finite; image_set asserts that, so a NaN would abort the binary.
 *
 * Tests that could harm the machine if the program misbehaved (writing to
 * /dev/null or /dev/stdout) run the binary as nobody when they run as root,
 * so that a program that tried to replace a device could not. */
#include <check.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <png.h>
#include <signal.h>
#include <string.h>
#include <time.h>

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
    "image 9 7\nsphere center 0 0 5 radius 1e-50\nsphere center 0 0 0 radius "
    "1e50\n",
    /* a triangle with three equal corners, on the centre ray */
    "image 9 7\ntriangle a 0 0 5 b 0 0 5 c 0 0 5\n",
    /* a light exactly at the point the centre ray hits */
    "image 9 7\nsphere center 0 0 5 radius 1\nlight point position 0 0 4\n",
    /* the eye inside a sphere, lit from inside and outside */
    "image 9 7\nsphere center 0 0 0 radius 10\nlight point position 1 1 1\n"
    "light spot position 0 0 20 direction 0 0 -1 angle 179.999 exponent 0\n",
    /* the brightest lights and the most extreme tone map allowed */
    "image 9 7\ntonemap alpha 1e300 beta 1e-300\nsphere center 0 0 5 radius 1 "
    "color 1e6 1e6 1e6\n"
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
        snprintf(scene_path, sizeof scene_path, "%s",
                 write_file("degenerate.scene", degenerate_scenes[k]));
        snprintf(out, sizeof out, "%s", tmp_path("out.png"));
        unlink(out);
        const char *args[] = {scene_path, "-o", out, NULL};
        int status = run_bin(args, errors, sizeof errors);
        ck_assert_msg(status == 0 || status == 1,
                      "scene %d: status %d, stderr: %s", k, status, errors);
        if (status == 1) {
            ck_assert_msg(strstr(errors, "degenerate.scene:") &&
                              strstr(errors, ": error: "),
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
                ck_assert_msg(isfinite(img.pixels[p].x) &&
                                  isfinite(img.pixels[p].y) &&
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
static size_t first_picture(char *path, size_t path_size, char *bytes,
                            size_t size)
{
    char folder[192], errors[1024];
    snprintf(folder, sizeof folder, "%s", tmp_path("keep"));
    ck_assert_int_eq(mkdir(folder, 0755), 0);
    snprintf(path, path_size, "%.160s/picture.png",
             folder); /* tmpdir is 24 characters */
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
    ck_assert_int_eq(count_entries(tmp_path("keep")),
                     1); /* no temporary left */
}

START_TEST(test_a_bad_scene_keeps_the_old_picture)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("bad.scene", "camera fov 400\n"));
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

/* Runs the binary as nobody when the tests run as root (root ignores
 * permissions). Nobody may not reach the build folder, so a copy of the
 * binary in the (world-readable) test folder is run. */
static int run_as_nobody(const char *const *args, char *errors, size_t size,
                         run_limits limits)
{
    ck_assert_int_eq(chmod(tmpdir, 0755), 0);
    char *original = strdup(getenv("CHAPTER_BIN"));
    char copy[192];
    snprintf(copy, sizeof copy, "%s", tmp_path("chapter-bin"));
    copy_file(original, copy);
    ck_assert_int_eq(chmod(copy, 0755), 0);
    setenv("CHAPTER_BIN", copy, 1);
    limits.as_nobody = true;
    int status = run_bin_limited(args, errors, size, limits);
    setenv("CHAPTER_BIN", original, 1); /* for the tests after this one */
    free(original);
    unlink(copy);
    return status;
}

START_TEST(test_an_unwritable_folder_keeps_the_old_picture)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    /* Nobody may read but not write the folder; a user other than root
     * makes it read only. */
    if (geteuid() != 0)
        ck_assert_int_eq(chmod(tmp_path("keep"), 0555), 0);
    const char *args[] = {"-o", path, "--size", "160x120", NULL};
    int status = run_as_nobody(args, errors, sizeof errors, (run_limits){0});
    ck_assert_int_eq(status, 1);
    ck_assert_msg(strstr(errors, "error: cannot create") != NULL, "stderr: %s",
                  errors);
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
    ck_assert_int_eq(run_bin_limited(args, errors, sizeof errors,
                                     (run_limits){.max_file_bytes = 256}),
                     1);
    ck_assert_msg(strstr(errors, "error: cannot write") != NULL, "stderr: %s",
                  errors);
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

/* ------------------------------------------------------------ where the output
 * goes */

static bool is_png(const char *path)
{
    char head[8];
    return read_bytes(path, head, sizeof head) == 8 &&
           memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0;
}

START_TEST(test_a_fifo_is_written_in_place)
{
    char fifo[192], errors[1024];
    snprintf(fifo, sizeof fifo, "%s", tmp_path("pipe"));
    ck_assert_int_eq(mkfifo(fifo, 0644), 0);
    const char *args[] = {"-o", fifo, "--size", "16x12", NULL};
    run_limits no_hang = {.alarm_seconds = 30};
    /* No program reads from the FIFO: an error, not a wait. */
    ck_assert_int_eq(run_bin_limited(args, errors, sizeof errors, no_hang), 1);
    ck_assert_msg(strstr(errors, "no program reads from it") != NULL,
                  "stderr: %s", errors);
    int reader = open(fifo, O_RDONLY | O_NONBLOCK);
    ck_assert_int_ge(reader, 0);
    ck_assert_int_eq(run_bin_limited(args, errors, sizeof errors, no_hang), 0);
    unsigned char head[8] = {0};
    ck_assert_int_eq(read(reader, head, sizeof head), 8);
    close(reader);
    ck_assert(memcmp(head, "\x89PNG", 4) == 0);
    struct stat st;
    ck_assert_int_eq(lstat(fifo, &st), 0);
    ck_assert(S_ISFIFO(st.st_mode)); /* not replaced by a regular file */
}
END_TEST

START_TEST(test_a_device_is_written_in_place)
{
    char errors[1024];
    const char *args[] = {"-o", "/dev/null", "--size", "16x12", NULL};
    int status = run_as_nobody(args, errors, sizeof errors, (run_limits){0});
    ck_assert_msg(status == 0, "status %d, stderr: %s", status, errors);
    struct stat st;
    ck_assert_int_eq(lstat("/dev/null", &st), 0);
    ck_assert(S_ISCHR(st.st_mode));
}
END_TEST

START_TEST(test_dash_is_standard_output)
{
    char out[192], errors[1024];
    snprintf(out, sizeof out, "%s", tmp_path("stdout.png"));
    const char *args[] = {"-o", "-", "--size", "16x12", NULL};
    int status = run_bin_limited(args, errors, sizeof errors,
                                 (run_limits){.stdout_path = out});
    bool wrote_a_file =
        unlink("-") == 0; /* where "-" would go as a file name */
    ck_assert_msg(status == 0, "stderr: %s", errors);
    ck_assert(!wrote_a_file);
    ck_assert(is_png(out));
}
END_TEST

START_TEST(test_dev_stdout_is_written_through_its_link)
{
    char folder[192], out[192], errors[1024];
    snprintf(folder, sizeof folder, "%s", tmp_path("open"));
    ck_assert_int_eq(mkdir(folder, 0777), 0);
    ck_assert_int_eq(chmod(folder, 0777), 0); /* nobody may write in it */
    snprintf(out, sizeof out, "%s/open/stdout.png", tmpdir);
    write_bytes("open/stdout.png", "", 0);
    ck_assert_int_eq(chmod(out, 0666), 0);
    const char *args[] = {"-o", "/dev/stdout", "--size", "16x12", NULL};
    int status = run_as_nobody(args, errors, sizeof errors,
                               (run_limits){.stdout_path = out});
    ck_assert_msg(status == 0, "stderr: %s", errors);
    ck_assert(is_png(out));
    struct stat st;
    ck_assert_int_eq(lstat("/dev/stdout", &st), 0);
    ck_assert(S_ISLNK(st.st_mode)); /* the link is still a link */
}
END_TEST

START_TEST(test_output_errors_come_before_the_render)
{
    char missing[192], errors[1024];
    snprintf(missing, sizeof missing, "%s", tmp_path("no/such/folder.png"));
    const char *cases[][2] = {{missing, "cannot create"},
                              {"", "-o expects a file name"},
                              {tmpdir, "Is a directory"}};
    for (int k = 0; k < 3; k++) {
        const char *args[] = {"-o", cases[k][0], "--size", "4096x4096", NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, cases[k][1]) != NULL, "stderr: %s",
                      errors);
        /* Measured in work, not time: the render would fill an image of
         * 4096 * 4096 vec3 of doubles, 384 MiB; failing first fills none
         * (a peak under 3 MiB; under 60 MiB with AddressSanitizer). */
        ck_assert_msg(last_run_peak_kib < (128L << 10),
                      "'%s': peak of %ld KiB before the error", cases[k][0],
                      last_run_peak_kib);
    }
}
END_TEST

START_TEST(test_a_replaced_file_keeps_its_mode)
{
    static char bytes[65536], now[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    ck_assert_int_eq(chmod(path, 0640), 0);
    umask(022); /* a new file would get 0644 */
    const char *args[] = {"-o", path, "--size", "80x60", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    struct stat st;
    ck_assert_int_eq(stat(path, &st), 0);
    ck_assert_int_eq(st.st_mode & 0777, 0640);
    ck_assert_uint_ne(read_bytes(path, now, sizeof now),
                      n); /* a new, smaller picture */
}
END_TEST

START_TEST(test_a_read_only_file_is_not_replaced)
{
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    ck_assert_int_eq(chmod(tmp_path("keep"), 0777),
                     0); /* anyone may write the folder */
    ck_assert_int_eq(chmod(path, 0444), 0);
    const char *args[] = {"-o", path, "--size", "80x60", NULL};
    ck_assert_int_eq(
        run_as_nobody(args, errors, sizeof errors, (run_limits){0}), 1);
    ck_assert_msg(strstr(errors, "read-only") != NULL, "stderr: %s", errors);
    expect_picture_kept(path, bytes, n);
    if (geteuid() ==
        0) { /* root may write it, as cp may: replaced, still read only */
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
        struct stat st;
        ck_assert_int_eq(stat(path, &st), 0);
        ck_assert_int_eq(st.st_mode & 0777, 0444);
    }
}
END_TEST

/* Does the folder hold an entry whose name starts with prefix? */
static bool has_entry_starting(const char *folder, const char *prefix)
{
    DIR *d = opendir(folder);
    ck_assert_ptr_nonnull(d);
    bool found = false;
    for (struct dirent *e; !found && (e = readdir(d)) != NULL;)
        found = strncmp(e->d_name, prefix, strlen(prefix)) == 0;
    closedir(d);
    return found;
}

START_TEST(test_a_signal_leaves_no_temporary_file)
{
    const int stops[] = {SIGINT, SIGTERM};
    for (int k = 0; k < 2; k++) {
        char folder[192], out[192], errors[1024];
        snprintf(folder, sizeof folder, "%s/stop%d", tmpdir, k);
        ck_assert_int_eq(mkdir(folder, 0755), 0);
        snprintf(out, sizeof out, "%s/stop%d/out.png", tmpdir, k);
        const char *args[] = {"-o", out, "--size", "4096x4096", NULL};
        pid_t pid = start_bin(args, (run_limits){.alarm_seconds = 120});
        /* The temporary file appears when the output is being made. */
        struct timespec ms = {0, 1000000};
        int waited = 0;
        while (!has_entry_starting(folder, "out.png.tmp-") &&
               waited++ < 60000) {
            /* a program that has stopped will make no file: no need to wait */
            ck_assert_msg(!has_exited(pid),
                          "the program ended before its output");
            nanosleep(&ms, NULL);
        }
        ck_assert_int_eq(kill(pid, stops[k]), 0);
        ck_assert_int_eq(finish_bin(pid, errors, sizeof errors),
                         128 + stops[k]);
        ck_assert_msg(waited < 60000, "no temporary file appeared");
        ck_assert_int_eq(count_entries(folder), 0);
    }
}
END_TEST

/* ------------------------------------------------------------ hostile input
 * files */

START_TEST(test_a_scene_must_be_a_regular_file)
{
    char fifo[192], out[192], errors[1024];
    snprintf(fifo, sizeof fifo, "%s", tmp_path("scene-pipe"));
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    ck_assert_int_eq(mkfifo(fifo, 0644), 0);
    const char *paths[] = {fifo, "/dev/zero"};
    for (int k = 0; k < 2; k++) {
        const char *args[] = {paths[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin_limited(args, errors, sizeof errors,
                                         (run_limits){.alarm_seconds = 30}),
                         1);
        ck_assert_msg(strstr(errors, "not a regular file") != NULL,
                      "stderr: %s", errors);
        ck_assert(!file_exists(out));
    }
    /* A file under /proc says it is empty but holds text: it is read whole. */
    const char *proc[] = {"/proc/self/status", "-o", out, NULL};
    ck_assert_int_eq(run_bin(proc, errors, sizeof errors), 1);
    ck_assert_msg(
        strstr(
            errors,
            "status:1:1: error: expected a statement keyword, found 'Name:'"),
        "stderr: %s", errors);
}
END_TEST

START_TEST(test_a_byte_order_mark_is_skipped)
{
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s,
                             "\xEF\xBB\xBF"
                             "image 8 6\n",
                             &err),
                  "%s", err.message);
    ck_assert_int_eq(s.cam.width, 8);
    scene_free(&s);
    /* Columns count from after the mark, as an editor shows them. */
    expect_parse_error("\xEF\xBB\xBF" "camera fov x\n", 1, 12, "found 'x'");
    /* Only at the start of the file: elsewhere it is reported. */
    expect_parse_error("image 8 6\n\xEF\xBB\xBF"
                       "image 8 6\n",
                       2, 1, "byte order mark");
}
END_TEST

START_TEST(test_numbers_may_have_any_number_of_digits)
{
    char text[1024];
    int n = snprintf(text, sizeof text, "camera fov ");
    memset(text + n, '0', 300); /* 000...0060.000...0 */
    memcpy(text + n + 300, "60.", 3);
    memset(text + n + 303, '0', 300);
    strcpy(text + n + 603, "\n");
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    ck_assert(s.cam.fov_deg == 60);
    scene_free(&s);
}
END_TEST

START_TEST(test_a_whole_number_too_large_is_out_of_range)
{
    /* 2^64 + 16: whole, and no long holds it; the message is the range's */
    expect_parse_error("image 18446744073709551632 6\n", 1, 7,
                       "an image width from 1 to");
    expect_parse_error("image 8 -1e300\n", 1, 9, "an image height from 1 to");
    expect_parse_error("image 8.5 6\n", 1, 7, "(a whole number)");
}
END_TEST

/* Runs the binary on args; stderr must hold want and no byte of avoid. */
static void expect_stderr(const char *const *args, const char *want,
                          const char *avoid)
{
    char errors[2048];
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, want) != NULL, "stderr '%s' lacks '%s'",
                  errors, want);
    ck_assert_msg(strpbrk(errors, avoid) == NULL,
                  "stderr '%s' holds a raw control byte", errors);
}

START_TEST(test_errors_escape_what_a_terminal_would_obey)
{
    char scene_path[192], out[192], name[192];
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    /* A token that would retitle the terminal. */
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("title.scene", "camera fov \x1b]0;owned\x07\n"));
    const char *token[] = {scene_path, "-o", out, NULL};
    expect_stderr(token,
                  ":1:12: error: expected a field of view in degrees, found "
                  "'\\x1b]0;owned\\x07'",
                  "\x1b\x07");
    /* A file name that would clear the screen, and one with a C1 control. */
    snprintf(name, sizeof name, "%s", tmp_path("x\x1b[2J\xc2\x9b.scene"));
    const char *path[] = {name, "-o", out, NULL};
    expect_stderr(path, "x\\x1b[2J\\xc2\\x9b.scene: error: No such file",
                  "\x1b");
    /* An option's value. */
    const char *size[] = {"--size", "\x1b[2J", "-o", out, NULL};
    expect_stderr(size, "found '\\x1b[2J'", "\x1b");
    /* Letters beyond ASCII are shown as they are. */
    snprintf(name, sizeof name, "%s", tmp_path("caf\xc3\xa9.scene"));
    const char *letters[] = {name, "-o", out, NULL};
    expect_stderr(letters, "caf\xc3\xa9.scene: error: No such file", "\x1b");
}
END_TEST

START_TEST(test_long_file_names_are_named_in_full)
{
    /* Two folders of 200 bytes each: the scene's path is over 400 bytes. */
    char path[1024], out[192], errors[2048], expected[1100];
    int n = snprintf(path, sizeof path, "%s/", tmpdir);
    for (int folder = 0; folder < 2; folder++) {
        memset(path + n, 'a' + folder, 200);
        path[n + 200] = '\0';
        ck_assert_int_eq(mkdir(path, 0755), 0);
        path[n + 200] = '/';
        n += 201;
    }
    strcpy(path + n, "bad.scene");
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs("camera fov 400\n", f);
    fclose(f);
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    const char *args[] = {path, "-o", out, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    snprintf(expected, sizeof expected, "%s:1:12: error:", path);
    ck_assert_msg(strstr(errors, expected) != NULL, "stderr: %s", errors);
    /* A name longer than any path the system takes ends in "...". */
    static char longer[PARSE_MAX_NAME + 1000];
    memset(longer, 'n', sizeof longer - 1);
    scene s;
    scene_error err;
    ck_assert(!parse_named(&s, "camera fov 400\n", 15, longer, &err));
    ck_assert_uint_eq(strlen(err.file), PARSE_MAX_NAME - 1);
    ck_assert_str_eq(err.file + PARSE_MAX_NAME - 4, "...");
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ inputs and
 * outputs */

/* The output named as the scene, through a symbolic link to it, and through
 * a second hard link: refused, the scene kept, nothing left beside it. */
START_TEST(test_the_output_may_not_be_an_input)
{
    char folder[192], scene_path[256], names[3][256], errors[2048];
    snprintf(folder, sizeof folder, "%s", tmp_path("in"));
    ck_assert_int_eq(mkdir(folder, 0755), 0);
    snprintf(scene_path, sizeof scene_path, "%s/s.scene", folder);
    const char text[] = "image 8 6\n";
    FILE *f = fopen(scene_path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
    snprintf(names[0], sizeof names[0], "%s/./s.scene", folder);
    snprintf(names[1], sizeof names[1], "%s/link.png", folder);
    snprintf(names[2], sizeof names[2], "%s/hard.png", folder);
    ck_assert_int_eq(symlink("s.scene", names[1]), 0);
    ck_assert_int_eq(link(scene_path, names[2]), 0);
    for (int k = 0; k < 3; k++) {
        const char *args[] = {scene_path, "-o", names[k], NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "error: the output is an input:"), "%s",
                      errors);
        char now[64] = "";
        ck_assert_int_eq(read_bytes(scene_path, now, sizeof now), strlen(text));
        ck_assert(memcmp(now, text, strlen(text)) == 0);
        ck_assert_int_eq(count_entries(folder), 3); /* no temporary either */
    }
}
END_TEST

START_TEST(test_a_name_that_fits_has_a_temporary_that_fits)
{
    /* NAME_MAX is 255: a 254-byte name is legal, and its temporary, with
     * 11 bytes of suffix, must be too */
    char name[256], out[512], errors[1024];
    memset(name, 'n', 250);
    strcpy(name + 250, ".png");
    snprintf(out, sizeof out, "%s/%s", tmpdir, name);
    const char *args[] = {"-o", out, "--size", "8x6", NULL};
    int status = run_bin(args, errors, sizeof errors);
    ck_assert_msg(status == 0, "stderr: %s", errors);
    ck_assert(is_png(out));
    ck_assert_int_eq(count_entries(tmpdir), 2); /* the picture and stderr.txt */
}
END_TEST

START_TEST(test_command_line_numbers_are_digits_only)
{
    /* strtol would skip blanks and take a sign; the options take digits */
    const char *sizes[] = {" 64x48", "+64x48", "-64x48", "64x 48",
                           "64x+48", "64x48 ", ""};
    char out[192], errors[1024];
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    for (int k = 0; k < 7; k++) {
        const char *args[] = {"--size", sizes[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "--size expects WIDTHxHEIGHT"), "'%s': %s",
                      sizes[k], errors);
    }
    /* --threads (chapter 12) and, before it, an unknown option alike */
    const char *counts[] = {" 2", "+2", "2 ", "0x2", ""};
    for (int k = 0; k < 5; k++) {
        const char *args[] = {"--threads", counts[k], "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, ": error: ") && strstr(errors, "Try '"),
                      "'%s': %s", counts[k], errors);
    }
    ck_assert(!file_exists(out));
    const char *good[] = {"--size", "0064x048", "-o", out, NULL};
    ck_assert_int_eq(run_bin(good, errors, sizeof errors), 0);
}
END_TEST

/* Does the file at path contain text? */
static bool file_contains(const char *path, const char *text)
{
    static char buf[1 << 16];
    size_t n = read_bytes(path, buf, sizeof buf - 1);
    buf[n] = '\0';
    return strstr(buf, text) != NULL;
}

START_TEST(test_a_usage_error_is_two_documented_lines)
{
    /* The error, then where help is: GNU's convention, which the README
     * states (the tests run in the repository's root). */
    char errors[1024], expected[1024];
    const char *bin = getenv("CHAPTER_BIN");
    const char *args[] = {"--sise", "64x48", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    snprintf(expected, sizeof expected,
             "%s: error: unknown option, found '--sise'\nTry '%s --help'.\n",
             bin, bin);
    ck_assert_str_eq(errors, expected);
    ck_assert_msg(file_contains("README.md",
                                "bin/chNN: error: unknown option, found "
                                "'--sise'\nTry 'bin/chNN --help'.\n"),
                  "README.md does not show the two lines");
}
END_TEST


/* Holds the running binary pid still for ms milliseconds: its clock goes
 * on, so that the render seems to have taken that much longer. */
static void pause_bin(pid_t pid, long ms)
{
    ck_assert_int_eq(kill(pid, SIGSTOP), 0);
    struct timespec t = {ms / 1000, (ms % 1000) * 1000000};
    nanosleep(&t, NULL);
    ck_assert_int_eq(kill(pid, SIGCONT), 0);
}

/* How many newlines tmpdir/stderr.txt holds so far. */
static int stderr_lines(void)
{
    char text[4096];
    size_t n = read_bytes(tmp_path("stderr.txt"), text, sizeof text);
    int lines = 0;
    for (size_t k = 0; k < n; k++)
        lines += text[k] == '\n';
    return lines;
}

START_TEST(test_a_long_render_shows_progress_lines_in_a_log)
{
    /* stderr is a file here, not a terminal. The render is held still for
     * 1.2 s as soon as it starts: it has then taken over a second, and a
     * line must follow. Held again for 1.2 s, it may not write another:
     * lines come at most every 10 s. */
    char folder[192], out[192], errors[4096];
    snprintf(folder, sizeof folder, "%s", tmp_path("log"));
    ck_assert_int_eq(mkdir(folder, 0755), 0);
    snprintf(out, sizeof out, "%.160s/out.png",
             folder); /* tmpdir is 24 bytes */
    const char *args[] = {"-o", out, "--size", "4096x4096", NULL};
    pid_t pid = start_bin(args, (run_limits){.alarm_seconds = 120});
    struct timespec ms = {0, 1000000};
    int waited = 0;
    /* the output is opened just before the render; a program that has
     * ended will open none */
    while (!has_entry_starting(folder, "out.png.tmp-") && !has_exited(pid) &&
           waited++ < 60000)
        nanosleep(&ms, NULL);
    pause_bin(pid, 1200);
    /* The line comes with the next row drawn after the render's first
     * second (the pause may come before the render starts, while the
     * image is made). Waited for by the work done, not by a clock: ten
     * CPU seconds of the program's make the image and thousands of rows,
     * even on a machine whose other tests take most of its memory's
     * bandwidth; a line ends the wait at once. */
    double start = cpu_seconds_of(pid);
    for (waited = 0; stderr_lines() == 0 && waited < 30000 &&
                     !has_exited(pid) &&
                     (start < 0 || cpu_seconds_of(pid) - start < 10.0);
         waited++)
        nanosleep(&ms, NULL);
    pause_bin(pid, 1200);
    struct timespec band = {0, 200000000}; /* many bands, were it per band */
    nanosleep(&band, NULL);
    kill(pid, SIGTERM);
    int status = finish_bin(pid, errors, sizeof errors);
    ck_assert_msg(status == 0 || status == 128 + SIGTERM, "status %d", status);
    ck_assert_msg(strchr(errors, '\r') == NULL, "a terminal's redrawn line: %s",
                  errors);
    ck_assert_msg(stderr_lines() == 1, "%d lines: %s", stderr_lines(), errors);
    ck_assert_msg(strstr(errors, "rendering: row ") || strstr(errors, "% "),
                  "%s", errors);
}
END_TEST

/* ------------------------------------------------- every signal, and SIGPIPE
 * and SIGXFSZ (a closed pipe, a file size limit) */

/* Starts $CHAPTER_BIN with args as start_bin does, but with stderr the
 * descriptor err, every signal at its default action, files limited to
 * max_file_bytes (> 0) and no core dump. */
static pid_t start_bin_as_is(const char *const *args, int err,
                             long max_file_bytes)
{
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert_ptr_nonnull(bin);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        const char *argv[16] = {bin};
        for (int k = 0; args[k] != NULL && k < 14; k++)
            argv[k + 1] = args[k];
        struct rlimit none = {0, 0}, size = {(rlim_t)max_file_bytes,
                                             (rlim_t)max_file_bytes};
        if (dup2(err, STDERR_FILENO) < 0 ||
            freopen("/dev/null", "w", stdout) == NULL ||
            setrlimit(RLIMIT_CORE, &none) != 0 ||
            (max_file_bytes > 0 && setrlimit(RLIMIT_FSIZE, &size) != 0))
            _exit(126);
        for (int sig = 1; sig < 32; sig++)
            if (sig != SIGKILL && sig != SIGSTOP)
                signal(sig, SIG_DFL);
        alarm(120); /* a binary that hangs ends */
        execv(bin, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

/* Waits until folder holds a file named out.png.tmp-*, the output of pid
 * being made. */
static void wait_for_temporary(pid_t pid, const char *folder)
{
    struct timespec ms = {0, 1000000};
    int waited = 0;
    while (!has_entry_starting(folder, "out.png.tmp-") && waited++ < 60000) {
        ck_assert_msg(!has_exited(pid), "the program ended before its output");
        nanosleep(&ms, NULL);
    }
    ck_assert_msg(waited < 60000, "no temporary file appeared");
}

START_TEST(test_every_stop_signal_leaves_no_temporary_file)
{
    /* Ctrl-\, a timer, a user's signal, a limit of processor time: each
     * ends the program as it would, with no temporary left. */
    const int stops[] = {SIGQUIT, SIGALRM, SIGUSR1, SIGXCPU};
    for (int k = 0; k < 4; k++) {
        char folder[192], out[192], errors[1024];
        snprintf(folder, sizeof folder, "%s/stop%d", tmpdir, k);
        ck_assert_int_eq(mkdir(folder, 0755), 0);
        snprintf(out, sizeof out, "%.160s/out.png", folder);
        const char *args[] = {"-o", out, "--size", "4096x4096", NULL};
        int err = open(tmp_path("stderr.txt"), O_WRONLY | O_CREAT | O_TRUNC,
                       0644);
        ck_assert_int_ge(err, 0);
        pid_t pid = start_bin_as_is(args, err, 0);
        close(err);
        wait_for_temporary(pid, folder);
        ck_assert_int_eq(kill(pid, stops[k]), 0);
        ck_assert_int_eq(finish_bin(pid, errors, sizeof errors),
                         128 + stops[k]);
        ck_assert_msg(count_entries(folder) == 0, "signal %d left a file",
                      stops[k]);
    }
}
END_TEST

START_TEST(test_a_file_size_limit_keeps_the_old_picture)
{
    /* ulimit -f: a write past the limit raises SIGXFSZ, whose default
     * action would end the program with its temporary half written. */
    static char bytes[65536];
    char path[192], errors[1024];
    size_t n = first_picture(path, sizeof path, bytes, sizeof bytes);
    const char *args[] = {"-o", path, "--size", "160x120", NULL};
    int err = open(tmp_path("stderr.txt"), O_WRONLY | O_CREAT | O_TRUNC,
                   0644);
    ck_assert_int_ge(err, 0);
    pid_t pid = start_bin_as_is(args, err, 512); /* the PNG is over 1900 */
    close(err);
    int status = finish_bin(pid, errors, sizeof errors);
    ck_assert_msg(status == 1, "status %d: %s", status, errors);
    ck_assert_msg(strstr(errors, "error: cannot write") != NULL, "stderr: %s",
                  errors);
    expect_picture_kept(path, bytes, n);
}
END_TEST

START_TEST(test_progress_to_a_closed_pipe_does_not_end_the_render)
{
    /* bin/chNN ... 2>&1 | head -1: the pipe of standard error closes; a
     * progress line written to it must not cost the picture. The program
     * is held still for 1.2 s as it starts its render, so that it has run
     * for over a second and writes a line after the next band. */
    char folder[192], out[192], errors[1024];
    snprintf(folder, sizeof folder, "%s", tmp_path("pipe"));
    ck_assert_int_eq(mkdir(folder, 0755), 0);
    snprintf(out, sizeof out, "%.160s/out.png", folder);
    char sky[192]; /* the sky alone: cheap in every chapter */
    snprintf(sky, sizeof sky, "%s",
             write_file("sky.scene", "image 2048 2048\n"));
    const char *args[] = {sky, "-o", out, NULL};
    int ends[2];
    ck_assert_int_eq(pipe(ends), 0);
    /* the program gets the write end as stderr (dup2 keeps that one open
     * across execv), and neither end otherwise: no reader is left */
    ck_assert_int_eq(fcntl(ends[0], F_SETFD, FD_CLOEXEC), 0);
    ck_assert_int_eq(fcntl(ends[1], F_SETFD, FD_CLOEXEC), 0);
    pid_t pid = start_bin_as_is(args, ends[1], 0);
    close(ends[1]);
    close(ends[0]); /* nobody reads: a write gets EPIPE, or SIGPIPE */
    wait_for_temporary(pid, folder);
    pause_bin(pid, 1200);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0,
                  "ended by signal %d, status %d",
                  WIFSIGNALED(status) ? WTERMSIG(status) : 0,
                  WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    (void)errors;
    ck_assert(file_exists(out));
    ck_assert_int_eq(count_entries(folder), 1); /* no temporary left */
}
END_TEST

START_TEST(test_the_png_memory_is_taken_before_the_render)
{
#ifndef TEST_ASAN
    /* A 4096 x 4096 image is 384 MiB of doubles, its PNG's bytes 48 MiB
     * more: with 408 MiB of address space the image fits and the bytes do
     * not, which must show before the render, not after it. */
    char errors[1024];
    write_file("sky.scene", "image 4096 4096\n");
    char scene_path[192], out[192];
    snprintf(scene_path, sizeof scene_path, "%s", tmp_path("sky.scene"));
    snprintf(out, sizeof out, "%s", tmp_path("sky.png"));
    const char *args[] = {scene_path, "-o", out, NULL};
    int status = run_bin_limited(args, errors, sizeof errors,
                                 (run_limits){.max_memory_bytes = 408L << 20,
                                              .alarm_seconds = 120});
    ck_assert_msg(status == 1, "status %d: %s", status, errors);
    ck_assert_msg(strstr(errors, "no memory for a 4096x4096 image and its "
                                 "PNG") != NULL,
                  "stderr: %s", errors);
    ck_assert(!file_exists(out));
#endif
}
END_TEST

Suite *ch01_robustness_suite(void)
{
    Suite *s = suite_create("ch01 robustness");
    TCase *scenes = tcase_create("edge cases");
    tcase_add_checked_fixture(scenes, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(scenes, 120);
    tcase_add_test(scenes,
                   test_degenerate_scenes_render_finite_or_are_rejected);
    tcase_add_test(scenes, test_degenerate_scenes_have_only_finite_pixels);
    suite_add_tcase(s, scenes);

    TCase *output = tcase_create("output safety");
    tcase_add_checked_fixture(output, make_tmpdir, remove_tmpdir);
    tcase_add_test(output, test_a_bad_scene_keeps_the_old_picture);
    tcase_add_test(output, test_an_unwritable_folder_keeps_the_old_picture);
    tcase_add_test(output, test_a_full_disk_keeps_the_old_picture);
    tcase_add_test(output, test_writing_to_dev_full_is_reported);
    suite_add_tcase(s, output);

    TCase *where = tcase_create("where the output goes");
    tcase_add_checked_fixture(where, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(where, 180);
    tcase_add_test(where, test_a_fifo_is_written_in_place);
    tcase_add_test(where, test_a_device_is_written_in_place);
    tcase_add_test(where, test_dash_is_standard_output);
    tcase_add_test(where, test_dev_stdout_is_written_through_its_link);
    tcase_add_test_in_a_process(where,
                                test_output_errors_come_before_the_render);
    tcase_add_test(where, test_a_replaced_file_keeps_its_mode);
    tcase_add_test(where, test_a_read_only_file_is_not_replaced);
    tcase_add_test(where, test_a_signal_leaves_no_temporary_file);
    tcase_add_slow_test(where,
                        test_a_long_render_shows_progress_lines_in_a_log);
    suite_add_tcase(s, where);

    TCase *input = tcase_create("hostile input files");
    tcase_add_checked_fixture(input, make_tmpdir, remove_tmpdir);
    tcase_add_test(input, test_a_scene_must_be_a_regular_file);
    tcase_add_test(input, test_a_byte_order_mark_is_skipped);
    tcase_add_test(input, test_numbers_may_have_any_number_of_digits);
    tcase_add_test(input, test_a_whole_number_too_large_is_out_of_range);
    tcase_add_test(input, test_errors_escape_what_a_terminal_would_obey);
    tcase_add_test(input, test_long_file_names_are_named_in_full);
    suite_add_tcase(s, input);

    TCase *io = tcase_create("inputs and outputs");
    tcase_add_checked_fixture(io, make_tmpdir, remove_tmpdir);
    tcase_add_test(io, test_the_output_may_not_be_an_input);
    tcase_add_test(io, test_a_name_that_fits_has_a_temporary_that_fits);
    tcase_add_test(io, test_command_line_numbers_are_digits_only);
    tcase_add_test(io, test_a_usage_error_is_two_documented_lines);
    suite_add_tcase(s, io);

    TCase *signals = tcase_create("every way a run may end");
    tcase_add_checked_fixture(signals, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(signals, 180);
    tcase_add_test(signals, test_every_stop_signal_leaves_no_temporary_file);
    tcase_add_test(signals, test_a_file_size_limit_keeps_the_old_picture);
    tcase_add_slow_test(signals,
                        test_progress_to_a_closed_pipe_does_not_end_the_render);
    tcase_add_test_in_a_process(signals,
                                test_the_png_memory_is_taken_before_the_render);
    suite_add_tcase(s, signals);
    return s;
}

