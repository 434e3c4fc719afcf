/* reuse_object.c: compile a chapter's file, or copy the previous chapter's
 * object when nothing it was compiled from has changed.
 *
 *   reuse_object [--code] PREV_OBJ PREV_DIR DIR -- COMPILER ARGS... -o OBJ ...
 *
 * Most files of chapter N are the same text as in chapter N-1, with the
 * same headers: compiled again they would give the same object. PREV_OBJ
 * is chapter N-1's object of the same file, PREV_DIR and DIR the two
 * chapters' tangle folders. PREV_OBJ's dependency file (the .d beside it,
 * which -MMD wrote) lists every file that object was compiled from; when
 * each one under PREV_DIR has the same bytes as its namesake under DIR
 * (files elsewhere, as tests/, are the same file for both), PREV_OBJ is
 * copied to OBJ and its dependency file to OBJ's, with DIR for PREV_DIR.
 * Otherwise, or when anything cannot be read, the compiler runs in this
 * process (execvp), as if this program were not there. The command's
 * flags must be those PREV_OBJ was compiled with but for the folders: the
 * Makefile's one rule for both sees to it. Exits 0 when it copied, 1 when
 * a copy failed half way (nothing is left at OBJ then), 127 when the
 * compiler could not be run.
 *
 * --code compares the files' code only, without their #line directives:
 * the grader's tangle of a workbook holds the book's code wherever the
 * reader has not started an exercise, with #line directives that name the
 * workbook instead of the chapter, and the book's own object then serves
 * (its debugging information names the chapter's lines). Several
 * reuse_object commands may follow one another: each that does not copy
 * runs the next. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_FILE_BYTES (64L << 20) /* a source or object file, generously */

/* The whole file at path, NUL-ended, its length in *length; NULL if it
 * cannot be read. */
static char *read_all(const char *path, long *length)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    char *text = NULL;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 &&
        n <= MAX_FILE_BYTES && fseek(f, 0, SEEK_SET) == 0 &&
        (text = malloc((size_t)n + 1)) != NULL &&
        fread(text, 1, (size_t)n, f) == (size_t)n)
        text[n] = '\0';
    else
        free(text), text = NULL;
    fclose(f);
    *length = n;
    return text;
}

static bool code_only; /* --code: #line directives do not count */

/* Whether the text at p starts a #line directive. */
static bool is_line_directive(const char *p)
{
    return strncmp(p, "#line ", 6) == 0;
}

/* p past its line and its newline. */
static const char *next_line(const char *p)
{
    const char *end = strchr(p, '\n');
    return end ? end + 1 : p + strlen(p);
}

/* Whether texts x and y are the same but for lines that start "#line ". */
static bool same_code(const char *x, const char *y)
{
    for (;;) {
        while (is_line_directive(x))
            x = next_line(x);
        while (is_line_directive(y))
            y = next_line(y);
        if (*x == '\0' || *y == '\0')
            return *x == *y;
        const char *ex = next_line(x), *ey = next_line(y);
        if (ex - x != ey - y || memcmp(x, y, (size_t)(ex - x)) != 0)
            return false;
        x = ex, y = ey;
    }
}

static bool same_bytes(const char *a, const char *b)
{
    long na, nb;
    char *x = read_all(a, &na), *y = read_all(b, &nb);
    bool same = x != NULL && y != NULL &&
                (code_only ? same_code(x, y)
                           : na == nb && memcmp(x, y, na) == 0);
    free(x), free(y);
    return same;
}

/* path with its prefix from replaced by to, into out[size]; false if it
 * does not start with from followed by '/'. */
static bool rebase(const char *path, const char *from, const char *to,
                   char *out, size_t size)
{
    size_t k = strlen(from);
    if (strncmp(path, from, k) != 0 || path[k] != '/')
        return false;
    return snprintf(out, size, "%s%s", to, path + k) < (int)size;
}

/* The end of the dependency text's first rule: its first newline that no
 * backslash continues (GCC's -MP rules for the headers follow it). */
