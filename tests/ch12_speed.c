/* ch12_speed.c: rendering on all cores (chapter 12).
 *
 * A pixel depends only on its ray, so the number of threads may change how
 * soon the picture is done, never what it is: every test here renders the
 * same scene on several thread counts and compares the outputs byte for
 * byte, or the counts of --stats line for line. */
#define _XOPEN_SOURCE 700 /* posix_openpt: a terminal for the progress */
#include <check.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/syscall.h>
#endif

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

/* The counts --stats prints for --threads n: not the times, the rates,
 * nor the threads' own lines (the helpers started, the parts read). */
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
            !strstr(line, "built in") && !strstr(line, "pool threads") &&
            !strstr(line, "meshes read"))
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

/* --stats says how the scene's OBJ file was read (the teapot's 124,599
 * bytes: two parts of OBJ_MIN_PART_BYTES at most, on any number of
 * threads above one) and how many helpers the pool started: one fewer
 * than the threads asked for, the bands being more than the threads. */
START_TEST(test_stats_count_the_parts_read_and_the_threads_started)
{
    char errors[4096], scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s", teapot_scene());
    const char *args[] = {scene_path, "--threads", "3",
                          "--stats",  "-o",        tmp_path("s.png"),
                          NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, "\nmeshes read        1 in parts "
                                 "(2 parts), 0 by one thread\n"),
                  "%s", errors);
    ck_assert_msg(strstr(errors, "\npool threads       2 started for the "
                                 "run\n"),
                  "%s", errors);
    ck_assert_ptr_nonnull(strstr(errors, "\none-thread time    file read "));
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

/* ------------------------------------------------------------ the progress */

#ifdef __linux__
/* The calendar's clock, as this process reads it, this many seconds ahead
 * of the system's (or behind): the date set while the program runs. Every
 * call of the suites' and the program's code in this runner comes here;
 * the system's own clock is asked directly. */
static atomic_long calendar_shift;

int clock_gettime(clockid_t clock, struct timespec *t)
{
    int r = (int)syscall(SYS_clock_gettime, clock, t);
    if (r == 0 && clock == CLOCK_REALTIME)
        t->tv_sec += atomic_load(&calendar_shift);
    return r;
}
#endif

static double monotonic_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* How often the reporter told its progress before the image was done. */
static void count_progress(void *context, int rows_done, int rows,
                           long long rays_done)
{
    (void)rays_done;
    if (rows_done < rows)
        ++*(int *)context;
}

#ifdef __linux__
/* Renders a floor lit by an area light of 1024 shadow rays a point, 160
 * pixels wide and rows high, on two threads, with the calendar's clock
 * shift seconds off;
 * counts the reporter's reports into *reports and returns the seconds the
 * render took on the monotonic clock. */
static double render_with_the_date_off(long shift, int rows, int *reports)
{
    char text[256];
    snprintf(text, sizeof text,
             "image 160 %d\n"
             "light area position 0 5 6 direction 0 -1 0 radius 1 "
             "samples 1024\n"
             "sphere center 0 -1001 6 radius 1000\n"
             "sphere center 0 0 6 radius 0.5\n", rows);
    scene s;
    scene_error err;
    scene_init(&s);
    ck_assert_msg(scene_parse(&s, text, strlen(text), "t", &err), "%s",
                  err.message);
    image img;
    ck_assert(image_init(&img, 160, rows));
    render_stats st = {0};
    *reports = 0;
    atomic_store(&calendar_shift, shift);
    double start = monotonic_seconds();
    render_in_bands(&s, &img,
                    &(render_settings){.threads = 2,
                                       .progress = count_progress,
                                       .progress_context = reports},
                    &st);
    double took = monotonic_seconds() - start;
    atomic_store(&calendar_shift, 0);
    image_free(&img);
    scene_free(&s);
    return took;
}
#endif

/* The render's reporter shows the progress four times a second while the
 * date is set an hour ahead or an hour back: its waits end on the
 * monotonic clock. On the calendar's, an hour ahead would hold it the
 * whole render, an hour back make it report without a pause. */
START_TEST(test_the_reporter_keeps_to_the_monotonic_clock)
{
#ifdef __linux__
    const long shifts[] = {3600, -3600};
    int rows = 120; /* the second date starts where the first ended */
    for (int k = 0; k < 2; k++) {
        /* a second or so of work, whatever the machine's speed: the
         * rows doubled until the render takes 0.75 s */
        int reports = 0;
        double took = render_with_the_date_off(shifts[k], rows, &reports);
        while (took < 0.75 && rows < 120 * 16) {
            rows *= 2;
            took = render_with_the_date_off(shifts[k], rows, &reports);
        }
        /* a report every quarter second, give or take one */
        ck_assert_msg(took < 0.75 || reports >= 1,
                      "date %+ld s: no report in %.2f s", shifts[k], took);
        ck_assert_msg(reports <= 4 * took + 2,
                      "date %+ld s: %d reports in %.2f s", shifts[k], reports,
                      took);
        ck_assert_msg(took >= 0.75, "the render took %.2f s only", took);
    }
#endif
}
END_TEST

