/*
 * tangle - extract the program of a literate book from its chapters.
 *
 * USAGE: tangle [--line] [--strict] [--skip-not-done] -o OUTDIR CHAPTER.md...
 *   Reads the chapters in the order given and writes every root file they
 *   define below OUTDIR, creating directories as needed.  A file is only
 *   rewritten when its bytes change (so make does not rebuild needlessly);
 *   other files in OUTDIR are left alone.
 *   --line    emit #line directives into .c and .h outputs, so that the
 *             compiler reports errors at CHAPTER.md:LINE
 *   --strict  a chunk that no root file uses is an error, not a warning
 *   --skip-not-done
 *             a block marked .exercise that holds a line starting with
 *             "// NOT DONE" (blanks in front allowed) is skipped, as if it were an
 *             illustration: a workbook exercise its reader has not started
 *             (see EXERCISES)
 *   --help    print the usage
 *
 * CODE BLOCKS
 *   A fence is 3 or more backticks or tildes at column 0, closed by a line
 *   at column 0 of at least as many of the same character and nothing else
 *   but blanks.  A block is program code only when its info string is a
 *   pandoc attribute list with chunk= or file=; other blocks are skipped.
 *     ```{.c file="vec.h"}                root file, written to OUTDIR/vec.h
 *     ```{.c chunk="vector ops"}          first definition of a named chunk
 *     ```{.c chunk="vector ops" .append}  adds lines at the end of the body
 *     ```{.c chunk="shade" .replace}      replaces the whole body so far
 *   Braces hold .class, #id, key="value" (with \" and \\) and key=value.
 *   .append and .replace work for files too.  A file path must stay inside
 *   OUTDIR ("a/../b.c" means "b.c"), and no part of it below OUTDIR that
 *   already exists may be a symbolic link (OUTDIR itself may be one): a
 *   link such as scenes/meshes -> the repository's meshes/ would make the
 *   tangler overwrite what it points at.
 *
 * EXERCISES
 *   The class .exercise marks a block that the book's reader may write
 *   themselves; key="value" pairs such as tests="..." describe it for the
 *   workbook tools (tools/workbook/workbook.awk, tools/workbook/grade.sh).  To the tangler
 *   it means nothing, except with --skip-not-done (above): the workbook's
 *   stub of a chunk is a .replace with .exercise and a line "// NOT DONE",
 *   and it replaces the book's code only once its reader deletes that line.
 *
 * REFERENCES
 *   A code line holding only <<name>> (blanks around it allowed) expands to
 *   the body of chunk 'name', each line prefixed with the blanks in front
 *   of the reference (blank lines get no prefix).  References nest up to
 *   1000 deep.  "<<" anywhere else in a line is plain text.
 *
 * MARKERS
 *   Without --line, every expansion of a chunk in a .c or .h output starts
 *   with a C comment holding "<<vector ops>> ch03": the chunk, and the
 *   chapter of its first piece that writes lines (an empty hook defined in
 *   ch01 and filled in ch02 says ch02).  It is indented like the lines it
 *   names, so that a reader of the plain tangle can find them in the book.
 *   Where a later chapter's piece of the chunk starts, a comment holding
 *   "<<vector ops>> += ch05" marks it.  A chapter is named "ch" and the
 *   leading digits of its file name (chapters/03-phong.md: ch03), or its
 *   file name if that has no leading digits.  An expansion that writes no
 *   line (an empty hook) gets no marker, and neither does one inside a
 *   block comment or after a line ending in a backslash, where a comment
 *   would change the code (comments, strings and // are looked at just
 *   enough for that).  In a marker, a "/" and a "*" side by side in a chunk
 *   name get a blank between them, and bytes that are not printable are
 *   written as \xHH, as in messages.  Root files, other outputs (.scene,
 *   ...) and --line output get no markers.  Markers depend only on the
 *   chapters, so the output stays the same from run to run.
 *
 * LINE DIRECTIVES
 *   With --line, '#line N "CHAPTER"' is written whenever the next line of a
 *   .c or .h output does not directly follow the previous one in the same
 *   chapter: before every piece of a definition and after every reference.
 *
 * LIMITS
 *   A chapter must be a regular file (not a directory, FIFO or device) of
 *   at most 16 MiB.  An output may hold at most 64 MiB and all outputs
 *   together at most 256 MiB, since all of them are held in memory until
 *   every one is known to be good.
 *
 * DIAGNOSTICS: "CHAPTER:LINE: error: MESSAGE" on stderr, exit status 1.
 *   Everything is checked before anything is written; after an error
 *   nothing is written.  Errors: unreadable chapter (missing, not a
 *   regular file, over 16 MiB), unclosed fence, bad attributes, chunk=
 *   with file=, .append with .replace, empty name or path, path absolute
 *   or leaving OUTDIR, path through a symbolic link or through a file that
 *   is not a directory, path naming a directory, second definition without
 *   .append/.replace, .append/.replace of something undefined, reference
 *   to an undefined chunk, cycle of references, nesting deeper than 1000,
 *   an output over 64 MiB, outputs over 256 MiB in all, unwritable output.
 *   A chunk no root file reaches gets a warning (an error with --strict).
 *   Bad usage exits 2.  Messages show every byte that is not printable
 *   (control characters, C1 controls, invalid UTF-8; valid UTF-8 is kept)
 *   as \xHH, so that a chapter or a file name cannot send escape sequences
 *   to the terminal; names and paths are shown whole, however long.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { MAX_DEPTH = 1000 };
/* Stops a chunk that doubles itself level after level from eating memory. */
#define MAX_OUTPUT_BYTES ((size_t)64 << 20)
/* All outputs wait in memory until every one is known to be good: many
   root files of a small chapter must not add up to gigabytes. */
