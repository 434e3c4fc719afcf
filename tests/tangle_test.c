/*
 * Tests for tools/book/tangle.c.
 *
 * Every test writes small chapters into a fresh temporary directory, runs
 * the tangler there as a subprocess (its path comes from the environment
 * variable TANGLE) and checks the exact bytes it wrote, what it said on
 * stderr and its exit status.  The suite has no main(): the shared test
 * runner calls tangle_suite().
 */
#include <check.h>
#include "shard.h"
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <dirent.h>
#include <time.h>
#include <unistd.h>

Suite *tangle_suite(void);

/* Set up afresh for every test by the fixture (Check forks each test). */
static char work_dir[sizeof "/tmp/tangle-test-XXXXXX"];
static char *tangle_path;

struct run {
    int status;   /* exit status, or 128 + signal */
    char *out;    /* everything written to stdout */
    char *err;    /* everything written to stderr */
};

/* ---- files in the test directory ----------------------------------- */

static char *work_path(const char *name)
{
    char *path = malloc(strlen(work_dir) + strlen(name) + 2);
    ck_assert_ptr_nonnull(path);
    sprintf(path, "%s/%s", work_dir, name);
    return path;
}

static void put_bytes(const char *name, const char *data, size_t len)
{
    char *path = work_path(name);
    for (char *p = strchr(path + 1, '/'); p; p = strchr(p + 1, '/')) {
        *p = '\0';
        mkdir(path, 0777); /* parents of the file; most already exist */
        *p = '/';
    }
    FILE *f = fopen(path, "wb");
    ck_assert_msg(f != NULL, "cannot create %s", path);
    ck_assert_uint_eq(fwrite(data, 1, len, f), len);
    ck_assert_int_eq(fclose(f), 0);
    free(path);
}

static void put(const char *name, const char *text)
{
    put_bytes(name, text, strlen(text));
}

/* The contents of NAME (NUL-terminated for convenience), or NULL. */
static char *slurp(const char *name, size_t *len)
{
    char *path = work_path(name), *data = NULL;
    size_t size = 0;
    FILE *f = fopen(path, "rb");
    free(path);
    if (!f)
        return NULL;
    FILE *mem = open_memstream(&data, &size);
    ck_assert_ptr_nonnull(mem);
    for (int c; (c = getc(f)) != EOF;)
        putc(c, mem);
    fclose(f);
    fclose(mem);
    if (len)
        *len = size;
    return data;
}

static void assert_file(const char *name, const char *expected)
{
    size_t len;
    char *actual = slurp(name, &len);
    ck_assert_msg(actual != NULL, "%s was not written", name);
    ck_assert_msg(len == strlen(expected) && memcmp(actual, expected, len) == 0,
                  "%s holds:\n%s\n--- but expected:\n%s", name, actual,
                  expected);
    free(actual);
}

static bool exists(const char *name)
{
    struct stat st;
    char *path = work_path(name);
    bool found = stat(path, &st) == 0;
    free(path);
    return found;
}

static time_t mtime_of(const char *name)
{
    struct stat st;
    char *path = work_path(name);
    ck_assert_int_eq(stat(path, &st), 0);
    free(path);
    return st.st_mtime;
}

static void set_mtime(const char *name, time_t when)
{
    struct timespec times[2] = {{.tv_sec = when}, {.tv_sec = when}};
    char *path = work_path(name);
    ck_assert_int_eq(utimensat(AT_FDCWD, path, times, 0), 0);
    free(path);
}

/* The output directory "out" must not exist, or at least be empty. */
static void assert_nothing_written(void)
{
    char *path = work_path("out");
    DIR *dir = opendir(path);
    free(path);
    if (!dir)
        return;
    for (struct dirent *e; (e = readdir(dir));)
        ck_assert_msg(strcmp(e->d_name, ".") == 0 ||
                          strcmp(e->d_name, "..") == 0,
                      "out/%s was written despite an error", e->d_name);
    closedir(dir);
}

/* ---- running programs ---------------------------------------------- */

/* How a program is run, beyond its arguments. */
struct run_options {
    unsigned deadline;  /* seconds before SIGALRM kills it; 0: none */
    bool stdin_pipe;    /* stdin is a pipe that never ends (the program
                           itself holds its write end) */
};

/* Runs ARGV inside the test directory, capturing stdout and stderr. */
static struct run run_with(const struct run_options *options,
                           char *const argv[])
{
    pid_t pid = fork();
    ck_assert_int_ne(pid, -1);
    if (pid == 0) {
        int out = -1, err = -1, pipe_ends[2];
        if (chdir(work_dir) == 0) {
            out = open(".stdout", O_WRONLY | O_CREAT | O_TRUNC, 0600);
            err = open(".stderr", O_WRONLY | O_CREAT | O_TRUNC, 0600);
        }
        if (out < 0 || err < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0)
            _exit(126);
        if (options->stdin_pipe &&
            (pipe(pipe_ends) != 0 || dup2(pipe_ends[0], 0) < 0))
            _exit(126);
        alarm(options->deadline); /* survives exec */
        execvp(argv[0], argv);
        _exit(127);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        ck_assert_int_eq(errno, EINTR);
    struct run r = {WIFEXITED(status) ? WEXITSTATUS(status)
                                      : 128 + WTERMSIG(status),
                    slurp(".stdout", NULL), slurp(".stderr", NULL)};
    ck_assert_msg(r.out && r.err, "could not capture the output of %s",
                  argv[0]);
    char *out = work_path(".stdout"), *err = work_path(".stderr");
    unlink(out);
    unlink(err);
    free(out);
    free(err);
    return r;
}

static struct run run_in_work_dir(char *const argv[])
{
    static const struct run_options plain = {0};
    return run_with(&plain, argv);
}

/* Runs the tangler with the arguments given, up to a NULL. */
static struct run tangle(const char *arg, ...)
{
    char *argv[32] = {tangle_path};
    int n = 1;
    va_list ap;
    va_start(ap, arg);
    for (const char *a = arg; a && n < 31; a = va_arg(ap, const char *))
        argv[n++] = (char *)a;
    va_end(ap);
    return run_in_work_dir(argv);
}

/* The tangler with ARGV[1..] (ARGV[0] is replaced), run as OPTIONS say. */
static struct run tangle_with(const struct run_options *options, char *argv[])
{
    argv[0] = tangle_path;
    return run_with(options, argv);
}

static struct run compile(const char *file)
{
    char *argv[] = {"cc", "-fsyntax-only", (char *)file, NULL};
    return run_in_work_dir(argv);
}

static void free_run(struct run *r)
{
    free(r->out);
    free(r->err);
}

static void expect_success(struct run r)
{
    ck_assert_msg(r.status == 0, "tangle exited with %d:\n%s", r.status, r.err);
    ck_assert_str_eq(r.err, "");
    free_run(&r);
}

/* Exit status 1, exactly these messages and not a single file written. */
static void expect_failure(struct run r, const char *messages)
{
    ck_assert_msg(r.status == 1, "tangle exited with %d:\n%s", r.status, r.err);
    ck_assert_str_eq(r.err, messages);
    assert_nothing_written();
    free_run(&r);
}

static void setup(void)
{
    const char *tangle_env = getenv("TANGLE");
    ck_assert_msg(
        tangle_env && *tangle_env,
        "TANGLE is not set: run the tests as TANGLE=path/to/tangle ...");
    /* The tangler runs inside the test directory: make its path absolute. */
    char cwd[4096] = "";
    if (tangle_env[0] != '/')
        ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
    tangle_path = malloc(strlen(cwd) + strlen(tangle_env) + 2);
    ck_assert_ptr_nonnull(tangle_path);
    sprintf(tangle_path, "%s%s%s", cwd, *cwd ? "/" : "", tangle_env);
    ck_assert_msg(access(tangle_path, X_OK) == 0, "TANGLE=%s: %s", tangle_env,
                  strerror(errno));
    strcpy(work_dir, "/tmp/tangle-test-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(work_dir));
}

static void teardown(void)
{
    char *argv[] = {"rm", "-rf", work_dir, NULL};
    pid_t pid = fork();
    if (pid == 0) {
        execvp(argv[0], argv);
        _exit(127);
    }
    if (pid > 0)
        waitpid(pid, NULL, 0);
    free(tangle_path);
}

/* ---- rules ---------------------------------------------------------- */

START_TEST(test_file_block_is_written_to_outdir)
{
    put("chapters/01-a.md",
        "# Hello\n"
        "\n"
        "```{.c file=\"hello.c\"}\n"
        "int x;\n"
        "int y;\n"
        "```\n"
        "Prose after the code.\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/hello.c", "int x;\nint y;\n");
}
END_TEST

START_TEST(test_append_adds_to_end_of_definition)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<decls>>\n"
        "```\n"
        "```{.c chunk=\"decls\"}\n"
        "int one;\n"
        "```\n"
        "```{.c chunk=\"decls\" .append}\n"
        "int two;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c", "/* <<decls>> ch01 */\nint one;\nint two;\n");
}
END_TEST

