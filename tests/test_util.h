/* test_util.h: helpers shared by the chapter suites: a temporary folder per
 * test, files written into it, and running the chapter's binary.
 *
 * Each suite that includes this gets its own copies (everything is static
 * inline). The binary under test is named by $CHAPTER_BIN, which the
 * Makefile sets to bin/chNN for the chapter whose program is being tested. */
#ifndef TEST_UTIL_H
#define TEST_UTIL_H

#include <check.h>
#include "shard.h"
#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "scene_file.h"

/* TEST_ASAN: AddressSanitizer is in the build (GCC says so with a macro,
 * Clang with __has_feature); it reserves terabytes of address space, so a
 * test that limits a program's memory cannot run under it. */
#if defined(__SANITIZE_ADDRESS__)
#define TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TEST_ASAN 1
#endif
#endif

static char tmpdir[64];

/* Fixtures: a fresh, empty folder for every test, removed afterwards. */
static inline void make_tmpdir(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/rt-test-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(tmpdir));
}

/* Removes path and all a folder there holds, symbolic links not followed,
 * as rm -rf does, but in this process: every test of a fixture calls it,
 * and a shell and an rm cost more than many a test. 0 when all is gone. */
static inline int remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? 0 : -1;
    if (!S_ISDIR(st.st_mode))
        return unlink(path);
    int status = 0;
    DIR *d = opendir(path);
    if (d == NULL)
        status = -1;
    for (struct dirent *e; d != NULL && (e = readdir(d)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char child[4096];
        int n = snprintf(child, sizeof child, "%s/%s", path, e->d_name);
        if (n < 0 || (size_t)n >= sizeof child || remove_tree(child) != 0)
            status = -1;
    }
    if (d != NULL)
        closedir(d);
    return rmdir(path) == 0 ? status : -1;
}

static inline void remove_tmpdir(void)
{
    if (remove_tree(tmpdir) != 0)
        fprintf(stderr, "could not remove %s\n", tmpdir);
}

/* tmpdir/name, in a buffer that the next call reuses. */
static inline const char *tmp_path(const char *name)
{
    static char path[192];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    return path;
}

/* Writes length bytes of text to tmpdir/name; returns the path. */
static inline const char *write_bytes(const char *name, const char *text,
                                      size_t length)
{
    const char *path = tmp_path(name);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fwrite(text, 1, length, f), length);
    fclose(f);
    return path;
}

static inline const char *write_file(const char *name, const char *text)
{
    return write_bytes(name, text, strlen(text));
}

/* tmpdir/meshes: a link to the project's meshes/, so that a scene written
 * to tmpdir finds them as the chapters' scenes do. */
static inline void link_meshes(void)
{
    char target[4096];
    ck_assert_ptr_nonnull(getcwd(target, sizeof target - 16));
    strcat(target, "/meshes");
    ck_assert_int_eq(symlink(target, tmp_path("meshes")), 0);
}

static inline bool file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Chapter NN's folder of scenes: the committed tangle's (src/chNN/scenes),
 * or, in a handout, which has no src/, the build's tangle of it. */
static inline const char *chapter_scene_folder(const char *chapter)
{
    static char path[128];
    snprintf(path, sizeof path, "src/%s/scenes", chapter);
    if (!file_exists(path))
        snprintf(path, sizeof path, "build/tangle/%s/scenes", chapter);
    return path;
}

/* The scene file name of chapter NN's folder of scenes. */
static inline const char *chapter_scene(const char *chapter,
                                        const char *name)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", chapter_scene_folder(chapter),
             name);
    return path;
}

/* How many entries the folder has (. and .. not counted), as ls -A | wc -l
 * counts them (a folder that is not there has none, a file is one), in
 * this process. */
static inline int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        struct stat st;
        return errno == ENOTDIR && stat(dir, &st) == 0 ? 1 : 0;
    }
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}

/* How run_bin_limited restricts the child before it runs the binary. */
typedef struct {
    bool as_nobody;          /* when run as root: drop to uid/gid 65534 */
    long max_file_bytes; /* > 0: RLIMIT_FSIZE, a disk that is full past this */
    long max_memory_bytes; /* > 0: RLIMIT_AS, a machine with that little memory
                            */
    unsigned alarm_seconds;  /* > 0: SIGALRM ends a binary that hangs */
    const char *stdout_path; /* where its stdout goes; NULL: /dev/null */
} run_limits;

static inline void apply_limits(run_limits limits)
{
    if (limits.max_file_bytes > 0) {
        struct rlimit r = {(rlim_t)limits.max_file_bytes,
                           (rlim_t)limits.max_file_bytes};
        signal(SIGXFSZ,
               SIG_IGN); /* a write past the limit fails instead of killing */
        if (setrlimit(RLIMIT_FSIZE, &r) != 0)
            _exit(126);
    }
    if (limits.max_memory_bytes > 0) {
        struct rlimit r = {(rlim_t)limits.max_memory_bytes,
                           (rlim_t)limits.max_memory_bytes};
        if (setrlimit(RLIMIT_AS, &r) != 0)
            _exit(126);
    }
    if (limits.as_nobody && geteuid() == 0 &&
        (setgid(65534) != 0 || setuid(65534) != 0))
        _exit(126);
    signal(SIGINT, SIG_DFL); /* a background shell may have ignored them */
    signal(SIGTERM, SIG_DFL);
    alarm(limits.alarm_seconds); /* kept across execv */
}

/* Starts $CHAPTER_BIN with the NULL-ended args under the limits, its stderr
 * going to tmpdir/stderr.txt; returns its process id. */