#define MAX_TOTAL_OUTPUT_BYTES ((size_t)256 << 20)
/* A chapter is text that people write and read: anything bigger is a
   mistake (a data file or a device given by accident), not a chapter. */
#define MAX_CHAPTER_BYTES ((size_t)16 << 20)

struct span { const char *text; size_t len; };
struct buffer { char *data; size_t len, cap; };

struct source {
    const char *path;          /* exactly as given on the command line */
    char *label;               /* what markers call it: "ch03" */
    char *text;
    struct span *lines;        /* without the "\n" or "\r\n" */
    size_t n_lines, cap_lines;
};

/* One fenced block: lines first .. first+count-1 (0-based) of src. */
struct piece {
    const struct source *src;
    size_t first, count;
    bool yields_lines;         /* expanding it writes at least one line */
};

struct chunk {
    char *name;                /* chunk name, or clean path of a root file */
    size_t name_len;
    bool is_file, used;
    const struct source *src;  /* where it was first defined */
    size_t line;
    struct piece *pieces;
    size_t n_pieces, cap_pieces;
    size_t live_from;          /* pieces before this one were replaced */
    enum { UNVISITED, VISITING, DONE } state;
    enum { YIELD_UNKNOWN, YIELD_NOTHING, YIELD_LINES } yield;
};

struct tangle {
    bool line_directives, strict, skip_not_done;
    const char *outdir;
    struct source *sources;
    size_t n_sources;
    struct chunk **chunks;     /* in order of definition */
    size_t n_chunks, cap_chunks;
    struct chunk **slots;      /* open-addressing hash table, half empty */
    size_t n_slots;
    int errors;
};

/* ---- memory and messages ------------------------------------------- */

/* Running out of memory is the one failure we do not try to survive. */
static void *check_alloc(void *p)
{
    if (!p) {
        fputs("tangle: out of memory\n", stderr);
        exit(1);
    }
    return p;
}

/* Makes room for one more element in the growable array ITEMS. */
static void *grow(void *items, size_t count, size_t *cap, size_t size)
{
    if (count < *cap)
        return items;
    *cap = *cap ? 2 * *cap : 16;
    return check_alloc(*cap > SIZE_MAX / size ? NULL : realloc(items, *cap * size));
}

static char *copy_string(const char *s, size_t len)
{
    char *copy = check_alloc(malloc(len + 1));
    memcpy(copy, s, len);
    copy[len] = '\0';
    return copy;
}

/* Makes room for N more bytes. */
static void buffer_reserve(struct buffer *b, size_t n)
{
    while (b->cap - b->len < n)
        b->data = grow(b->data, b->cap, &b->cap, 1);
}

static void buffer_add(struct buffer *b, const char *s, size_t n)
{
    buffer_reserve(b, n);
    if (n > 0) /* memcpy wants real pointers even for 0 bytes */
        memcpy(b->data + b->len, s, n);
    b->len += n;
}

static void buffer_add_str(struct buffer *b, const char *s)
{
    buffer_add(b, s, strlen(s));
}

/* Returns the contents as a C string; the buffer gives up ownership. */
static char *buffer_take_string(struct buffer *b)
{
    buffer_add(b, "", 1);
    return b->data;
}