/* The test's clock and the program's processor time at one moment. */
typedef struct {
    double at, cpu; /* seconds */
} moment;

/* What the progress bar said, and when: some time after the test began
 * the read before the one that brought it (that read would have brought
 * it otherwise), and before the test saw it. */
typedef struct {
    double rate, left; /* rays a second; seconds */
    int percent;
    moment after, seen;
} bar_seen;

/* Reads one bar line "[###  ]  40%  2.31 Mrays/s  3 s left"; false if
 * line is not one. */
static bool read_bar(const char *line, bar_seen *b)
{
    const char *end = strchr(line, ']');
    char prefix[4] = "";
    if (line[0] != '[' || end == NULL)
        return false;
    int n = sscanf(end + 1, " %d%% %lf %3[kMGT]rays/s %lf s left",
                   &b->percent, &b->rate, prefix, &b->left);
    if (n != 4) /* no prefix: rays a second */
        n = sscanf(end + 1, " %d%% %lf rays/s %lf s left", &b->percent,
                   &b->rate, &b->left) + 1;
    if (n != 4)
        return false;
    b->rate *= prefix[0] == 'k' ? 1e3 : prefix[0] == 'M' ? 1e6
             : prefix[0] == 'G' ? 1e9 : prefix[0] == 'T' ? 1e12 : 1;
    return true;
}

/* The value of the --stats line that starts with name, or -1. */
static double stats_value(const char *text, const char *name)
{
    const char *at = strstr(text, name);
    double v;
    return at && sscanf(at + strlen(name), " %lf", &v) == 1 ? v : -1;
}

/* The truth of a render at one moment (see below). */
typedef struct {
    double elapsed, done, left, rate, slack;
} truth;

static truth truth_at(moment m, double render_start, double cpu_scene,
                      double cpu_render, double rays)
{
    truth t;
    t.elapsed = m.at - render_start;
    t.done = (m.cpu - cpu_scene) / cpu_render;
    t.left = t.elapsed * (1 - t.done) / t.done;
    t.rate = rays * t.done / t.elapsed;
    /* besides the factor of two: half a second for the whole seconds
     * shown, and the time of a band (8 rows of 360) at the pace so far,
     * the band in hand, whose rows count only once it is done */
    t.slack = 0.5 + t.elapsed * (8.0 / 360) / t.done;
    return t;
}

/* What a render on a terminal showed: its bars, and its --stats. */
typedef struct {
    char text[1 << 16];
    bar_seen bars[2048];
    int count;    /* bars read */
    double ended; /* when the program had gone, on the test's clock */
} watched_render;

/* Renders the scene at scene_path on one thread, its stderr a terminal
 * the test reads, into *w. */
static void watch_render(const char *scene_path, watched_render *w)
{
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    ck_assert_int_ge(master, 0);
    ck_assert(grantpt(master) == 0 && unlockpt(master) == 0);
    char terminal[128];
    snprintf(terminal, sizeof terminal, "%s", ptsname(master));
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert_ptr_nonnull(bin);
    char out[192];
    snprintf(out, sizeof out, "%s", tmp_path("uneven.png"));
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        int slave = open(terminal, O_RDWR | O_NOCTTY);
        if (slave < 0 || dup2(slave, STDERR_FILENO) < 0 ||
            freopen("/dev/null", "w", stdout) == NULL)
            _exit(126);
        close(master);
        alarm(120);
        execl(bin, bin, scene_path, "--threads", "1", "--stats", "-o", out,
              (char *)NULL);
        _exit(127);
    }
    /* held still for a second a tenth of a second into its render: the
     * bar, which comes a second into the program, then shows from early
     * in the work on, where an order of bands that misleads shows most */
    struct timespec ms = {0, 1000000}, still = {1, 0};
    for (int waited = 0; waited < 60000 && !has_exited(pid) &&
                         cpu_seconds_of(pid) < 0.1;
         waited++)
        nanosleep(&ms, NULL);
    ck_assert_int_eq(kill(pid, SIGSTOP), 0);
    nanosleep(&still, NULL);
    ck_assert_int_eq(kill(pid, SIGCONT), 0);
    size_t length = 0;
    w->count = 0;
    moment last_read = {-1, -1}; /* when the read before began */
    for (;;) { /* read until the program has gone */
        struct pollfd in = {master, POLLIN, 0};
        if (poll(&in, 1, 100) == 0)
            continue;
        moment this_read = {monotonic_seconds(), cpu_seconds_of(pid)};
        ssize_t n = read(master, w->text + length,
                         sizeof w->text - 1 - length);
        if (n <= 0)
            break; /* EIO: no program has the terminal any more */
        moment now = {monotonic_seconds(), cpu_seconds_of(pid)};
        size_t from = length;
        length += (size_t)n;
        w->text[length] = '\0';
        /* each bar begins with a carriage return */
        for (char *at = strchr(w->text + from, '\r');
             at != NULL && w->count < 2048; at = strchr(at + 1, '\r'))
            if (read_bar(at + 1, &w->bars[w->count])) {
                w->bars[w->count].after = last_read;
                w->bars[w->count++].seen = now;
            }
        last_read = this_read;
    }
    w->ended = monotonic_seconds();
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    close(master);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s",
                  w->text);
}

