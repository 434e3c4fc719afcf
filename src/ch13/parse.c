/* parse.c: lines, tokens, numbers and located errors (chapter 1). */
#include "parse.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "memory.h"

static int column_of(const parser *p, const char *at)
{
    return (int)(at - p->line) + 1;
}

/* <<parser errors>> ch01 */
void parse_copy_name(char *to, size_t size, const char *name)
{
    if (snprintf(to, size, "%s", name) >= (int)size && size > 3)
        memcpy(to + size - 4, "...", 4); /* never a wrong, shortened name */
}

static void fail(parser *p, parse_error_kind kind, const char *at,
                 const char *format, va_list args)
{
    parse_error *err = p->err;
    parse_copy_name(err->file, sizeof err->file, p->name);
    err->line = p->line_number;
    err->col = column_of(p, at);
    err->kind = kind;
    vsnprintf(err->message, sizeof err->message, format, args);
}

bool parse_fail_at(parser *p, const char *at, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fail(p, PARSE_BAD_INPUT, at, format, args);
    va_end(args);
    return false;
}

bool parse_fail_with(parser *p, parse_error_kind kind, const char *at,
                     const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fail(p, kind, at, format, args);
    va_end(args);
    return false;
}

bool parse_fail_on_line(parse_error *err, const char *name, int line,
                        parse_error_kind kind, const char *format, ...)
{
    parser p = {.name = name, .line_number = line, .err = err};
    va_list args;
    va_start(args, format);
    fail(&p, kind, p.line, format, args); /* p.line: column 1 */
    va_end(args);
    if (line == 0)
        err->col = 0;
    return false;
}

bool parse_expected(parser *p, const char *format, ...)
{
    char what[160];
    va_list args;
    va_start(args, format);
    vsnprintf(what, sizeof what, format, args);
    va_end(args);
    if (p->token_length == 0)
        return parse_fail_at(p, p->token, "%s, found end of line", what);
    int shown = p->token_length > 40 ? 40 : p->token_length;
    return parse_fail_at(p, p->token, "%s, found '%.*s%s'", what, shown,
                         p->token, shown < p->token_length ? "..." : "");
}

bool parse_no_room(parser *p, const char *at, int count, int max,
                   const char *plural)
{
    if (count >= max)
        return parse_fail_at(p, at, "more than %d %s", max, plural);
    return parse_fail_with(p, PARSE_NO_MEMORY, at,
                           "out of memory for more than %d %s", count,
                           plural);
}

/* <<tokens>> ch01 */
bool parse_is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

bool parse_next_token(parser *p)
{
    const char *c = p->next;
    while (c < p->end && parse_is_blank(*c))
        c++;
    p->token = c;
    p->token_length = 0;
    if (c == p->end || *c == '#')
        return false;
    while (c < p->end && !parse_is_blank(*c))
        c++;
    p->token_length = (int)(c - p->token);
    p->next = c;
    return true;
}

bool parse_token_is(const parser *p, const char *word)
{
    return (size_t)p->token_length == strlen(word) &&
           memcmp(p->token, word, (size_t)p->token_length) == 0;
}

/* <<numbers and colours>> ch01 */
/* Is the whole token a number for strtod? Its value in *value. */
static bool token_to_double(const parser *p, double *value, bool *no_memory)
{
    char small[64];
    size_t n = (size_t)p->token_length;
    char *text = n < sizeof small ? small : memory_alloc(n + 1, 1);
    if ((*no_memory = text == NULL))
        return false;
    memcpy(text, p->token, n);
    text[n] = '\0';
    char *stop;
    *value = strtod(text, &stop);
    bool whole = stop != text && *stop == '\0';
    if (text != small)
        free(text);
    return whole;
}

bool parse_number(parser *p, const char *what, double *out)
{
    double value;
    bool no_memory;
    if (!parse_next_token(p))
        return parse_expected(p, "expected %s", what);
    if (!token_to_double(p, &value, &no_memory))
        return no_memory ? parse_fail_with(p, PARSE_NO_MEMORY, p->token,
                                           "out of memory for a number")
                         : parse_expected(p, "expected %s", what);
    if (!isfinite(value))
        return parse_expected(p, "expected %s (a finite number)", what);
    *out = value;
    return true;
}