/* Appends printf-style text, however long: paths are never cut short. */
static void buffer_add_vformat(struct buffer *b, const char *fmt, va_list ap)
{
    va_list again;
    va_copy(again, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    if (n > 0) {
        buffer_reserve(b, (size_t)n + 1); /* vsnprintf also writes a '\0' */
        vsnprintf(b->data + b->len, (size_t)n + 1, fmt, again);
        b->len += (size_t)n;
    }
    va_end(again);
}

/* Length of the valid UTF-8 sequence at P for a printable character
   (U+00A0 and up), or 0: C1 controls and malformed bytes get escaped. */
static size_t printable_utf8_length(const unsigned char *p, size_t n)
{
    static const uint32_t smallest[] = {0, 0, 0xA0, 0x800, 0x10000};
    size_t len = p[0] >= 0xF0 ? 4 : p[0] >= 0xE0 ? 3 : p[0] >= 0xC2 ? 2 : 0;
    if (len == 0 || len > n || p[0] > 0xF4)
        return 0;
    uint32_t code = p[0] & (0x7Fu >> len);
    for (size_t i = 1; i < len; i++) {
        if ((p[i] & 0xC0) != 0x80)
            return 0;
        code = code << 6 | (p[i] & 0x3Fu);
    }
    bool valid = code >= smallest[len] && code <= 0x10FFFF &&
                 !(code >= 0xD800 && code <= 0xDFFF);
    return valid ? len : 0;
}

/* Copies S with every byte that is not printable as \xHH, so that a name
   from a chapter cannot drive the terminal; IN_COMMENT also keeps "/" and
   "*" apart, so that the text cannot end or nest a C comment. */
static void add_escaped(struct buffer *b, const char *s, size_t n, bool in_comment)
{
    const unsigned char *u = (const unsigned char *)s;
    for (size_t i = 0; i < n;) {
        size_t len = u[i] >= 0x20 && u[i] < 0x7F ? 1 : printable_utf8_length(u + i, n - i);
        if (len == 0) {
            char hex[5];
            snprintf(hex, sizeof hex, "\\x%02X", u[i]);
            buffer_add(b, hex, 4);
            len = 1;
        } else {
            buffer_add(b, s + i, len);
        }
        if (in_comment && i + 1 < n && (s[i] == '/' || s[i] == '*') &&
            (s[i + 1] == '/' || s[i + 1] == '*') && s[i] != s[i + 1])
            buffer_add(b, " ", 1);
        i += len;
    }
}

/* A copy of the N bytes at S that is safe to print (NUL bytes too). */
static char *copy_escaped(const char *s, size_t n)
{
    struct buffer b = {0};
    add_escaped(&b, s, n, false);
    return buffer_take_string(&b);
}

/* Prints PATH:LINE: error: ... (LINE 0: about the whole file), escaped. */
static void __attribute__((format(printf, 5, 6)))
diagnose(struct tangle *t, bool is_error, const char *path, size_t line,
         const char *fmt, ...)
{
    struct buffer raw = {0}, shown = {0};
    va_list ap;
    buffer_add_str(&raw, path);
    if (line > 0) {
        char number[32];
        snprintf(number, sizeof number, ":%zu", line);
        buffer_add_str(&raw, number);
    }
    buffer_add_str(&raw, is_error ? ": error: " : ": warning: ");
    va_start(ap, fmt);
    buffer_add_vformat(&raw, fmt, ap);
    va_end(ap);
    add_escaped(&shown, raw.data, raw.len, false);
    buffer_add(&shown, "\n", 1);
    fwrite(shown.data, 1, shown.len, stderr);
    free(raw.data);
    free(shown.data);
    t->errors += is_error;
}

/* ---- reading chapters ---------------------------------------------- */

/* Why a file was not read: an errno, or one of these. */
enum { READ_NOT_REGULAR = -1, READ_TOO_LARGE = -2 };

/* Reads from FD until end of file, but never more than LIMIT + 1 bytes. */
static int read_at_most(int fd, size_t limit, struct buffer *b)
{
    for (;;) {
        size_t want = limit + 1 - b->len;
        buffer_reserve(b, want < (1 << 16) ? want : (1 << 16));
        size_t room = b->cap - b->len < want ? b->cap - b->len : want;
        ssize_t n = read(fd, b->data + b->len, room);
        if (n < 0 && errno != EINTR)
            return errno;
        b->len += n > 0 ? (size_t)n : 0;
        if (n == 0 || b->len > limit)
            return b->len > limit ? READ_TOO_LARGE : 0;
    }
}

/* Reads PATH into *TEXT ('\0' added) if it is a regular file of at most
   LIMIT bytes.  Returns 0, an errno, READ_NOT_REGULAR (*MODE tells what it
   is) or READ_TOO_LARGE.  A FIFO or a device would block or never end. */
static int read_regular_file(const char *path, size_t limit, char **text,
                             size_t *len, mode_t *mode)
{
    struct buffer b = {0};
    struct stat st;
    *text = NULL;
    *len = 0;
    int fd = open(path, O_RDONLY | O_NOCTTY | O_NONBLOCK); /* a FIFO must not block */
    if (fd < 0)
        return errno;
    int err = fstat(fd, &st) != 0 ? errno
            : !S_ISREG(st.st_mode) ? READ_NOT_REGULAR
            : (uintmax_t)st.st_size > limit ? READ_TOO_LARGE : 0;
    *mode = err == READ_NOT_REGULAR ? st.st_mode : 0;
    if (!err) {
        buffer_reserve(&b, (size_t)st.st_size + 1);
        err = read_at_most(fd, limit, &b);
    }
    close(fd);
    *len = b.len;
    *text = buffer_take_string(&b);
    return err;
}

/* What a file that is not a regular one is, for a message. */
static const char *file_kind(mode_t mode)
{
    return S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO"
         : S_ISCHR(mode) || S_ISBLK(mode) ? "a device"
         : S_ISSOCK(mode) ? "a socket" : "something else";
}

/* "ch03" for chapters/03-phong.md; the file name if it has no number. */
static char *chapter_label(const char *path)
{
    const char *name = strrchr(path, '/');
    name = name ? name + 1 : path;
    size_t digits = strspn(name, "0123456789");
    if (digits == 0)
        return copy_string(name, strlen(name));
    char *label = check_alloc(malloc(digits + 3));
    memcpy(label, "ch", 2);
    memcpy(label + 2, name, digits);
    label[digits + 2] = '\0';
    return label;
}

/* A line ends at "\n"; a "\r" right before it (or before the end) is dropped. */
static void split_lines(struct source *s, size_t len)
{
    const char *p = s->text, *end = s->text + len;
    while (p < end) {
        const char *newline = memchr(p, '\n', (size_t)(end - p));
        size_t n = (size_t)((newline ? newline : end) - p);
        if (n > 0 && p[n - 1] == '\r')
            n--;
        s->lines = grow(s->lines, s->n_lines, &s->cap_lines, sizeof *s->lines);
        s->lines[s->n_lines++] = (struct span){p, n};
        p = newline ? newline + 1 : end;
    }
}

static bool is_blank_char(char c) { return c == ' ' || c == '\t'; }

static struct span trim(struct span s)
{
    while (s.len > 0 && is_blank_char(s.text[0]))
        s.text++, s.len--;
    while (s.len > 0 && is_blank_char(s.text[s.len - 1]))
        s.len--;
    return s;
}

static bool is_blank(struct span s) { return trim(s).len == 0; }

static bool span_is(struct span s, const char *word)
{
    return s.len == strlen(word) && memcmp(s.text, word, s.len) == 0;
}

/* ---- chunk table --------------------------------------------------- */

/* The slot holding the chunk, or the empty slot where it would go. */
static struct chunk **table_slot(const struct tangle *t, bool is_file,
                                 const char *name, size_t len)
{
    uint64_t hash = 14695981039346656037u ^ (uint64_t)is_file; /* FNV-1a */
    for (size_t i = 0; i < len; i++)
        hash = (hash ^ (unsigned char)name[i]) * 1099511628211u;
    for (size_t i = (size_t)hash;; i++) {
        struct chunk *c = t->slots[i & (t->n_slots - 1)];
        if (!c || (c->is_file == is_file && c->name_len == len &&
                   memcmp(c->name, name, len) == 0))
            return &t->slots[i & (t->n_slots - 1)];
    }
}

static struct chunk *find_chunk(const struct tangle *t, bool is_file,
                                const char *name, size_t len)
{
    return t->n_slots ? *table_slot(t, is_file, name, len) : NULL;
}

static struct chunk *new_chunk(struct tangle *t, bool is_file, const char *name,
                               const struct source *src, size_t line)
{
    struct chunk *c = check_alloc(malloc(sizeof *c));
    *c = (struct chunk){.name = copy_string(name, strlen(name)),
                        .name_len = strlen(name), .is_file = is_file,
                        .src = src, .line = line};
    t->chunks = grow(t->chunks, t->n_chunks, &t->cap_chunks, sizeof *t->chunks);
    t->chunks[t->n_chunks++] = c;
    if (2 * t->n_chunks > t->n_slots) { /* rebuild the table twice as big */
        free(t->slots);
        t->n_slots = t->n_slots ? 2 * t->n_slots : 64;
        t->slots = check_alloc(calloc(t->n_slots, sizeof *t->slots));
        for (size_t i = 0; i < t->n_chunks; i++)
            *table_slot(t, t->chunks[i]->is_file, t->chunks[i]->name,
                        t->chunks[i]->name_len) = t->chunks[i];
    } else {
        *table_slot(t, is_file, c->name, c->name_len) = c;
    }
    return c;
}

/* ---- attributes: {.c chunk="name" .append} ------------------------- */

struct attributes { char *chunk, *file; bool append, replace, exercise; };

/* Length of the word at P: it stops at a blank, '}' or STOP. */
static size_t word_length(const char *p, const char *end, char stop)
{
    size_t n = 0;
    while (p + n < end && !is_blank_char(p[n]) && p[n] != '}' && p[n] != stop)
        n++;
    return n;
}

/* Reads a "quoted" (with \" and \\) or bare value at *PP. */
static const char *read_value(const char **pp, const char *end, char **value)
{
    struct buffer b = {0};
    const char *p = *pp;
    if (p < end && *p == '"') {
        for (p++; p < end && *p != '"'; p++) {
            p += *p == '\\' && p + 1 < end;
            buffer_add(&b, p, 1);
        }
        if (p++ == end) {
            free(b.data);
            return "unterminated quote in attributes";
        }
    } else {
        buffer_add(&b, p, word_length(p, end, '\0'));
        p += b.len;
    }
    *pp = p;
    *value = buffer_take_string(&b);
    return NULL;
}

static const char *parse_key_value(const char **pp, const char *end,
                                   struct attributes *a)
{
    struct span key = {*pp, word_length(*pp, end, '=')};
    char *value = NULL, **slot = span_is(key, "chunk") ? &a->chunk
                               : span_is(key, "file")  ? &a->file : NULL;
    *pp += key.len;
    if (key.len == 0 || *pp == end || **pp != '=')
        return "expected .class, #id or key=\"value\" in attributes";
    (*pp)++;
    const char *err = read_value(pp, end, &value);
    if (!err && slot && *slot)
        err = "chunk= or file= given twice";
    if (!err && slot) {
        *slot = value;
        value = NULL;
    }
    free(value); /* other keys mean nothing to the tangler */
    return err;
}

/* INFO starts with '{'.  Returns NULL, or a message saying what is wrong. */
static const char *parse_attributes(struct span info, struct attributes *a)
{
    const char *p = info.text + 1, *end = info.text + info.len;
    if (memchr(info.text, '\0', info.len))
        return "NUL byte in attributes";
    for (;;) {
        while (p < end && is_blank_char(*p))
            p++;
        if (p == end)
            return "missing '}' in attributes";
        if (*p == '}')
            break;
        if (*p != '.' && *p != '#') {
            const char *err = parse_key_value(&p, end, a);
            if (err)
                return err;
            continue;
        }
        struct span word = {p + 1, word_length(p + 1, end, '\0')};
        if (word.len == 0)
            return "empty class or id in attributes";
        a->append |= *p == '.' && span_is(word, "append");
        a->replace |= *p == '.' && span_is(word, "replace");
        a->exercise |= *p == '.' && span_is(word, "exercise");
        p = word.text + word.len;
    }
    return is_blank((struct span){p + 1, (size_t)(end - p - 1)})
               ? NULL : "unexpected text after '}' in attributes";
}

/* ---- definitions --------------------------------------------------- */

/* Folds "." and "x/.." away; NULL with *WHY set if the path is unusable. */
static char *clean_path(const char *path, const char **why)
{
    const char *last = strrchr(path, '/');
    last = last ? last + 1 : path;
    *why = path[0] == '/' ? "is absolute"
         : (!*last || !strcmp(last, ".") || !strcmp(last, "..")) ? "does not name a file"
         : NULL;
    char *out = check_alloc(malloc(strlen(path) + 1));
    size_t n = 0; /* out[0..n) is the clean path so far */
    for (const char *p = path; *p && !*why; p += *p == '/') {
        size_t len = strcspn(p, "/");
        if (len == 2 && p[0] == '.' && p[1] == '.') {
            if (n == 0)
                *why = "leaves the output directory";
            while (n > 0 && out[n - 1] != '/')
                n--;
            n -= n > 0; /* and the slash in front of the dropped component */
        } else if (len > 0 && !(len == 1 && p[0] == '.')) {
            if (n > 0)
                out[n++] = '/';
            memcpy(out + n, p, len);
            n += len;
        }
        p += len;
    }
    out[n] = '\0';
    if (!*why)
        return out;
    free(out);
    return NULL;
}

/* The key a block defines (chunk name or clean path), or NULL on error. */
static char *block_key(struct tangle *t, const struct source *src, size_t line,
                       const struct attributes *a)
{
    const char *why = a->chunk && a->file ? "chunk= and file= cannot be combined"
                    : a->append && a->replace ? ".append and .replace cannot be combined"
                    : a->chunk && !*a->chunk ? "empty chunk name"
                    : a->file && !*a->file ? "empty file path" : NULL;
    if (why) {
        diagnose(t, true, src->path, line, "%s", why);
        return NULL;
    }
    if (a->chunk)
        return copy_string(a->chunk, strlen(a->chunk));
    char *path = clean_path(a->file, &why);
    if (!path)
        diagnose(t, true, src->path, line, "file path '%s' %s", a->file, why);
    return path;
}

static void define_piece(struct tangle *t, const struct source *src, size_t fence,
                         size_t count, const struct attributes *a)
{
    size_t line = fence + 1;
    char *key = block_key(t, src, line, a);
    if (!key)
        return;
    bool is_file = a->file != NULL, extends = a->append || a->replace;
    const char *kind = is_file ? "file" : "chunk";
    struct chunk *c = find_chunk(t, is_file, key, strlen(key));
    if (c && !extends)
        diagnose(t, true, src->path, line,
                 "%s '%s' is already defined at %s:%zu (use .append or .replace)",
                 kind, key, c->src->path, c->line);
    else if (!c && extends)
        diagnose(t, true, src->path, line, "cannot %s undefined %s '%s'",
                 a->append ? "append to" : "replace", kind, key);
    else {
        if (!c)
            c = new_chunk(t, is_file, key, src, line);
        if (a->replace)
            c->live_from = c->n_pieces;
        c->pieces = grow(c->pieces, c->n_pieces, &c->cap_pieces, sizeof *c->pieces);
        c->pieces[c->n_pieces++] =
            (struct piece){.src = src, .first = fence + 1, .count = count};
    }
    free(key);
}

/* ---- fences -------------------------------------------------------- */

struct fence { char ch; size_t width; struct span info; };

static bool opens_fence(struct span line, struct fence *f)
{
    f->ch = line.len > 0 ? line.text[0] : '\0';
    for (f->width = 0; f->width < line.len && line.text[f->width] == f->ch;)
        f->width++;
    f->info = trim((struct span){line.text + f->width, line.len - f->width});
    if (f->width < 3 || (f->ch != '`' && f->ch != '~'))
        return false;
    /* A backtick in the info string makes it inline code (CommonMark). */
    return !(f->ch == '`' && memchr(f->info.text, '`', f->info.len));
}

static bool closes_fence(struct span line, const struct fence *f)
{
    size_t n = 0;
    while (n < line.len && line.text[n] == f->ch)
        n++;
    return n >= f->width && is_blank((struct span){line.text + n, line.len - n});
}

/* An exercise its reader has not started: a line "// NOT DONE" in it. */
static bool is_not_done(const struct source *src, size_t fence, size_t count)
{
    for (size_t i = fence + 1; i <= fence + count; i++) {
        struct span line = trim(src->lines[i]);
        if (line.len >= 11 && memcmp(line.text, "// NOT DONE", 11) == 0)
            return true;
    }
    return false;
}

static void handle_block(struct tangle *t, const struct source *src, size_t fence,
                         struct span info, size_t count)
{
    struct attributes a = {0};
    if (info.len == 0 || info.text[0] != '{')
        return; /* ```c, ```text or no info at all: an illustration */
    const char *err = parse_attributes(info, &a);
    if (err)
        diagnose(t, true, src->path, fence + 1, "%s", err);
    else if ((a.chunk || a.file) &&
             !(t->skip_not_done && a.exercise && is_not_done(src, fence, count)))
        define_piece(t, src, fence, count, &a);
    free(a.chunk);
    free(a.file);
}

static void parse_source(struct tangle *t, const struct source *src)
{
    struct fence f;
    for (size_t i = 0; i < src->n_lines; i++) {
        if (!opens_fence(src->lines[i], &f))
            continue;
        size_t close = i + 1;
        while (close < src->n_lines && !closes_fence(src->lines[close], &f))
            close++;
        if (close == src->n_lines) {
            diagnose(t, true, src->path, i + 1, "code fence is never closed");
            return;
        }
        handle_block(t, src, i, f.info, close - i - 1);
        i = close;
    }
}

static void load_sources(struct tangle *t, char **paths, size_t n)
{
    t->sources = check_alloc(calloc(n, sizeof *t->sources));
    t->n_sources = n;
    for (size_t i = 0; i < n; i++) {
        struct source *s = &t->sources[i];
        size_t len;
        mode_t mode;
        s->path = paths[i];
        s->label = chapter_label(s->path);
        int err = read_regular_file(s->path, MAX_CHAPTER_BYTES, &s->text, &len, &mode);
        if (err == READ_NOT_REGULAR)
            diagnose(t, true, s->path, 0, "cannot read: not a regular file but %s",
                     file_kind(mode));
        else if (err == READ_TOO_LARGE)
            diagnose(t, true, s->path, 0, "cannot read: larger than %zu bytes, "
                     "too large for a chapter", MAX_CHAPTER_BYTES);
        else if (err)
            diagnose(t, true, s->path, 0, "cannot read: %s", strerror(err));
        if (err)
            continue;
        split_lines(s, len);
        parse_source(t, s);
    }
}

/* ---- checking references ------------------------------------------- */

/* A line that is only "<<name>>" (blanks around it allowed). */
static bool parse_reference(struct span line, struct span *indent, struct span *name)
{
    struct span s = trim(line);
    if (s.len < 5 || memcmp(s.text, "<<", 2) != 0 ||
        memcmp(s.text + s.len - 2, ">>", 2) != 0)
        return false;
    *indent = (struct span){line.text, (size_t)(s.text - line.text)};
    *name = (struct span){s.text + 2, s.len - 4};
    return true;
}

struct reference_walk {
    struct chunk *stack[MAX_DEPTH];
    size_t depth;
    bool from_root; /* only chunks reached from a root file count as used */
};

static void check_chunk(struct tangle *t, struct chunk *c, struct reference_walk *w);

static void report_cycle(struct tangle *t, const struct source *src, size_t line,
                         const struct chunk *target, const struct reference_walk *w)
{
    struct buffer msg = {0};
    size_t from = w->depth - 1;
    while (w->stack[from] != target)
        from--;
    for (size_t k = from; k <= w->depth; k++) {
        buffer_add_str(&msg, k > from ? " -> '" : "'");
        buffer_add_str(&msg, k < w->depth ? w->stack[k]->name : target->name);
        buffer_add_str(&msg, "'");
    }
    char *text = buffer_take_string(&msg);
    diagnose(t, true, src->path, line, "cycle of references: %s", text);
    free(text);
}

static void check_reference(struct tangle *t, const struct source *src, size_t line,
                            struct span name, struct reference_walk *w)
{
    struct chunk *target = find_chunk(t, false, name.text, name.len);
    if (!target) {
        char *text = copy_escaped(name.text, name.len); /* it may hold '\0' */
        diagnose(t, true, src->path, line, "reference to undefined chunk '%s'", text);
        free(text);
        return;
    }
    target->used |= w->from_root;
    if (target->state == VISITING)
        report_cycle(t, src, line, target, w);
    else if (target->state == UNVISITED && w->depth == MAX_DEPTH)
        diagnose(t, true, src->path, line, "references nested deeper than %d levels",
                 MAX_DEPTH);
    else if (target->state == UNVISITED)
        check_chunk(t, target, w);
}

static void check_chunk(struct tangle *t, struct chunk *c, struct reference_walk *w)
{
    struct span indent, name;
    c->state = VISITING;
    w->stack[w->depth++] = c;
    for (size_t p = c->live_from; p < c->n_pieces; p++) {
        const struct piece *pc = &c->pieces[p];
        for (size_t i = pc->first; i < pc->first + pc->count; i++)
            if (parse_reference(pc->src->lines[i], &indent, &name))
                check_reference(t, pc->src, i + 1, name, w);
    }
    w->depth--;
    c->state = DONE;
}

/* Walks from the root files first, then checks the chunks they never reach. */
static void check_references(struct tangle *t)
{
    struct reference_walk *w = check_alloc(calloc(1, sizeof *w));
    for (int pass = 0; pass < 2; pass++) {
        w->from_root = pass == 0;
        for (size_t i = 0; i < t->n_chunks; i++)
            if (t->chunks[i]->is_file == w->from_root && t->chunks[i]->state == UNVISITED)
                check_chunk(t, t->chunks[i], w);
    }
    free(w);
    for (size_t i = 0; i < t->n_chunks; i++) {
        const struct chunk *c = t->chunks[i];
        if (!c->is_file && !c->used)
            diagnose(t, t->strict, c->src->path, c->line,
                     "chunk '%s' is defined but never used", c->name);
    }
}

/* ---- expanding ----------------------------------------------------- */

static bool piece_yields_lines(const struct tangle *t, const struct piece *pc);

/* Whether expanding C writes any line: an empty hook gets no marker.
   Also fills in yields_lines of each of its pieces.  No cycles remain. */
static bool chunk_yields_lines(const struct tangle *t, struct chunk *c)
{
    if (c->yield == YIELD_UNKNOWN) {
        c->yield = YIELD_NOTHING;
        for (size_t p = c->live_from; p < c->n_pieces; p++) {
            c->pieces[p].yields_lines = piece_yields_lines(t, &c->pieces[p]);
            if (c->pieces[p].yields_lines)
                c->yield = YIELD_LINES;
        }
    }
    return c->yield == YIELD_LINES;
}

static bool piece_yields_lines(const struct tangle *t, const struct piece *pc)
{
    struct span indent, name;
    for (size_t i = pc->first; i < pc->first + pc->count; i++)
        if (!parse_reference(pc->src->lines[i], &indent, &name) ||
            chunk_yields_lines(t, find_chunk(t, false, name.text, name.len)))
            return true;
    return false;
}

struct output {
    struct buffer text;
    struct buffer indent;     /* blanks of the references we are inside */
    bool line_directives, markers, too_big;
    size_t limit;             /* too_big once the text is longer */
    const char *sync_path;    /* where the compiler thinks the next line is */
    size_t sync_line;
    bool in_comment;          /* the text so far ends inside a block comment */
    bool spliced;             /* its last line ends in a backslash */
};

/* Follows C's block comments, strings and line splices, just enough to
   know where a marker comment could not go. */
static void follow_c_line(struct output *out, struct span line)
{
    char quote = '\0'; /* inside a string or character constant */
    for (size_t i = 0; i < line.len; i++) {
        char c = line.text[i], next = i + 1 < line.len ? line.text[i + 1] : '\0';
        if (out->in_comment) {
            if (c == '*' && next == '/')
                out->in_comment = false, i++;
        } else if (quote) {
            if (c == '\\')
                i++; /* skips the escaped character */
            else if (c == quote)
                quote = '\0';
        } else if (c == '"' || c == '\'') {
            quote = c;
        } else if (c == '/' && next == '/') {
            break;
        } else if (c == '/' && next == '*') {
            out->in_comment = true, i++;
        }
    }
    out->spliced = line.len > 0 && line.text[line.len - 1] == '\\';
}

static void emit_line(struct output *out, const char *path, size_t number,
                      struct span line)
{
    if (out->line_directives && (out->sync_path != path || out->sync_line != number)) {
        char directive[32];
        snprintf(directive, sizeof directive, "#line %zu \"", number);
        buffer_add_str(&out->text, directive);
        for (const char *p = path; *p; p++) {
            if (*p == '"' || *p == '\\')
                buffer_add(&out->text, "\\", 1);
            buffer_add(&out->text, p, 1);
        }
        buffer_add_str(&out->text, "\"\n");
    }
    if (!is_blank(line)) /* blank lines stay free of trailing blanks */
        buffer_add(&out->text, out->indent.data, out->indent.len);
    buffer_add(&out->text, line.text, line.len);
    buffer_add(&out->text, "\n", 1);
    if (out->markers)
        follow_c_line(out, line);
    out->sync_path = path;
    out->sync_line = number + 1;
    out->too_big = out->text.len > out->limit;
}

/* Writes the comment that tells a reader of the plain tangle where in the
   book the lines below come from; not where a comment would change code. */
static void emit_marker(struct output *out, const struct chunk *c,
                        const struct source *src, bool appended)
{
    if (out->in_comment || out->spliced)
        return;
    struct buffer marker = {0};
    buffer_add_str(&marker, "/* <<");
    add_escaped(&marker, c->name, c->name_len, true);
    buffer_add_str(&marker, appended ? ">> += " : ">> ");
    add_escaped(&marker, src->label, strlen(src->label), true);
    buffer_add_str(&marker, " */");
    emit_line(out, NULL, 0, (struct span){marker.data, marker.len});
    free(marker.data);
}

static void emit_chunk(const struct tangle *t, struct output *out,
                       const struct chunk *c)
{
    struct span indent, name;
    const struct source *marked = NULL; /* the chapter the last marker named */
    for (size_t p = c->live_from; p < c->n_pieces; p++) {
        const struct piece *pc = &c->pieces[p];
        if (out->markers && !c->is_file && pc->yields_lines && pc->src != marked) {
            emit_marker(out, c, pc->src, marked != NULL);
            marked = pc->src;
        }
        for (size_t i = pc->first; i < pc->first + pc->count && !out->too_big; i++) {
            if (!parse_reference(pc->src->lines[i], &indent, &name)) {
                emit_line(out, pc->src->path, i + 1, pc->src->lines[i]);
                continue;
            }
            size_t outer = out->indent.len;
            buffer_add(&out->indent, indent.text, indent.len);
            out->too_big = out->indent.len > out->limit;
            emit_chunk(t, out, find_chunk(t, false, name.text, name.len));
            out->indent.len = outer;
        }
    }
}

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* The text of ROOT, added to *TOTAL (the bytes of all outputs so far), or
   an error if it is over 64 MiB or takes *TOTAL over 256 MiB; then *TOTAL
   becomes SIZE_MAX, so that no further output is built. */
static struct buffer generate_file(struct tangle *t, const struct chunk *root,
                                   size_t *total)
{
    struct output out = {0};
    size_t budget = MAX_TOTAL_OUTPUT_BYTES - *total;
    bool is_c = ends_with(root->name, ".c") || ends_with(root->name, ".h");
    out.line_directives = t->line_directives && is_c;
    out.markers = !t->line_directives && is_c;
    out.limit = budget < MAX_OUTPUT_BYTES ? budget : MAX_OUTPUT_BYTES;
    emit_chunk(t, &out, root);
    free(out.indent.data);
    if (!out.too_big) {
        *total += out.text.len;
        return out.text;
    }
    if (out.limit == MAX_OUTPUT_BYTES) {
        diagnose(t, true, root->src->path, root->line,
                 "file '%s' would be larger than %zu bytes", root->name, MAX_OUTPUT_BYTES);
    } else {
        diagnose(t, true, root->src->path, root->line,
                 "file '%s' would take all outputs together over %zu bytes",
                 root->name, MAX_TOTAL_OUTPUT_BYTES);
        *total = SIZE_MAX;
    }
    free(out.text.data); /* it will not be written: its memory goes back now */
    return (struct buffer){0};
}

/* ---- writing ------------------------------------------------------- */

/* OUTDIR/RELATIVE, newly allocated. */
static char *output_path(const struct tangle *t, const char *relative)
{
    struct buffer b = {0};
    buffer_add_str(&b, t->outdir);
    buffer_add_str(&b, ends_with(t->outdir, "/") ? "" : "/");
    buffer_add_str(&b, relative);
    return buffer_take_string(&b);
}

/* What is wrong with the thing at PATH as a directory (or, when LAST, as
   the file itself) on the way to an output, or NULL. */
static const char *path_problem(const char *path, bool last)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return NULL; /* nothing there yet (or an error writing will report) */
    return S_ISLNK(st.st_mode) ? "passes through a symbolic link"
         : !last && !S_ISDIR(st.st_mode) ? "passes through a file that is not a directory"
         : last && S_ISDIR(st.st_mode) ? "names a directory" : NULL;
}