START_TEST(test_replace_discards_whole_body_and_later_append_extends_it)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<shade>>\n"
        "```\n"
        "```{.c chunk=\"shade\"}\n"
        "old1;\n"
        "```\n"
        "```{.c chunk=\"shade\" .append}\n"
        "old2;\n"
        "```\n"
        "```{.c chunk=\"shade\" .replace}\n"
        "new1;\n"
        "```\n"
        "```{.c chunk=\"shade\" .append}\n"
        "new2;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c", "/* <<shade>> ch01 */\nnew1;\nnew2;\n");
}
END_TEST

START_TEST(test_append_works_across_chapter_files)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<body>>\n"
        "```\n"
        "```{.c chunk=\"body\"}\n"
        "first();\n"
        "```\n");
    put("chapters/02-b.md",
        "More prose.\n"
        "```{.c chunk=\"body\" .append}\n"
        "second();\n"
        "```\n");
    expect_success(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL));
    assert_file("out/a.c",
                "/* <<body>> ch01 */\n"
                "first();\n"
                "/* <<body>> += ch02 */\n"
                "second();\n");
}
END_TEST

START_TEST(test_file_roots_can_be_appended_and_replaced)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "a1;\n"
        "```\n"
        "```{.c file=\"a.c\" .append}\n"
        "a2;\n"
        "```\n"
        "```{.c file=\"b.c\"}\n"
        "b1;\n"
        "```\n");
    put("chapters/02-b.md",
        "```{.c file=\"b.c\" .replace}\n"
        "b2;\n"
        "```\n");
    expect_success(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL));
    assert_file("out/a.c", "a1;\na2;\n");
    assert_file("out/b.c", "b2;\n");
}
END_TEST

START_TEST(test_files_and_chunks_are_separate_namespaces)
{
    put("chapters/01-a.md",
        "```{.c file=\"x.c\"}\n"
        "<<x.c>>\n"
        "```\n"
        "```{.c chunk=\"x.c\"}\n"
        "from the chunk;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/x.c", "/* <<x.c>> ch01 */\nfrom the chunk;\n");
}
END_TEST

START_TEST(test_root_files_in_subdirectories_are_created)
{
    put("chapters/01-a.md",
        "```{.scene file=\"scenes/ch01-wide.scene\"}\n"
        "camera 0 0 0\n"
        "```\n"
        "```{.c file=\"src/deep/er.h\"}\n"
        "int deep;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/scenes/ch01-wide.scene", "camera 0 0 0\n");
    assert_file("out/src/deep/er.h", "int deep;\n");
}
END_TEST

START_TEST(test_inner_dotdot_stays_inside_outdir)
{
    put("chapters/01-a.md",
        "```{.c file=\"a/../b.c\"}\n"
        "b;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/b.c", "b;\n");
    ck_assert(!exists("b.c"));
}
END_TEST

START_TEST(test_nested_references_are_indented_cumulatively)
{
    put("chapters/01-a.md",
        "```{.c file=\"f.c\"}\n"
        "void f(void)\n"
        "{\n"
        "    <<outer>>\n"
        "}\n"
        "```\n"
        "```{.c chunk=\"outer\"}\n"
        "if (a) {\n"
        "\t<<inner>>  \n"
        "}\n"
        "```\n"
        "```{.c chunk=\"inner\"}\n"
        "g();\n"
        "h();\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c",
                "void f(void)\n"
                "{\n"
                "    /* <<outer>> ch01 */\n"
                "    if (a) {\n"
                "    \t/* <<inner>> ch01 */\n"
                "    \tg();\n"
                "    \th();\n"
                "    }\n"
                "}\n");
}
END_TEST

START_TEST(test_empty_lines_are_not_indented)
{
    put("chapters/01-a.md",
        "```{.c file=\"f.c\"}\n"
        "{\n"
        "    <<body>>\n"
        "}\n"
        "```\n"
        "```{.c chunk=\"body\"}\n"
        "a();\n"
        "\n"
        "b();\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c",
                "{\n    /* <<body>> ch01 */\n    a();\n\n    b();\n}\n");
}
END_TEST

START_TEST(test_angle_brackets_inside_a_line_are_plain_text)
{
    put("chapters/01-a.md",
        "```{.c file=\"f.c\"}\n"
        "x = a << b >> c;\n"
        "puts(\"<<name>>\");\n"
        "<<name>> + 1;\n"
        "<<>>\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c",
                "x = a << b >> c;\n"
                "puts(\"<<name>>\");\n"
                "<<name>> + 1;\n"
                "<<>>\n");
}
END_TEST

START_TEST(test_illustration_blocks_are_skipped)
{
    put("chapters/01-a.md",
        "```c\n"
        "illustration 1;\n"
        "```\n"
        "```text\n"
        "illustration 2\n"
        "```\n"
        "```\n"
        "illustration 3\n"
        "```\n"
        "```{.c #fig-1 .numberLines}\n"
        "illustration 4;\n"
        "```\n"
        "``` {.c file=\"f.c\"}\n"
        "real;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c", "real;\n");
}
END_TEST

START_TEST(test_longer_fence_keeps_shorter_fence_as_body)
{
    put("chapters/01-a.md",
        "````markdown\n"
        "```{.c file=\"fake.c\"}\n"
        "fake;\n"
        "```\n"
        "````\n"
        "````{.c file=\"f.c\"}\n"
        "/* A fence in a comment:\n"
        "```\n"
        "*/\n"
        "``````   \n"
        "after;\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c", "/* A fence in a comment:\n```\n*/\n");
    ck_assert(!exists("out/fake.c"));
}
END_TEST

START_TEST(test_tilde_fences_hold_code)
{
    put("chapters/01-a.md",
        "~~~{.c file=\"t.c\"}\n"
        "```\n"
        "tilde;\n"
        "~~~~\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/t.c", "```\ntilde;\n");
}
END_TEST

START_TEST(test_attribute_variants_are_accepted)
{
    put("chapters/01-a.md",
        "```{ #main .c file=main.c caption=\"a b\" }\n"
        "<<say \"hi\">>\n"
        "```\n"
        "```{.c chunk=\"say \\\"hi\\\"\"}\n"
        "hi;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/main.c", "/* <<say \"hi\">> ch01 */\nhi;\n");
}
END_TEST

START_TEST(test_crlf_line_endings_end_lines)
{
    put("chapters/01-a.md",
        "```{.c file=\"f.c\"}\r\n"
        "    <<x>>\r\n"
        "```\r\n"
        "```{.c chunk=\"x\"}\r\n"
        "a;\r\n"
        "\r\n"
        "```\r\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c", "    /* <<x>> ch01 */\n    a;\n\n");
}
END_TEST