bool parse_color(parser *p, const char *what, vec3 *out)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        if (!parse_number(p, what, &c[k]))
            return false;
        if (!(c[k] >= 0 && c[k] <= PARSE_MAX_INTENSITY))
            return parse_expected(p, "expected %s from 0 to 1e6", what);
    }
    *out = (vec3){c[0], c[1], c[2]};
    return true;
}

/* x as %g writes it, less the exponent's '+' and leading zeros: 1e50. */
static const char *bound_text(double x, char text[32])
{
    snprintf(text, 32, "%g", x);
    char *e = strchr(text, 'e');
    if (e != NULL) {
        char *digits = e + 1 + (e[1] == '-'), *from = digits;
        while (*from == '+' || *from == '0')
            from++;
        memmove(digits, from, strlen(from) + 1);
    }
    return text;
}

static bool number_in(parser *p, const char *what, double lo, double hi,
                      bool open_hi, double *out)
{
    double x;
    char a[32], b[32];
    if (!parse_number(p, what, &x))
        return false;
    if (!(x >= lo && (open_hi ? x < hi : x <= hi)))
        return parse_expected(p, "expected %s from %s to %s%s", what,
                              bound_text(lo, a), bound_text(hi, b),
                              open_hi ? " (not included)" : "");
    *out = x;
    return true;
}

bool parse_number_in(parser *p, const char *what, double lo, double hi,
                     double *out)
{
    return number_in(p, what, lo, hi, false, out);
}

bool parse_number_below(parser *p, const char *what, double lo, double hi,
                        double *out)
{
    return number_in(p, what, lo, hi, true, out);
}

bool parse_int_in(parser *p, const char *what, long lo, long hi, long *out)
{
    double value;
    if (!parse_number(p, what, &value))
        return false;
    if (value != floor(value))
        return parse_expected(p, "expected %s (a whole number)", what);
    /* a whole number too large for any long is out of range all the same */
    if (value < (double)lo || value > (double)hi)
        return parse_expected(p, "expected %s from %ld to %ld", what, lo, hi);
    *out = (long)value;
    return true;
}
/* <<numbers and colours>> += ch02 */

bool parse_point(parser *p, const char *what, vec3 *out)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        if (!parse_number(p, what, &c[k]))
            return false;
        if (fabs(c[k]) > PARSE_MAX_COORDINATE)
            return parse_expected(p, "expected %s between -1e50 and 1e50",
                                  what);
    }
    *out = (vec3){c[0], c[1], c[2]};
    return true;
}
/* <<numbers and colours>> += ch03 */

bool parse_coefficient(parser *p, const char *what, double *out)
{
    if (!parse_number(p, what, out))
        return false;
    if (!(*out >= 0 && *out <= 1))
        return parse_expected(p, "expected %s from 0 to 1", what);
    return true;
}

bool parse_positive(parser *p, const char *what, double *out)
{
    if (!parse_number(p, what, out))
        return false;
    return *out > 0 || parse_expected(p, "expected %s greater than 0", what);
}

bool parse_direction(parser *p, const char *what, vec3 *out)
{
    const char *first = p->next;
    if (!parse_point(p, what, out))
        return false;
    while (parse_is_blank(*first))
        first++;
    if (!vec3_is_direction(*out))
        return parse_fail_at(p, first, "expected %s of non-zero length",
                             what);
    *out = vec3_normalize_scaled(*out); /* however short or long */
    return true;
}