/* Every part of ROOT's path below OUTDIR that exists must be a real
   directory, not a link: a link such as scenes/meshes would let an output
   overwrite what it points at.  Checked before anything is written. */
static void check_output_path(struct tangle *t, const struct chunk *root)
{
    char *path = output_path(t, root->name);
    char *part = path + strlen(path) - root->name_len; /* first part below OUTDIR */
    const char *problem = NULL;
    for (char *slash = strchr(part, '/'); !problem; slash = strchr(slash + 1, '/')) {
        if (slash)
            *slash = '\0';
        problem = path_problem(path, slash == NULL);
        if (!slash)
            break;
        *slash = '/';
    }
    if (problem)
        diagnose(t, true, root->src->path, root->line, "output path '%s' %s",
                 root->name, problem);
    free(path);
}

/* Whether PATH holds TEXT already: then it keeps its mtime, and make
   rebuilds nothing. */
static bool file_has_bytes(const char *path, const struct buffer *text)
{
    char *old = NULL;
    size_t len;
    mode_t mode;
    bool same = read_regular_file(path, text->len, &old, &len, &mode) == 0 &&
                len == text->len && (len == 0 || memcmp(old, text->data, len) == 0);
    free(old);
    return same;
}

/* mkdir -p for every directory in front of the last '/' of PATH. */
static int make_parent_dirs(char *path)
{
    int err = 0;
    for (char *p = strchr(path + 1, '/'); p && !err; p = strchr(p + 1, '/')) {
        *p = '\0';
        if (mkdir(path, 0777) != 0 && errno != EEXIST)
            err = errno;
        *p = '/';
    }
    return err;
}