START_TEST(test_missing_final_newline_is_supplied)
{
    put("chapters/01-a.md",
        "```{.c file=\"f.c\"}\n"
        "last;\n"
        "```");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/f.c", "last;\n");
}
END_TEST

START_TEST(test_nul_bytes_and_long_lines_are_copied)
{
    const char head[] = "```{.c file=\"f.c\"}\nab\0cd\n";
    size_t long_len = 200000;
    char *md = malloc(sizeof head + long_len + 8),
         *expected = malloc(long_len + 16);
    memcpy(md, head, sizeof head - 1);
    memset(md + sizeof head - 1, 'x', long_len);
    memcpy(md + sizeof head - 1 + long_len, "\n```\n", 5);
    put_bytes("chapters/01-a.md", md, sizeof head - 1 + long_len + 5);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));

    memcpy(expected, "ab\0cd\n", 6);
    memset(expected + 6, 'x', long_len);
    expected[6 + long_len] = '\n';
    size_t len;
    char *actual = slurp("out/f.c", &len);
    ck_assert_uint_eq(len, 6 + long_len + 1);
    ck_assert(memcmp(actual, expected, len) == 0);
    free(actual);
    free(expected);
    free(md);
}
END_TEST

START_TEST(test_many_chunks_are_tangled)
{
    enum { N = 20000 };
    char *md = NULL, *expected = NULL;
    size_t md_len, expected_len;
    FILE *m = open_memstream(&md, &md_len),
         *e = open_memstream(&expected, &expected_len);
    fputs("```{.c file=\"many.c\"}\n", m);
    for (int i = 0; i < N; i++)
        fprintf(m, "<<c%d>>\n", i);
    fputs("```\n", m);
    for (int i = 0; i < N; i++) {
        fprintf(m, "```{.c chunk=\"c%d\"}\nint v%d;\n```\n", i, i);
        fprintf(e, "/* <<c%d>> ch01 */\nint v%d;\n", i, i);
    }
    fclose(m);
    fclose(e);
    put("chapters/01-a.md", md);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/many.c", expected);
    free(md);
    free(expected);
}
END_TEST

static const char small_chapter[] =
    "```{.c file=\"a.c\"}\n"
    "    <<x>>\n"
    "```\n"
    "```{.c chunk=\"x\"}\n"
    "x;\n"
    "```\n";

START_TEST(test_running_twice_gives_identical_bytes)
{
    put("chapters/01-a.md", small_chapter);
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md", NULL));
    expect_success(tangle("--line", "-o", "out2", "chapters/01-a.md", NULL));
    const char *expected = "#line 5 \"chapters/01-a.md\"\n    x;\n";
    assert_file("out/a.c", expected);
    assert_file("out2/a.c", expected);
}
END_TEST

START_TEST(test_unchanged_output_keeps_its_mtime)
{
    put("chapters/01-a.md", small_chapter);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    set_mtime("out/a.c", 1000000000);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    ck_assert_int_eq(mtime_of("out/a.c"), 1000000000);
    assert_file("out/a.c", "    /* <<x>> ch01 */\n    x;\n");
}
END_TEST

START_TEST(test_changed_output_is_rewritten)
{
    put("chapters/01-a.md", small_chapter);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    set_mtime("out/a.c", 1000000000);
    put("out/keep.txt", "not ours\n");
    put("chapters/01-a.md", "```{.c file=\"a.c\"}\nchanged;\n```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    ck_assert_int_gt(mtime_of("out/a.c"), 1000000000);
    assert_file("out/a.c", "changed;\n");
    assert_file("out/keep.txt", "not ours\n");
}
END_TEST

START_TEST(test_unused_chunk_is_only_a_warning)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "a;\n"
        "```\n"
        "\n"
        "```{.c chunk=\"spare\"}\n"
        "spare;\n"
        "```\n");
    struct run r = tangle("-o", "out", "chapters/01-a.md", NULL);
    ck_assert_int_eq(r.status, 0);
    ck_assert_str_eq(r.err, "chapters/01-a.md:5: warning: chunk 'spare' is "
                            "defined but never used\n");
    free_run(&r);
    assert_file("out/a.c", "a;\n");
}
END_TEST

START_TEST(test_bad_usage_exits_with_status_2)
{
    const char *usage = "usage: tangle [--line] [--strict] [--skip-not-done] "
                        "-o OUTDIR CHAPTER.md...\n";
    struct run runs[] = {
        tangle(NULL),
        tangle("--bogus", "-o", "out", "a.md", NULL),
        tangle("a.md", NULL),
        tangle("-o", "out", NULL),
        tangle("a.md", "-o", NULL),
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        ck_assert_int_eq(runs[i].status, 2);
        ck_assert_str_eq(runs[i].err, usage);
        free_run(&runs[i]);
    }
}
END_TEST

START_TEST(test_help_prints_usage_and_succeeds)
{
    struct run r = tangle("--help", NULL);
    ck_assert_int_eq(r.status, 0);
    ck_assert_str_eq(r.out, "usage: tangle [--line] [--strict] "
                            "[--skip-not-done] -o OUTDIR CHAPTER.md...\n");
    free_run(&r);
}
END_TEST

/* ---- workbook exercises --------------------------------------------- */

static const char *const book_with_exercise =
    "```{.c file=\"a.c\"}\n"
    "<<x>>\n"
    "```\n"
    "```{.c chunk=\"x\" .exercise tests=\"test_x\"}\n"
    "book;\n"
    "```\n";

START_TEST(test_exercise_class_means_nothing_without_skip_option)
{
    put("chapters/01-a.md", book_with_exercise);
    put("workbook/01-a.md",
        "```{.c chunk=\"x\" .replace .exercise}\n"
        "stub;\n"
        "// NOT DONE: delete this line\n"
        "```\n");
    expect_success(
        tangle("-o", "out", "chapters/01-a.md", "workbook/01-a.md", NULL));
    assert_file("out/a.c",
                "/* <<x>> ch01 */\nstub;\n// NOT DONE: delete this line\n");
}
END_TEST

START_TEST(test_skip_not_done_leaves_an_unstarted_exercise_out)
{
    put("chapters/01-a.md", book_with_exercise);
    put("workbook/01-a.md",
        "```{.c chunk=\"x\" .replace .exercise}\n"
        "stub;\n"
        "    // NOT DONE: delete this line\n"
        "```\n");
    expect_success(tangle("--skip-not-done", "-o", "out", "chapters/01-a.md",
                          "workbook/01-a.md", NULL));
    assert_file("out/a.c", "/* <<x>> ch01 */\nbook;\n");
}
END_TEST

START_TEST(test_skip_not_done_uses_a_started_exercise)
{
    put("chapters/01-a.md", book_with_exercise);
    put("workbook/01-a.md",
        "```{.c chunk=\"x\" .replace .exercise}\n"
        "mine; // NOT DONE is only a marker at the start of a line\n"
        "```\n");
    expect_success(tangle("--skip-not-done", "--line", "-o", "out",
                          "chapters/01-a.md", "workbook/01-a.md", NULL));
    assert_file("out/a.c", "#line 2 \"workbook/01-a.md\"\n"
                "mine; // NOT DONE is only a marker at the start of a line\n");
}
END_TEST

START_TEST(test_skip_not_done_keeps_blocks_not_marked_exercise)
{
    put("chapters/01-a.md", book_with_exercise);
    put("workbook/01-a.md",
        "```{.c chunk=\"x\" .replace}\n"
        "// NOT DONE\n"
        "```\n");
    expect_success(tangle("--skip-not-done", "-o", "out", "chapters/01-a.md",
                          "workbook/01-a.md", NULL));
    assert_file("out/a.c", "/* <<x>> ch01 */\n// NOT DONE\n");
}
END_TEST

/* ---- line directives ------------------------------------------------ */