/* Judges every bar of w from the first tenth of its work on (below);
 * how many it judged. */
static int judge_bars(const watched_render *w)
{
    const char *text = w->text;
    /* "time  scene N ms, render N ms, write N ms", then the same line of
     * processor time */
    const char *wall = strstr(text, "\ntime "), *cpu = strstr(text,
                                                            "\nprocessor time");
    ck_assert_msg(wall && cpu, "%s", text);
    double render = stats_value(wall, "render") / 1e3;
    double write = stats_value(wall, "write") / 1e3;
    double cpu_scene = stats_value(cpu, "scene") / 1e3;
    double cpu_render = stats_value(cpu, "render") / 1e3;
    double rays = stats_value(text, "primary rays") +
                  stats_value(text, "shadow rays") +
                  stats_value(text, "reflection rays") +
                  stats_value(text, "refraction rays");
    ck_assert_msg(render > 0 && write >= 0 && cpu_render > 0 && rays > 0,
                  "%s", text);
    /* The truth at a moment: the share of the render's work done, read
     * as the processor time it has used (one thread renders). A machine
     * that others load changes the pace of the wall clock, which no
     * estimate can foresee; at the pace so far, the work left takes
     * elapsed * (1 - done) / done, and the rays traced so far are that
     * share of all of them. A bar is judged against the truth at both
     * ends of the time in which it was written: a loaded machine may keep
     * the test from reading for a while. */
    double render_start = w->ended - write - render;
    int judged = 0;
    for (int k = 0; k < w->count; k++) {
        const bar_seen *b = &w->bars[k];
        truth early = truth_at(b->after, render_start, cpu_scene, cpu_render,
                               rays);
        truth late = truth_at(b->seen, render_start, cpu_scene, cpu_render,
                              rays);
        /* from the first tenth of the work on, to the last twentieth:
         * there the processor time that is not the render's (the
         * reporter's turns, a sanitizer's) outweighs what is left */
        if (b->after.cpu < 0 || early.done < 0.1 || late.done > 0.95)
            continue;
        judged++;
        double most = fmax(2 * early.left + early.slack,
                           2 * late.left + late.slack);
        double least = fmin(early.left / 2 - early.slack,
                            late.left / 2 - late.slack);
        ck_assert_msg(b->left <= most && b->left >= least,
                      "between %.2f and %.2f s of %.2f s, %.0f%% to %.0f%% "
                      "of the work, %d%% of the rows: %.0f s left, truly "
                      "%.2f to %.2f", early.elapsed, late.elapsed, render,
                      100 * early.done, 100 * late.done, b->percent, b->left,
                      late.left, early.left);
        ck_assert_msg(b->rate <= 2 * fmax(early.rate, late.rate) &&
                          b->rate >= fmin(early.rate, late.rate) / 2,
                      "between %.2f and %.2f s of %.2f s: %.3g rays/s, "
                      "truly %.3g to %.3g", early.elapsed, late.elapsed,
                      render, b->rate, early.rate, late.rate);
    }
    return judged;
}

/* A picture whose upper half is sky, one ray a pixel, and whose lower
 * half a floor lit through 128 shadow rays a point: its lower bands cost
 * a hundred times its upper ones (the samples doubled, up to 1024, on a
 * machine so fast that the render is over before the bar can judge it).
 * Drawn on one thread with stderr a terminal, each bar from the first
 * tenth of the work on must give the time left within a factor of two,
 * and the rate of rays within a factor of two (judge_bars, what "truly"
 * means). Drawn from the top down, its bars would promise the end at once:
 * a second left, say, where ten remain. */