static int write_all(int fd, const struct buffer *text)
{
    for (size_t done = 0; done < text->len;) {
        ssize_t n = write(fd, text->data + done, text->len - done);
        if (n < 0 && errno != EINTR)
            return errno;
        done += n > 0 ? (size_t)n : 0;
    }
    return 0;
}

/* Writes a temporary file beside PATH and renames it over PATH, so that
   nobody ever sees half a file. */
static int replace_file(const char *path, const struct buffer *text)
{
    struct buffer tmp = {0};
    buffer_add(&tmp, path, (size_t)(strrchr(path, '/') + 1 - path));
    buffer_add_str(&tmp, ".tangle-XXXXXX");
    char *tmp_path = buffer_take_string(&tmp);
    int fd = mkstemp(tmp_path);
    int err = fd < 0 ? errno : write_all(fd, text);
    if (fd >= 0 && !err && fchmod(fd, 0644) != 0) /* mkstemp made it 0600 */
        err = errno;
    if (fd >= 0 && close(fd) != 0 && !err)
        err = errno;
    if (!err && rename(tmp_path, path) != 0)
        err = errno;
    if (err && fd >= 0)
        unlink(tmp_path);
    free(tmp_path);
    return err;
}

static void write_if_changed(struct tangle *t, const char *relative,
                             const struct buffer *text)
{
    char *path = output_path(t, relative);
    if (!file_has_bytes(path, text)) {
        int err = make_parent_dirs(path);
        if (!err)
            err = replace_file(path, text);
        if (err)
            diagnose(t, true, path, 0, "cannot write: %s", strerror(err));
    }
    free(path);
}