START_TEST(test_no_line_directives_without_line_option)
{
    put("chapters/01-a.md", small_chapter);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c", "    /* <<x>> ch01 */\n    x;\n");
}
END_TEST

START_TEST(test_line_directive_precedes_each_definition_piece)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.h\"}\n"
        "one;\n"
        "two;\n"
        "```\n"
        "\n"
        "```{.c file=\"a.h\" .append}\n"
        "three;\n"
        "```\n");
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.h",
                "#line 2 \"chapters/01-a.md\"\n"
                "one;\n"
                "two;\n"
                "#line 7 \"chapters/01-a.md\"\n"
                "three;\n");
}
END_TEST

START_TEST(test_line_directives_resync_after_nested_references)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "top;\n"
        "    <<outer>>\n"
        "bottom;\n"
        "```\n"
        "```{.c chunk=\"outer\"}\n"
        "<<inner>>\n"
        "after_inner;\n"
        "```\n"
        "```{.c chunk=\"inner\"}\n"
        "inner;\n"
        "```\n");
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c",
                "#line 2 \"chapters/01-a.md\"\n"
                "top;\n"
                "#line 11 \"chapters/01-a.md\"\n"
                "    inner;\n"
                "#line 8 \"chapters/01-a.md\"\n"
                "    after_inner;\n"
                "#line 4 \"chapters/01-a.md\"\n"
                "bottom;\n");
}
END_TEST

START_TEST(test_line_directives_name_each_chapter_file)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<body>>\n"
        "end;\n"
        "```\n"
        "```{.c chunk=\"body\"}\n"
        "first;\n"
        "```\n");
    put("chapters/02-b.md",
        "Text.\n"
        "\n"
        "```{.c chunk=\"body\" .append}\n"
        "second;\n"
        "```\n");
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md",
                          "chapters/02-b.md", NULL));
    assert_file("out/a.c",
                "#line 6 \"chapters/01-a.md\"\n"
                "first;\n"
                "#line 4 \"chapters/02-b.md\"\n"
                "second;\n"
                "#line 3 \"chapters/01-a.md\"\n"
                "end;\n");
}
END_TEST

START_TEST(test_scene_files_get_no_line_directives)
{
    put("chapters/01-a.md",
        "```{.scene file=\"scenes/wide.scene\"}\n"
        "<<camera>>\n"
        "sphere 0 0 -1 0.5\n"
        "```\n"
        "```{.scene chunk=\"camera\"}\n"
        "camera 0 0 0\n"
        "```\n");
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/scenes/wide.scene", "camera 0 0 0\nsphere 0 0 -1 0.5\n");
}
END_TEST

/* Chapter 1 and 2 of a tiny book; ERROR_LINE goes into a nested chunk. */
static void put_book(const char *error_line)
{
    put("chapters/01-camera.md",
        "# Camera\n"
        "\n"
        "```{.c file=\"main.c\"}\n"
        "#include <stdio.h>\n"
        "\n"
        "int main(void)\n"
        "{\n"
        "    <<main body>>\n"
        "    return 0;\n"
        "}\n"
        "```\n"
        "\n"
        "```{.c chunk=\"main body\"}\n"
        "int width = 320;\n"
        "```\n");
    char *second = NULL;
    size_t len;
    FILE *f = open_memstream(&second, &len);
    fprintf(f,
            "# Shading\n"
            "\n"
            "```{.c chunk=\"main body\" .append}\n"
            "if (width > 0) {\n"
            "    <<report>>\n"
            "}\n"
            "```\n"
            "\n"
            "```{.c chunk=\"report\"}\n"
            "printf(\"%%d\\n\", width);\n"
            "%s\n"
            "```\n",
            error_line);
    fclose(f);
    put("chapters/02-shade.md", second);
    free(second);
}

START_TEST(test_line_output_compiles_with_cc)
{
    put_book("puts(\"done\");");
    expect_success(tangle("--line", "-o", "out", "chapters/01-camera.md",
                          "chapters/02-shade.md", NULL));
    struct run cc = compile("out/main.c");
    ck_assert_msg(cc.status == 0, "cc failed:\n%s", cc.err);
    free_run(&cc);
}
END_TEST

START_TEST(test_syntax_error_is_reported_at_its_markdown_line)
{
    put_book("int broken = ;");
    expect_success(tangle("--line", "-o", "out", "chapters/01-camera.md",
                          "chapters/02-shade.md", NULL));
    struct run cc = compile("out/main.c");
    ck_assert_int_ne(cc.status, 0);
    ck_assert_msg(strstr(cc.err, "chapters/02-shade.md:11:"), "cc said:\n%s",
                  cc.err);
    free_run(&cc);
}
END_TEST

START_TEST(test_syntax_error_after_reference_is_reported_at_its_markdown_line)
{
    put("chapters/01-camera.md",
        "```{.c file=\"main.c\"}\n"
        "int main(void)\n"
        "{\n"
        "    <<setup>>\n"
        "    return 0 +;\n"
        "}\n"
        "```\n"
        "```{.c chunk=\"setup\"}\n"
        "int a = 1;\n"
        "(void)a;\n"
        "```\n");
    expect_success(
        tangle("--line", "-o", "out", "chapters/01-camera.md", NULL));
    struct run cc = compile("out/main.c");
    ck_assert_int_ne(cc.status, 0);
    ck_assert_msg(strstr(cc.err, "chapters/01-camera.md:5:"), "cc said:\n%s",
                  cc.err);
    ck_assert_msg(!strstr(cc.err, "out/main.c"), "cc said:\n%s", cc.err);
    free_run(&cc);
}
END_TEST

/* ---- errors --------------------------------------------------------- */

/* A valid root file that must not be written when anything else fails. */
static const char good_root[] =
    "```{.c file=\"good.c\"}\n"
    "good;\n"
    "```\n";

START_TEST(test_reference_to_undefined_chunk_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "ok;\n"
        "  <<missing piece>>\n"
        "```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:3: error: reference to undefined chunk "
                   "'missing piece'\n");
}
END_TEST

START_TEST(test_cycle_of_references_names_its_chunks)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<a>>\n"
        "```\n"
        "```{.c chunk=\"a\"}\n"
        "<<b>>\n"
        "```\n"
        "```{.c chunk=\"b\"}\n"
        "<<c>>\n"
        "```\n"
        "```{.c chunk=\"c\"}\n"
        "x;\n"
        "<<a>>\n"
        "```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:12: error: cycle of references: 'a' -> "
                   "'b' -> 'c' -> 'a'\n");
}
END_TEST

START_TEST(test_chunk_referring_to_itself_is_a_cycle)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-b.md",
        "```{.c chunk=\"self\"}\n"
        "<<self>>\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/02-b.md:2: error: cycle of references: 'self' -> 'self'\n"
        "chapters/02-b.md:1: warning: chunk 'self' is defined but never "
        "used\n");
}
END_TEST

START_TEST(test_second_definition_without_append_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<x>>\n"
        "```\n"
        "```{.c chunk=\"x\"}\n"
        "one;\n"
        "```\n");
    put("chapters/02-b.md",
        "\n"
        "```{.c chunk=\"x\"}\n"
        "two;\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/02-b.md:2: error: chunk 'x' is already defined at "
        "chapters/01-a.md:4 (use .append or .replace)\n");
}
END_TEST

START_TEST(test_second_definition_of_a_file_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"good.c\"}\n"
        "one;\n"
        "```\n"
        "```{.c file=\"./good.c\"}\n"
        "two;\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", NULL),
        "chapters/01-a.md:4: error: file 'good.c' is already defined at "
        "chapters/01-a.md:1 (use .append or .replace)\n");
}
END_TEST

START_TEST(test_append_to_undefined_chunk_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<later>>\n"
        "```\n"
        "```{.c chunk=\"later\" .append}\n"
        "x;\n"
        "```\n"
        "```{.c chunk=\"later\"}\n"
        "y;\n"
        "```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:4: error: cannot append to undefined "
                   "chunk 'later'\n");
}
END_TEST