START_TEST(test_the_time_left_holds_when_bands_cost_differently)
{
    static watched_render w;
    int judged = 0;
    for (int samples = 128; judged < 2 && samples <= 1024; samples *= 2) {
        char scene[512], scene_path[192];
        snprintf(scene, sizeof scene,
                 "image 480 360\n"
                 "light area position 0 5 6 direction 0 -1 0 radius 1 "
                 "samples %d\n"
                 "sphere center 0 -1001 6 radius 1000\n"
                 "sphere center 0 -0.5 6 radius 0.3\n", samples);
        snprintf(scene_path, sizeof scene_path, "%s",
                 write_file("uneven.scene", scene));
        watch_render(scene_path, &w);
        judged = judge_bars(&w);
    }
    ck_assert_msg(judged >= 2, "%d bars judged of %d: %s", judged, w.count,
                  w.text);
}
END_TEST

/* Reading a scene of 350,000 spheres and building their tree takes
 * seconds: the line says so (here a log, a line after the program's first
 * second). The program is held still for 1.2 s as soon as it has used a
 * twentieth of a second of processor time, in the middle of its loading;
 * the line must come before the render, a picture of 8 x 6 pixels that
 * takes no time. */
START_TEST(test_a_long_load_says_what_it_does)
{
    enum { SPHERES = 350000 };
    static char text[SPHERES * 40];
    size_t n = 0;
    unsigned seed = 12345;
    for (int k = 0; k < SPHERES && n + 64 < sizeof text; k++) {
        seed = seed * 1103515245u + 12345u;
        int x = (int)(seed >> 8) % 600 - 300, y = (int)(seed >> 4) % 400;
        n += (size_t)snprintf(text + n, sizeof text - n,
                              "sphere center %d %d %d radius .02\n", x,
                              y - 200, 400 + k % 600);
    }
    char scene_path[192];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_bytes("many.scene", text, n));
    const char *args[] = {scene_path, "--size", "8x6", "-o",
                          tmp_path("many.png"), NULL};
    pid_t pid = start_bin(args, (run_limits){.alarm_seconds = 120});
    struct timespec ms = {0, 1000000};
    for (int waited = 0; waited < 60000 && !has_exited(pid) &&
                         cpu_seconds_of(pid) < 0.05;
         waited++)
        nanosleep(&ms, NULL);
    ck_assert_int_eq(kill(pid, SIGSTOP), 0);
    struct timespec still = {1, 200000000};
    nanosleep(&still, NULL);
    ck_assert_int_eq(kill(pid, SIGCONT), 0);
    char errors[4096];
    ck_assert_int_eq(finish_bin(pid, errors, sizeof errors), 0);
    ck_assert_msg(strncmp(errors, "reading the scene", 17) == 0 ||
                      strncmp(errors, "building the trees", 18) == 0,
                  "stderr: %s", errors);
}
END_TEST

Suite *ch12_speed_suite(void)
{
    Suite *s = suite_create("ch12 speed");
    TCase *threads = tcase_create("threads");
    tcase_add_checked_fixture(threads, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(threads, 120);
    tcase_add_test(threads, test_thread_count_does_not_change_the_image);
    tcase_add_test(threads, test_ties_come_out_alike_on_any_number_of_threads);
    tcase_add_test(threads, test_statistics_add_up_whatever_the_thread_count);
    tcase_add_test(threads, test_bad_thread_counts_are_usage_errors);
    tcase_add_test(threads, test_the_kd_trees_line_holds_no_bvh_build_time);
    tcase_add_test(threads,
                   test_stats_count_the_parts_read_and_the_threads_started);
    tcase_add_threaded_test(threads,
                            test_bands_on_threads_draw_what_one_render_draws);
    tcase_add_threaded_test(threads,
                            test_the_threads_counts_add_up_to_one_renders);
    tcase_add_threaded_test(threads,
                            test_a_tall_image_on_four_threads_is_one_renders);
    suite_add_tcase(s, threads);

    TCase *progress = tcase_create("progress");
    tcase_add_checked_fixture(progress, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(progress, 120);
    tcase_add_slow_test(progress,
                        test_the_reporter_keeps_to_the_monotonic_clock);
    tcase_add_slow_test(progress,
                        test_the_time_left_holds_when_bands_cost_differently);
    tcase_add_slow_test(progress, test_a_long_load_says_what_it_does);
    suite_add_tcase(s, progress);
    return s;
}