/* Builds every file in memory first: an error anywhere writes nothing. */
static void write_outputs(struct tangle *t)
{
    struct buffer *texts = check_alloc(calloc(t->n_chunks + 1, sizeof *texts));
    size_t total = 0;
    for (size_t i = 0; i < t->n_chunks; i++)
        chunk_yields_lines(t, t->chunks[i]); /* which expansions get markers */
    for (size_t i = 0; i < t->n_chunks && total <= MAX_TOTAL_OUTPUT_BYTES; i++) {
        if (!t->chunks[i]->is_file)
            continue;
        check_output_path(t, t->chunks[i]);
        texts[i] = generate_file(t, t->chunks[i], &total);
    }
    for (size_t i = 0; i < t->n_chunks && t->errors == 0; i++)
        if (t->chunks[i]->is_file)
            write_if_changed(t, t->chunks[i]->name, &texts[i]);
    for (size_t i = 0; i < t->n_chunks; i++)
        free(texts[i].data);
    free(texts);
}

/* ---- main ---------------------------------------------------------- */

static void free_tangle(struct tangle *t)
{
    for (size_t i = 0; i < t->n_chunks; i++) {
        free(t->chunks[i]->name);
        free(t->chunks[i]->pieces);
        free(t->chunks[i]);
    }
    for (size_t i = 0; i < t->n_sources; i++) {
        free(t->sources[i].label);
        free(t->sources[i].text);
        free(t->sources[i].lines);
    }
    free(t->chunks);
    free(t->slots);
    free(t->sources);
}