/* <<parse every line>> ch01 */
bool parse_lines(const char *text, size_t length, const char *name,
                 parse_error *err, line_parser parse_line, void *target)
{
    parser p = {.name = name, .err = err};
    const char *end = text + length;
    const char *line = text;
    if (length >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        line += 3; /* a UTF-8 byte order mark says nothing: skip it */
    while (line < end) {
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        if (eol == NULL)
            eol = end;
        p.line = p.next = line;
        p.end = eol;
        p.line_number++;
        const char *nul = memchr(line, '\0', (size_t)(eol - line));
        if (nul != NULL)
            return parse_fail_at(&p, nul, "unexpected NUL byte: "
                                          "this is not a text file");
        if (p.line_number > 1 && eol - line >= 3 &&
            memcmp(line, "\xEF\xBB\xBF", 3) == 0)
            return parse_fail_at(&p, line, "a byte order mark (EF BB BF) "
                                           "after the start of the file");
        if (!parse_line(&p, target))
            return false;
        line = eol < end ? eol + 1 : end;
    }
    return true;
}

/* <<reading a file>> ch01 */
static bool file_error(parse_error *err, parse_error_kind kind,
                       const char *path, const char *format, ...)
{
    parse_copy_name(err->file, sizeof err->file, path);
    err->line = err->col = 0;
    err->kind = kind;
    va_list args;
    va_start(args, format);
    vsnprintf(err->message, sizeof err->message, format, args);
    va_end(args);
    return false;
}

static bool too_large(parse_error *err, const char *path, long max_bytes)
{
    return file_error(err, PARSE_CANNOT_READ, path,
                      "larger than such a file may be: more than %ld bytes",
                      max_bytes);
}

/* Room for more of the file: twice as much, but never more than max + 1
 * bytes and a NUL; false, with err filled, when that is not possible. */
static bool grow_buffer(char **text, size_t *capacity, size_t max,
                        const char *path, parse_error *err)
{
    if (*capacity > max)
        return too_large(err, path, (long)max); /* it holds max + 1 bytes */
    size_t wanted = *capacity <= max / 2 ? 2 * *capacity : max + 1;
    char *grown = memory_resize(*text, wanted + 1, 1);
    if (grown == NULL)
        return file_error(err, PARSE_NO_MEMORY, path, "out of memory");
    *text = grown, *capacity = wanted;
    return true;
}

enum { READ_PIECE = 1 << 20 }; /* bytes read, and checked, at a time */

/* Reads fd to its end, or to its first NUL byte, into *text, starting with
 * room for size bytes. */
static bool read_all(int fd, size_t size, size_t max, char **text,
                     size_t *length, const char *path, parse_error *err)
{
    size_t capacity = size < max ? size : max; /* the first read's room */
    if (capacity > READ_PIECE)
        capacity = READ_PIECE; /* a wrong size costs no more than this */
    if ((*text = memory_alloc(capacity + 2, 1)) == NULL)
        return file_error(err, PARSE_NO_MEMORY, path, "out of memory");
    capacity++; /* a byte more than the size, to read the end at once */
    for (*length = 0;;) {
        if (*length == capacity && !grow_buffer(text, &capacity, max, path,
                                                err))
            return false;
        size_t room = capacity - *length;
        char *piece = *text + *length;
        ssize_t n = read(fd, piece, room < READ_PIECE ? room : READ_PIECE);
        if (n == 0)
            break;
        if (n < 0 && errno != EINTR)
            return file_error(err, PARSE_CANNOT_READ, path, "%s",
                              strerror(errno));
        *length += n > 0 ? (size_t)n : 0;
        if (n > 0 && memchr(piece, '\0', (size_t)n) != NULL)
            break; /* not text: the parser reports the NUL where it is */
    }
    (*text)[*length] = '\0'; /* there is room: a byte beyond capacity */
    return true;
}

/* What is wrong with reading the open file as text of at most max_bytes. */
static bool check_file(int fd, long max_bytes, const char *path,
                       parse_error *err, size_t *size)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return file_error(err, PARSE_CANNOT_READ, path, "%s",
                          strerror(errno));
    if (S_ISDIR(st.st_mode))
        return file_error(err, PARSE_CANNOT_READ, path, "%s",
                          strerror(EISDIR));
    if (!S_ISREG(st.st_mode))
        return file_error(err, PARSE_CANNOT_READ, path,
                          "not a regular file (a device, a pipe or a "
                          "socket cannot be read as one)");
    if (st.st_size > max_bytes)
        return too_large(err, path, max_bytes);
    *size = (size_t)st.st_size;
    return true;
}

bool parse_read_file(const char *path, long max_bytes, char **text,
                     size_t *length, parse_error *err)
{
    *text = NULL;
    /* O_NONBLOCK: opening a FIFO must not wait for a writer */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0)
        return file_error(err, PARSE_CANNOT_READ, path, "%s",
                          strerror(errno));
    size_t size = 0;
    bool ok = check_file(fd, max_bytes, path, err, &size) &&
              read_all(fd, size, (size_t)max_bytes, text, length, path, err);
    close(fd);
    if (!ok) {
        free(*text);
        *text = NULL;
    }
    return ok;
}