START_TEST(test_replace_of_undefined_file_is_an_error)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-b.md",
        "```{.c file=\"other.c\" .replace}\n"
        "x;\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/02-b.md:1: error: cannot replace undefined file 'other.c'\n");
}
END_TEST

START_TEST(test_append_together_with_replace_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"good.c\"}\n"
        "good;\n"
        "```\n"
        "```{.c file=\"good.c\" .append .replace}\n"
        "x;\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", NULL),
        "chapters/01-a.md:4: error: .append and .replace cannot be combined\n");
}
END_TEST

START_TEST(test_chunk_together_with_file_is_an_error)
{
    put("chapters/01-a.md",
        "Intro.\n"
        "```{.c chunk=\"x\" file=\"x.c\"}\n"
        "x;\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", NULL),
        "chapters/01-a.md:2: error: chunk= and file= cannot be combined\n");
}
END_TEST

START_TEST(test_empty_chunk_name_is_an_error)
{
    put("chapters/01-a.md", "```{.c chunk=\"\"}\nx;\n```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:1: error: empty chunk name\n");
}
END_TEST

START_TEST(test_empty_file_path_is_an_error)
{
    put("chapters/01-a.md", "\n\n```{.c file=\"\"}\nx;\n```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:3: error: empty file path\n");
}
END_TEST

START_TEST(test_unterminated_fence_is_reported_where_it_opened)
{
    put("chapters/01-a.md",
        "```{.c file=\"good.c\"}\n"
        "good;\n"
        "```\n"
        "\n"
        "````c\n"
        "```\n"
        "never closed\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:5: error: code fence is never closed\n");
}
END_TEST

START_TEST(test_unterminated_quote_is_an_error)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-b.md", "```{.c chunk=\"open}\nx;\n```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/02-b.md:1: error: unterminated quote in attributes\n");
}
END_TEST

START_TEST(test_missing_closing_brace_is_an_error)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-b.md", "text\n```{.c chunk=\"x\"\nx;\n```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/02-b.md:2: error: missing '}' in attributes\n");
}
END_TEST

START_TEST(test_absolute_path_is_an_error)
{
    put("chapters/01-a.md", "```{.c file=\"/tmp/tangle-escape.c\"}\nx;\n```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:1: error: file path "
                   "'/tmp/tangle-escape.c' is absolute\n");
}
END_TEST

START_TEST(test_path_leaving_outdir_is_an_error)
{
    put("chapters/01-a.md",
        "```{.c file=\"../x.c\"}\n"
        "x;\n"
        "```\n"
        "```{.c file=\"a/../../y.c\"}\n"
        "y;\n"
        "```\n");
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:1: error: file path '../x.c' leaves the "
                   "output directory\n"
                   "chapters/01-a.md:4: error: file path 'a/../../y.c' leaves "
                   "the output directory\n");
    ck_assert(!exists("x.c") && !exists("y.c"));
}
END_TEST

START_TEST(test_unreadable_input_is_an_error)
{
    put("chapters/01-a.md", good_root);
    char *dir = work_path("adir");
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    free(dir);
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-missing.md",
               "adir", NULL),
        "chapters/02-missing.md: error: cannot read: No such file or "
        "directory\n"
        "adir: error: cannot read: not a regular file but a directory\n");
}
END_TEST

START_TEST(test_unwritable_output_is_an_error)
{
    put("chapters/01-a.md", good_root);
    put("blocker", "a file where the output directory should be\n");
    struct run r = tangle("-o", "blocker", "chapters/01-a.md", NULL);
    ck_assert_int_eq(r.status, 1);
    ck_assert_str_eq(r.err,
                     "blocker/good.c: error: cannot write: Not a directory\n");
    free_run(&r);
}
END_TEST

START_TEST(test_unused_chunk_is_an_error_with_strict)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-b.md",
        "\n"
        "```{.c chunk=\"spare\"}\n"
        "```\n");
    expect_failure(
        tangle("--strict", "-o", "out", "chapters/01-a.md", "chapters/02-b.md",
               NULL),
        "chapters/02-b.md:2: error: chunk 'spare' is defined but never used\n");
}
END_TEST

START_TEST(test_every_error_is_reported_not_only_the_first)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<one>>\n"
        "<<two>>\n"
        "```\n"
        "```{.c chunk=\"\"}\n"
        "```\n");
    put("chapters/02-b.md",
        "```{.c chunk=\"x\" .replace}\n"
        "```\n"
        "```{.c file=\"/abs\"}\n"
        "```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL),
        "chapters/01-a.md:5: error: empty chunk name\n"
        "chapters/02-b.md:1: error: cannot replace undefined chunk 'x'\n"
        "chapters/02-b.md:3: error: file path '/abs' is absolute\n"
        "chapters/01-a.md:2: error: reference to undefined chunk 'one'\n"
        "chapters/01-a.md:3: error: reference to undefined chunk 'two'\n");
}
END_TEST

/* A root file and a chain of N chunks, c1 -> c2 -> ... -> cN -> "leaf;". */
static void put_chain(int n)
{
    char *md = NULL;
    size_t len;
    FILE *f = open_memstream(&md, &len);
    fputs("```{.c file=\"deep.c\"}\n<<c1>>\n```\n", f);
    for (int i = 1; i < n; i++)
        fprintf(f, "```{.c chunk=\"c%d\"}\n<<c%d>>\n```\n", i, i + 1);
    fprintf(f, "```{.c chunk=\"c%d\"}\nleaf;\n```\n", n);
    fclose(f);
    put("chapters/01-a.md", md);
    free(md);
}

START_TEST(test_nesting_of_999_chunks_is_accepted)
{
    char *expected = NULL;
    size_t len;
    FILE *e = open_memstream(&expected, &len);
    for (int i = 1; i <= 999; i++)
        fprintf(e, "/* <<c%d>> ch01 */\n", i);
    fputs("leaf;\n", e);
    fclose(e);
    put_chain(999);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/deep.c", expected);
    free(expected);
}
END_TEST

START_TEST(test_nesting_deeper_than_1000_levels_is_an_error)
{
    put_chain(
        1000); /* the root plus 1000 chunks: c999's reference is too deep */
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:2999: error: references nested deeper "
                   "than 1000 levels\n");
}
END_TEST

START_TEST(test_exponential_expansion_is_stopped)
{
    char *md = NULL;
    size_t len;
    FILE *f = open_memstream(&md, &len);
    fputs("```{.c file=\"big.c\"}\n<<l0>>\n```\n", f);
    for (int i = 0; i < 40; i++)
        fprintf(f, "```{.c chunk=\"l%d\"}\n<<l%d>>\n<<l%d>>\n```\n", i, i + 1,
                i + 1);
    fputs("```{.c chunk=\"l40\"}\nint x;\n```\n", f);
    fclose(f);
    put("chapters/01-a.md", md);
    free(md);
    expect_failure(tangle("-o", "out", "chapters/01-a.md", NULL),
                   "chapters/01-a.md:1: error: file 'big.c' would be larger "
                   "than 67108864 bytes\n");
}
END_TEST

/* ---- markers -------------------------------------------------------- */

START_TEST(test_marker_names_chunk_and_chapter_at_expansion_indent)
{
    put("chapters/03-phong.md",
        "```{.c file=\"a.c\"}\n"
        "void f(void)\n"
        "{\n"
        "    <<shade the hit>>\n"
        "}\n"
        "```\n"
        "```{.c chunk=\"shade the hit\"}\n"
        "if (hit) {\n"
        "\t<<inner>>\n"
        "}\n"
        "```\n"
        "```{.c chunk=\"inner\"}\n"
        "light();\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/03-phong.md", NULL));
    assert_file("out/a.c",
                "void f(void)\n"
                "{\n"
                "    /* <<shade the hit>> ch03 */\n"
                "    if (hit) {\n"
                "    \t/* <<inner>> ch03 */\n"
                "    \tlight();\n"
                "    }\n"
                "}\n");
}
END_TEST