static inline pid_t start_bin(const char *const *args, run_limits limits)
{
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert_msg(bin != NULL, "set CHAPTER_BIN to the chapter's binary");
    char err_path[128];
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", tmpdir);
    const char *out_path =
        limits.stdout_path ? limits.stdout_path : "/dev/null";
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        const char *argv[16] = {bin};
        for (int k = 0; args[k] != NULL && k < 14; k++)
            argv[k + 1] = args[k];
        if (freopen(err_path, "w", stderr) == NULL ||
            freopen(out_path, "w", stdout) == NULL)
            _exit(127);
        apply_limits(limits);
        execv(bin, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

/* What the last binary that finish_bin waited for did, measured by the work
 * rather than by a clock (which a loaded machine or a sanitizer slows):
 * the bytes it read (rchar of /proc/PID/io: files, pipes and its own shared
 * libraries; -1 where /proc/PID/io cannot be read, as off Linux) and its
 * peak resident memory in KiB (on Linux the larger of its own and that of
 * the test process it was forked from, as it stood before execv: a test
 * that reads it is added with tcase_add_test_in_a_process). */
static long long last_run_bytes_read;
static long last_run_peak_kib;

/* rchar of /proc/pid/io, or -1 when there is no such file to read. */
static inline long long proc_bytes_read(pid_t pid)
{
    char path[64], line[128];
    snprintf(path, sizeof path, "/proc/%ld/io", (long)pid);
    FILE *f = fopen(path, "r");
    long long n = -1;
    while (f != NULL && fgets(line, sizeof line, f) != NULL)
        if (sscanf(line, "rchar: %lld", &n) == 1)
            break;
    if (f)
        fclose(f);
    return n;
}

/* Whether child PID has ended, without reaping it (finish_bin does). */
static inline bool has_exited(pid_t pid)
{
    siginfo_t info = {0};
    return waitid(P_PID, (id_t)pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
           info.si_pid == pid;
}

/* The CPU seconds child pid has used so far (user and system, all its
 * threads: fields 14 and 15 of /proc/PID/stat), or -1 where that file
 * cannot be read, as off Linux. */
static inline double cpu_seconds_of(pid_t pid)
{
    char path[64];
    snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
    FILE *f = fopen(path, "r");
    unsigned long user = 0, system = 0;
    /* the name, field 2, is in parentheses and may hold spaces */
    int read = f ? fscanf(f, "%*d (%*[^)]) %*c %*d %*d %*d %*d %*d %*u %*u "
                             "%*u %*u %*u %lu %lu",
                          &user, &system)
                 : 0;
    if (f)
        fclose(f);
    return read == 2 ? (double)(user + system) / sysconf(_SC_CLK_TCK) : -1;
}

/* Waits for the binary started as pid; returns its exit status (128 + the
 * signal that ended it) and puts what it wrote on stderr into errors[size]. */
static inline int finish_bin(pid_t pid, char *errors, size_t size)
{
    /* WNOWAIT leaves the child a zombie, whose /proc/PID/io is still there
     * to read; wait4 then reaps it and gives its resource usage. */
    siginfo_t info;
    ck_assert_int_eq(waitid(P_PID, (id_t)pid, &info, WEXITED | WNOWAIT), 0);
    last_run_bytes_read = proc_bytes_read(pid);
    int status;
    struct rusage usage;
    ck_assert_int_eq(wait4(pid, &status, 0, &usage), pid);
#ifdef __APPLE__
    last_run_peak_kib = usage.ru_maxrss / 1024; /* bytes on macOS */
#else
    last_run_peak_kib = usage.ru_maxrss; /* KiB on Linux and the BSDs */
#endif
    char err_path[128];
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", tmpdir);
    FILE *f = fopen(err_path, "r");
    size_t n = f ? fread(errors, 1, size - 1, f) : 0;
    errors[n] = '\0';
    if (f)
        fclose(f);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Runs $CHAPTER_BIN with the NULL-ended args under the limits; returns its
 * exit status and puts what it wrote on stderr into errors[size]. */
static inline int run_bin_limited(const char *const *args, char *errors,
                                  size_t size, run_limits limits)
{
    return finish_bin(start_bin(args, limits), errors, size);
}

static inline int run_bin(const char *const *args, char *errors, size_t size)
{
    return run_bin_limited(args, errors, size, (run_limits){0});
}

/* scene_init, then parse text[0..length) as the file called name. */
static inline bool parse_named(scene *s, const char *text, size_t length,
                               const char *name, scene_error *err)
{
    scene_init(s);
    return scene_parse(s, text, length, name, err);
}

static inline bool parse_text(scene *s, const char *text, scene_error *err)
{
    return parse_named(s, text, strlen(text), "test.scene", err);
}

/* Asserts that err is an error in file at line:col whose message contains
 * part; what names the rejected input in a failure message. */
static inline void expect_error_at(const parse_error *err, const char *file,
                                   int line, int col, const char *part,
                                   const char *what)
{
    ck_assert_str_eq(err->file, file);
    ck_assert_msg(err->line == line && err->col == col,
                  "'%s': error at %d:%d (%s), expected %d:%d", what, err->line,
                  err->col, err->message, line, col);
    ck_assert_msg(strstr(err->message, part) != NULL,
                  "'%s': message '%s' lacks '%s'", what, err->message, part);
}

/* Asserts that the text is rejected with an error at line:col of the file
 * called name, whose message contains part. */
static inline void expect_parse_error_named(const char *name, const char *text,
                                            size_t length, int line, int col,
                                            const char *part)
{
    scene s;
    scene_error err;
    ck_assert_msg(!parse_named(&s, text, length, name, &err), "accepted: %s",
                  text);
    expect_error_at(&err, name, line, col, part, text);
    scene_free(&s);
}

#define expect_parse_error(text, line, col, part)                              \
    expect_parse_error_named("bad.scene", (text), strlen(text), (line), (col), \
                             (part))

#endif