static char *end_of_first_rule(char *deps)
{
    for (char *p = strchr(deps, '\n'); p != NULL; p = strchr(p + 1, '\n'))
        if (p == deps || p[-1] != '\\')
            return p;
    return NULL;
}

/* Whether every file the dependency text's first rule lists (after its
 * colon, words split by blanks and backslash-newlines) is the same under
 * dir as under prev_dir. */
static bool inputs_unchanged(char *deps, const char *prev_dir, const char *dir)
{
    char *p = strchr(deps, ':'), *end = end_of_first_rule(deps);
    if (p == NULL)
        return false;
    if (end != NULL)
        *end = '\0';
    for (char *word = strtok(p + 1, " \t\\\n"); word != NULL;
         word = strtok(NULL, " \t\\\n")) {
        char now[4096];
        if (rebase(word, prev_dir, dir, now, sizeof now) &&
            !same_bytes(word, now))
            return false;
    }
    return true;
}

/* name with its extension (from the last '.') replaced by ext. */
static bool with_extension(const char *name, const char *ext, char *out,
                           size_t size)
{
    const char *dot = strrchr(name, '.');
    int k = dot ? (int)(dot - name) : (int)strlen(name);
    return snprintf(out, size, "%.*s%s", k, name, ext) < (int)size;
}

static bool write_all(const char *path, const char *text, long length)
{
    FILE *f = fopen(path, "wb");
    bool ok = f != NULL && fwrite(text, 1, (size_t)length, f) == (size_t)length;
    if (f != NULL && fclose(f) != 0)
        ok = false;
    return ok;
}

/* The dependency text with every prev_dir/ made dir/ and prev_obj made obj,
 * written to path. */
static bool write_deps(const char *path, const char *deps,
                       const char *prev_obj, const char *obj,
                       const char *prev_dir, const char *dir)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return false;
    size_t kd = strlen(prev_dir), ko = strlen(prev_obj);
    for (const char *p = deps; *p != '\0';) {
        if (strncmp(p, prev_obj, ko) == 0 && p[ko] == ':')
            fputs(obj, f), p += ko;
        else if (strncmp(p, prev_dir, kd) == 0 && p[kd] == '/')
            fputs(dir, f), p += kd;
        else
            fputc(*p++, f);
    }
    return fclose(f) == 0;
}

/* The argument after "-o" in the command. */
static const char *output_of(char **command)
{
    for (int k = 0; command[k] != NULL; k++)
        if (strcmp(command[k], "-o") == 0)
            return command[k + 1];
    return NULL;
}

/* Copies prev_obj and its dependency file to obj's; false when it did not
 * try (something differs or is missing). */
static bool reuse(const char *prev_obj, const char *prev_dir, const char *dir,
                  const char *obj, int *status)
{
    char prev_deps_path[4096], deps_path[4096];
    long n, m;
    if (obj == NULL ||
        !with_extension(prev_obj, ".d", prev_deps_path, sizeof prev_deps_path) ||
        !with_extension(obj, ".d", deps_path, sizeof deps_path))
        return false;
    char *deps = read_all(prev_deps_path, &n);
    char *scratch = deps ? strdup(deps) : NULL;
    char *object = NULL;
    bool tried = false;
    if (scratch != NULL && inputs_unchanged(scratch, prev_dir, dir) &&
        (object = read_all(prev_obj, &m)) != NULL) {
        tried = true;
        bool ok = write_all(obj, object, m) &&
                  write_deps(deps_path, deps, prev_obj, obj, prev_dir, dir);
        if (!ok)
            remove(obj);
        *status = ok ? 0 : 1;
    }
    free(deps), free(scratch), free(object);
    return tried;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--code") == 0)
        code_only = true, argv++, argc--;
    if (argc < 6 || strcmp(argv[4], "--") != 0) {
        fprintf(stderr, "usage: reuse_object [--code] PREV_OBJ PREV_DIR DIR "
                        "-- COMPILER ARGS... -o OBJ ...\n");
        return 2;
    }
    int status;
    if (reuse(argv[1], argv[2], argv[3], output_of(argv + 5), &status))
        return status;
    execvp(argv[5], argv + 5);
    perror(argv[5]);
    return 127;
}