START_TEST(test_marker_names_chapter_by_leading_digits_or_file_name)
{
    put("chapters/007.md",
        "```{.c file=\"a.c\"}\n"
        "<<x>>\n"
        "<<y>>\n"
        "```\n"
        "```{.c chunk=\"x\"}\n"
        "x;\n"
        "```\n");
    put("appendix/notes.md",
        "```{.c chunk=\"y\"}\n"
        "y;\n"
        "```\n");
    put("chapters/12-more.md",
        "```{.c chunk=\"y\" .append}\n"
        "more;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/007.md", "appendix/notes.md",
                          "chapters/12-more.md", NULL));
    assert_file("out/a.c",
                "/* <<x>> ch007 */\n"
                "x;\n"
                "/* <<y>> notes.md */\n"
                "y;\n"
                "/* <<y>> += ch12 */\n"
                "more;\n");
}
END_TEST

START_TEST(test_empty_hook_gets_no_marker)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<hook>>\n"
        "<<empty>>\n"
        "<<only empty hooks>>\n"
        "end;\n"
        "```\n"
        "```{.c chunk=\"hook\"}\n"
        "```\n"
        "```{.c chunk=\"empty\"}\n"
        "```\n"
        "```{.c chunk=\"only empty hooks\"}\n"
        "<<empty>>\n"
        "```\n");
    put("chapters/02-b.md",
        "```{.c chunk=\"hook\" .append}\n"
        "filled;\n"
        "```\n");
    expect_success(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md", NULL));
    /* the hook's lines come from chapter 02, and its marker says so */
    assert_file("out/a.c", "/* <<hook>> ch02 */\nfilled;\nend;\n");
}
END_TEST

START_TEST(test_later_chapters_pieces_are_marked_after_replace)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<shade>>\n"
        "```\n"
        "```{.c chunk=\"shade\"}\n"
        "old;\n"
        "```\n");
    put("chapters/02-b.md",
        "```{.c chunk=\"shade\" .append}\n"
        "older;\n"
        "```\n");
    put("chapters/03-c.md",
        "```{.c chunk=\"shade\" .replace}\n"
        "new;\n"
        "```\n"
        "```{.c chunk=\"shade\" .append}\n"
        "also new;\n"
        "```\n");
    put("chapters/04-d.md",
        "```{.c chunk=\"shade\" .append}\n"
        "newer;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", "chapters/02-b.md",
                          "chapters/03-c.md", "chapters/04-d.md", NULL));
    assert_file("out/a.c",
                "/* <<shade>> ch03 */\n"
                "new;\n"
                "also new;\n"
                "/* <<shade>> += ch04 */\n"
                "newer;\n");
}
END_TEST

START_TEST(test_markers_only_in_c_and_h_files)
{
    put("chapters/01-a.md",
        "```{.scene file=\"scenes/a.scene\"}\n"
        "<<x>>\n"
        "```\n"
        "```{.txt file=\"b.txt\"}\n"
        "<<x>>\n"
        "```\n"
        "```{.c file=\"c.h\"}\n"
        "<<x>>\n"
        "```\n"
        "```{.c file=\"d.c\"}\n"
        "<<x>>\n"
        "```\n"
        "```{.c chunk=\"x\"}\n"
        "x\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/scenes/a.scene", "x\n");
    assert_file("out/b.txt", "x\n");
    assert_file("out/c.h", "/* <<x>> ch01 */\nx\n");
    assert_file("out/d.c", "/* <<x>> ch01 */\nx\n");
}
END_TEST

START_TEST(test_line_option_writes_no_markers)
{
    put("chapters/01-a.md", small_chapter);
    put("chapters/02-b.md",
        "```{.c chunk=\"x\" .append}\n"
        "y;\n"
        "```\n");
    expect_success(tangle("--line", "-o", "out", "chapters/01-a.md",
                          "chapters/02-b.md", NULL));
    assert_file("out/a.c",
                "#line 5 \"chapters/01-a.md\"\n"
                "    x;\n"
                "#line 2 \"chapters/02-b.md\"\n"
                "    y;\n");
}
END_TEST

START_TEST(test_no_marker_inside_a_comment_or_a_spliced_line)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "/* licence:\n"
        "<<licence>>\n"
        "*/\n"
        "#define TWICE(x) \\\n"
        "    <<twice body>>\n"
        "int after = TWICE(1);\n"
        "const char *s = \"/* not a comment\";\n"
        "char c = '\"';\n"
        "// nor this /*\n"
        "<<tail>>\n"
        "```\n"
        "```{.c chunk=\"licence\"}\n"
        "free to use\n"
        "```\n"
        "```{.c chunk=\"twice body\"}\n"
        "((x) + (x))\n"
        "```\n"
        "```{.c chunk=\"tail\"}\n"
        "int tail;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c",
                "/* licence:\n"
                "free to use\n"
                "*/\n"
                "#define TWICE(x) \\\n"
                "    ((x) + (x))\n"
                "int after = TWICE(1);\n"
                "const char *s = \"/* not a comment\";\n"
                "char c = '\"';\n"
                "// nor this /*\n"
                "/* <<tail>> ch01 */\n"
                "int tail;\n");
    struct run cc = compile("out/a.c");
    ck_assert_msg(cc.status == 0, "cc failed:\n%s", cc.err);
    free_run(&cc);
}
END_TEST

START_TEST(test_marker_cannot_end_its_comment_early)
{
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "<<a */ b /* c **/ \001>>\n"
        "```\n"
        "```{.c chunk=\"a */ b /* c **/ \001\"}\n"
        "int x;\n"
        "```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/a.c", "/* <<a * / b / * c ** / \\x01>> ch01 */\nint x;\n");
    struct run cc = compile("out/a.c");
    ck_assert_msg(cc.status == 0, "cc failed:\n%s", cc.err);
    free_run(&cc);
}
END_TEST

START_TEST(test_plain_output_with_markers_compiles_with_cc)
{
    put_book("puts(\"done\");");
    expect_success(tangle("-o", "out", "chapters/01-camera.md",
                          "chapters/02-shade.md", NULL));
    char *text = slurp("out/main.c", NULL);
    ck_assert_ptr_nonnull(strstr(text, "    /* <<main body>> ch01 */\n"));
    ck_assert_ptr_nonnull(strstr(text, "    /* <<main body>> += ch02 */\n"));
    ck_assert_ptr_nonnull(strstr(text, "        /* <<report>> ch02 */\n"));
    free(text);
    struct run cc = compile("out/main.c");
    ck_assert_msg(cc.status == 0, "cc failed:\n%s", cc.err);
    free_run(&cc);
}
END_TEST

/* ---- inputs and outputs --------------------------------------------- */

static void make_link(const char *target, const char *name)
{
    char *path = work_path(name);
    ck_assert_msg(symlink(target, path) == 0, "symlink %s: %s", path,
                  strerror(errno));
    free(path);
}

static void make_dir(const char *name)
{
    char *path = work_path(name);
    ck_assert_msg(mkdir(path, 0777) == 0, "mkdir %s: %s", path,
                  strerror(errno));
    free(path);
}

START_TEST(test_output_through_a_symbolic_link_is_refused)
{
    put("meshes/bunny.obj", "v 0 0 0\n");
    make_dir("out");
    make_dir("out/scenes");
    make_link("../../meshes", "out/scenes/meshes");
    put("chapters/01-a.md",
        "```{.c file=\"a.c\"}\n"
        "a;\n"
        "```\n"
        "```{.obj file=\"scenes/meshes/bunny.obj\"}\n"
        "overwritten\n"
        "```\n");
    struct run r = tangle("-o", "out", "chapters/01-a.md", NULL);
    ck_assert_int_eq(r.status, 1);
    ck_assert_str_eq(
        r.err, "chapters/01-a.md:4: error: output path "
               "'scenes/meshes/bunny.obj' passes through a symbolic link\n");
    free_run(&r);
    assert_file("meshes/bunny.obj", "v 0 0 0\n");
    ck_assert(!exists("out/a.c"));
}
END_TEST