enum options_result { OPTIONS_OK, OPTIONS_HELP, OPTIONS_BAD };

static enum options_result parse_options(int argc, char **argv, struct tangle *t,
                                 char **inputs, size_t *n_inputs)
{
    bool only_inputs = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (only_inputs || a[0] != '-' || a[1] == '\0')
            inputs[(*n_inputs)++] = argv[i];
        else if (strcmp(a, "--") == 0)
            only_inputs = true;
        else if (strcmp(a, "--line") == 0)
            t->line_directives = true;
        else if (strcmp(a, "--strict") == 0)
            t->strict = true;
        else if (strcmp(a, "--skip-not-done") == 0)
            t->skip_not_done = true;
        else if (strcmp(a, "-o") == 0 && i + 1 < argc && argv[i + 1][0] != '\0')
            t->outdir = argv[++i];
        else
            return strcmp(a, "--help") == 0 ? OPTIONS_HELP : OPTIONS_BAD;
    }
    return t->outdir && *n_inputs > 0 ? OPTIONS_OK : OPTIONS_BAD;
}

int main(int argc, char **argv)
{
    static const char usage[] =
        "usage: tangle [--line] [--strict] [--skip-not-done] -o OUTDIR "
        "CHAPTER.md...\n";
    struct tangle t = {0};
    size_t n_inputs = 0;
    char **inputs = check_alloc(calloc((size_t)argc, sizeof *inputs));
    enum options_result parsed = parse_options(argc, argv, &t, inputs, &n_inputs);
    if (parsed == OPTIONS_OK) {
        load_sources(&t, inputs, n_inputs);
        check_references(&t);
        if (t.errors == 0)
            write_outputs(&t);
    } else {
        fputs(usage, parsed == OPTIONS_HELP ? stdout : stderr);
    }
    free_tangle(&t);
    free(inputs);
    return parsed == OPTIONS_BAD ? 2 : t.errors ? 1 : 0;
}