START_TEST(test_output_file_that_is_a_symbolic_link_is_refused)
{
    put("target.c", "keep\n");
    make_dir("out");
    make_link("../target.c", "out/a.c");
    put("chapters/01-a.md", "```{.c file=\"a.c\"}\nnew;\n```\n");
    struct run r = tangle("-o", "out", "chapters/01-a.md", NULL);
    ck_assert_int_eq(r.status, 1);
    ck_assert_str_eq(r.err, "chapters/01-a.md:1: error: output path 'a.c' "
                            "passes through a symbolic link\n");
    free_run(&r);
    assert_file("target.c", "keep\n");
}
END_TEST

START_TEST(test_outdir_itself_may_be_a_symbolic_link)
{
    make_dir("real");
    make_link("real", "out");
    put("chapters/01-a.md", "```{.c file=\"sub/a.c\"}\na;\n```\n");
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("real/sub/a.c", "a;\n");
}
END_TEST

START_TEST(test_output_through_a_plain_file_is_refused_before_writing)
{
    put("out/sub", "a file, not a directory\n");
    make_dir("out/d.c");
    put("chapters/01-a.md",
        "```{.c file=\"first.c\"}\n"
        "first;\n"
        "```\n"
        "```{.c file=\"sub/x.c\"}\n"
        "x;\n"
        "```\n"
        "```{.c file=\"d.c\"}\n"
        "d;\n"
        "```\n");
    struct run r = tangle("-o", "out", "chapters/01-a.md", NULL);
    ck_assert_int_eq(r.status, 1);
    ck_assert_str_eq(
        r.err,
        "chapters/01-a.md:4: error: output path 'sub/x.c' "
        "passes through a file that is not a directory\n"
        "chapters/01-a.md:7: error: output path 'd.c' names a directory\n");
    free_run(&r);
    ck_assert(!exists("out/first.c"));
}
END_TEST

START_TEST(test_outputs_over_256_mib_in_all_are_refused)
{
    /* Five files of exactly 64 MiB each (allowed one by one): 64 lines of
       1 MiB, by doubling a chunk six times. */
    enum { LINE = 1 << 20 };
    char *md = NULL;
    size_t len;
    FILE *f = open_memstream(&md, &len);
    for (int i = 1; i <= 5; i++)
        fprintf(f, "```{.txt file=\"f%d.txt\"}\n<<d0>>\n```\n", i);
    for (int i = 0; i < 6; i++)
        fprintf(f, "```{.txt chunk=\"d%d\"}\n<<d%d>>\n<<d%d>>\n```\n", i, i + 1,
                i + 1);
    fputs("```{.txt chunk=\"d6\"}\n", f);
    for (int i = 0; i < LINE - 1; i++)
        putc('x', f);
    fputs("\n```\n", f);
    fclose(f);
    put("chapters/01-a.md", md);
    free(md);
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", NULL),
        "chapters/01-a.md:13: error: file 'f5.txt' would take all outputs "
        "together over 268435456 bytes\n");
}
END_TEST

START_TEST(test_fifo_as_chapter_is_refused_without_hanging)
{
    put("chapters/01-a.md", good_root);
    char *fifo = work_path("chapters/02-fifo.md");
    ck_assert_int_eq(mkfifo(fifo, 0600), 0);
    free(fifo);
    struct run_options deadline = {.deadline = 10};
    char *argv[] = {
        NULL, "-o", "out", "chapters/01-a.md", "chapters/02-fifo.md", NULL};
    expect_failure(tangle_with(&deadline, argv),
                   "chapters/02-fifo.md: error: cannot read: not a regular "
                   "file but a FIFO\n");
}
END_TEST

START_TEST(test_endless_stdin_as_chapter_is_refused_without_hanging)
{
    put("chapters/01-a.md", good_root);
    struct run_options endless_pipe = {.deadline = 10, .stdin_pipe = true};
    char *argv[] = {NULL, "-o", "out", "chapters/01-a.md", "/dev/stdin", NULL};
    expect_failure(
        tangle_with(&endless_pipe, argv),
        "/dev/stdin: error: cannot read: not a regular file but a FIFO\n");
}
END_TEST

START_TEST(test_device_as_chapter_is_refused)
{
    put("chapters/01-a.md", good_root);
    struct run_options deadline = {.deadline = 10};
    char *argv[] = {NULL, "-o", "out", "chapters/01-a.md", "/dev/zero", NULL};
    expect_failure(
        tangle_with(&deadline, argv),
        "/dev/zero: error: cannot read: not a regular file but a device\n");
}
END_TEST

START_TEST(test_chapter_over_16_mib_is_refused)
{
    put("chapters/01-a.md", good_root);
    put("chapters/02-big.md", "```{.c file=\"big.c\"}\nbig;\n```\n");
    char *big = work_path("chapters/02-big.md");
    ck_assert_int_eq(truncate(big, (16 << 20) + 1), 0); /* sparse: quick */
    free(big);
    expect_failure(
        tangle("-o", "out", "chapters/01-a.md", "chapters/02-big.md", NULL),
        "chapters/02-big.md: error: cannot read: larger than 16777216 bytes, "
        "too large for a chapter\n");
}
END_TEST

START_TEST(test_chapter_of_exactly_16_mib_is_read)
{
    put("chapters/01-a.md", good_root);
    char *path = work_path("chapters/01-a.md");
    ck_assert_int_eq(truncate(path, 16 << 20),
                     0); /* NUL bytes after the block */
    free(path);
    expect_success(tangle("-o", "out", "chapters/01-a.md", NULL));
    assert_file("out/good.c", "good;\n");
}
END_TEST

/* ---- what messages show --------------------------------------------- */

START_TEST(test_long_paths_and_names_are_not_cut_short)
{
    char dir[3 * 201 + 1] = "", name[1001] = "";
    for (int i = 0; i < 3; i++) {
        memset(dir + 201 * i, 'd' + i, 200);
        dir[201 * i + 200] = '/';
    }
    memset(name, 'n', 1000);
    char *chapter = NULL, *md = NULL, *expected = NULL;
    size_t len;
    FILE *f = open_memstream(&chapter, &len);
    fprintf(f, "chapters/%s01-a.md", dir);
    fclose(f);
    f = open_memstream(&md, &len);
    fprintf(f, "```{.c file=\"a.c\"}\n<<%s>>\n```\n", name);
    fclose(f);
    f = open_memstream(&expected, &len);
    fprintf(f, "%s:2: error: reference to undefined chunk '%s'\n", chapter,
            name);
    fclose(f);
    put(chapter, md);
    expect_failure(tangle("-o", "out", chapter, NULL), expected);
    free(chapter);
    free(md);
    free(expected);
}
END_TEST

START_TEST(test_unprintable_bytes_in_messages_are_escaped)
{
    static const char md[] =
        "```{.c file=\"a.c\"}\n"
        "<<esc\033[31m>>\n"
        "<<nul\0byte>>\n"
        "<<bad\377 utf8 \302\233 c1>>\n"
        "<<fine \303\251>>\n"
        "```\n";
    put_bytes("chapters/01-\033[2J.md", md, sizeof md - 1);
    put("chapters/02-b.md", "```{.c file=\"/abs\a.c\"}\nx;\n```\n");
    expect_failure(
        tangle("-o", "out", "chapters/01-\033[2J.md", "chapters/02-b.md",
               "chapters/03-\033]0;title\a.md", NULL),
        "chapters/02-b.md:1: error: file path '/abs\\x07.c' is absolute\n"
        "chapters/03-\\x1B]0;title\\x07.md: error: cannot read: "
        "No such file or directory\n"
        "chapters/01-\\x1B[2J.md:2: error: reference to undefined chunk "
        "'esc\\x1B[31m'\n"
        "chapters/01-\\x1B[2J.md:3: error: reference to undefined chunk "
        "'nul\\x00byte'\n"
        "chapters/01-\\x1B[2J.md:4: error: reference to undefined chunk "
        "'bad\\xFF utf8 \\xC2\\x9B c1'\n"
        "chapters/01-\\x1B[2J.md:5: error: reference to undefined chunk "
        "'fine \303\251'\n");
}
END_TEST

Suite *tangle_suite(void)
{
    Suite *s = suite_create("tangle");
    TCase *rules = tcase_create("rules");
    TCase *lines = tcase_create("line directives");
    TCase *errors = tcase_create("errors");
    TCase *markers = tcase_create("markers");
    TCase *files = tcase_create("inputs and outputs");
    TCase *messages = tcase_create("messages");
    TCase *all[] = {rules, lines, errors, markers, files, messages};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        tcase_add_checked_fixture(all[i], setup, teardown);
        tcase_set_timeout(all[i], 20);
        suite_add_tcase(s, all[i]);
    }

    tcase_add_test(rules, test_file_block_is_written_to_outdir);
    tcase_add_test(rules, test_append_adds_to_end_of_definition);
    tcase_add_test(
        rules, test_replace_discards_whole_body_and_later_append_extends_it);
    tcase_add_test(rules, test_append_works_across_chapter_files);
    tcase_add_test(rules, test_file_roots_can_be_appended_and_replaced);
    tcase_add_test(rules,
                   test_exercise_class_means_nothing_without_skip_option);
    tcase_add_test(rules, test_skip_not_done_leaves_an_unstarted_exercise_out);
    tcase_add_test(rules, test_skip_not_done_uses_a_started_exercise);
    tcase_add_test(rules, test_skip_not_done_keeps_blocks_not_marked_exercise);
    tcase_add_test(rules, test_files_and_chunks_are_separate_namespaces);
    tcase_add_test(rules, test_root_files_in_subdirectories_are_created);
    tcase_add_test(rules, test_inner_dotdot_stays_inside_outdir);
    tcase_add_test(rules, test_nested_references_are_indented_cumulatively);
    tcase_add_test(rules, test_empty_lines_are_not_indented);
    tcase_add_test(rules, test_angle_brackets_inside_a_line_are_plain_text);
    tcase_add_test(rules, test_illustration_blocks_are_skipped);
    tcase_add_test(rules, test_longer_fence_keeps_shorter_fence_as_body);
    tcase_add_test(rules, test_tilde_fences_hold_code);
    tcase_add_test(rules, test_attribute_variants_are_accepted);
    tcase_add_test(rules, test_crlf_line_endings_end_lines);
    tcase_add_test(rules, test_missing_final_newline_is_supplied);
    tcase_add_test(rules, test_nul_bytes_and_long_lines_are_copied);
    tcase_add_test(rules, test_many_chunks_are_tangled);
    tcase_add_test(rules, test_running_twice_gives_identical_bytes);
    tcase_add_test(rules, test_unchanged_output_keeps_its_mtime);
    tcase_add_test(rules, test_changed_output_is_rewritten);
    tcase_add_test(rules, test_unused_chunk_is_only_a_warning);
    tcase_add_test(rules, test_bad_usage_exits_with_status_2);
    tcase_add_test(rules, test_help_prints_usage_and_succeeds);
    tcase_add_test(rules, test_nesting_of_999_chunks_is_accepted);

    tcase_add_test(lines, test_no_line_directives_without_line_option);
    tcase_add_test(lines, test_line_directive_precedes_each_definition_piece);
    tcase_add_test(lines, test_line_directives_resync_after_nested_references);
    tcase_add_test(lines, test_line_directives_name_each_chapter_file);
    tcase_add_test(lines, test_scene_files_get_no_line_directives);
    tcase_add_test(lines, test_line_output_compiles_with_cc);
    tcase_add_test(lines, test_syntax_error_is_reported_at_its_markdown_line);
    tcase_add_test(
        lines,
        test_syntax_error_after_reference_is_reported_at_its_markdown_line);

    tcase_add_test(errors, test_reference_to_undefined_chunk_is_an_error);
    tcase_add_test(errors, test_cycle_of_references_names_its_chunks);
    tcase_add_test(errors, test_chunk_referring_to_itself_is_a_cycle);
    tcase_add_test(errors, test_second_definition_without_append_is_an_error);
    tcase_add_test(errors, test_second_definition_of_a_file_is_an_error);
    tcase_add_test(errors, test_append_to_undefined_chunk_is_an_error);
    tcase_add_test(errors, test_replace_of_undefined_file_is_an_error);
    tcase_add_test(errors, test_append_together_with_replace_is_an_error);
    tcase_add_test(errors, test_chunk_together_with_file_is_an_error);
    tcase_add_test(errors, test_empty_chunk_name_is_an_error);
    tcase_add_test(errors, test_empty_file_path_is_an_error);
    tcase_add_test(errors, test_unterminated_fence_is_reported_where_it_opened);
    tcase_add_test(errors, test_unterminated_quote_is_an_error);
    tcase_add_test(errors, test_missing_closing_brace_is_an_error);
    tcase_add_test(errors, test_absolute_path_is_an_error);
    tcase_add_test(errors, test_path_leaving_outdir_is_an_error);
    tcase_add_test(errors, test_unreadable_input_is_an_error);
    tcase_add_test(errors, test_unwritable_output_is_an_error);
    tcase_add_test(errors, test_unused_chunk_is_an_error_with_strict);
    tcase_add_test(errors, test_every_error_is_reported_not_only_the_first);
    tcase_add_test(errors, test_nesting_deeper_than_1000_levels_is_an_error);
    tcase_add_test(errors, test_exponential_expansion_is_stopped);

    tcase_add_test(markers,
                   test_marker_names_chunk_and_chapter_at_expansion_indent);
    tcase_add_test(markers,
                   test_marker_names_chapter_by_leading_digits_or_file_name);
    tcase_add_test(markers, test_empty_hook_gets_no_marker);
    tcase_add_test(markers,
                   test_later_chapters_pieces_are_marked_after_replace);
    tcase_add_test(markers, test_markers_only_in_c_and_h_files);
    tcase_add_test(markers, test_line_option_writes_no_markers);
    tcase_add_test(markers, test_no_marker_inside_a_comment_or_a_spliced_line);
    tcase_add_test(markers, test_marker_cannot_end_its_comment_early);
    tcase_add_test(markers, test_plain_output_with_markers_compiles_with_cc);

    tcase_add_test(files, test_output_through_a_symbolic_link_is_refused);
    tcase_add_test(files, test_output_file_that_is_a_symbolic_link_is_refused);
    tcase_add_test(files, test_outdir_itself_may_be_a_symbolic_link);
    tcase_add_test(files,
                   test_output_through_a_plain_file_is_refused_before_writing);
    tcase_add_test(files, test_outputs_over_256_mib_in_all_are_refused);
    tcase_add_test(files, test_fifo_as_chapter_is_refused_without_hanging);
    tcase_add_test(files,
                   test_endless_stdin_as_chapter_is_refused_without_hanging);
    tcase_add_test(files, test_device_as_chapter_is_refused);
    tcase_add_test(files, test_chapter_over_16_mib_is_refused);
    tcase_add_test(files, test_chapter_of_exactly_16_mib_is_read);

    tcase_add_test(messages, test_long_paths_and_names_are_not_cut_short);
    tcase_add_test(messages, test_unprintable_bytes_in_messages_are_escaped);
    return s;
}
