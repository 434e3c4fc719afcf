/* parse.c: lines, tokens, numbers and located errors (chapter 01). */
#include "parse.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int column_of(const parser *p, const char *at)
{
    return (int)(at - p->line) + 1;
}

bool parse_fail_at(parser *p, const char *at, const char *format, ...)
{
    parse_error *err = p->err;
    snprintf(err->file, sizeof err->file, "%s", p->name);
    err->line = p->line_number;
    err->col = column_of(p, at);
    va_list args;
    va_start(args, format);
    vsnprintf(err->message, sizeof err->message, format, args);
    va_end(args);
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

bool parse_number(parser *p, const char *what, double *out)
{
    char text[64];
    if (!parse_next_token(p) || p->token_length >= (int)sizeof text)
        return parse_expected(p, "expected %s", what);
    memcpy(text, p->token, (size_t)p->token_length);
    text[p->token_length] = '\0';
    char *stop;
    double value = strtod(text, &stop);
    if (stop == text || *stop != '\0')
        return parse_expected(p, "expected %s", what);
    if (!isfinite(value))
        return parse_expected(p, "expected %s (a finite number)", what);
    *out = value;
    return true;
}

bool parse_int(parser *p, const char *what, long *out)
{
    double value;
    if (!parse_number(p, what, &value))
        return false;
    /* 1e15: every whole number up to it is exact in a double */
    if (value != floor(value) || fabs(value) > 1e15)
        return parse_expected(p, "expected %s (a whole number)", what);
    *out = (long)value;
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
    if (!(vec3_dot(*out, *out) > 0)) /* also too short to square */
        return parse_fail_at(p, first, "expected %s of non-zero length",
                             what);
    *out = vec3_normalize(*out);
    return true;
}

bool parse_lines(const char *text, size_t length, const char *name,
                 parse_error *err, line_parser parse_line, void *target)
{
    parser p = {.name = name, .err = err};
    const char *end = text + length;
    const char *line = text;
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
        if (!parse_line(&p, target))
            return false;
        line = eol < end ? eol + 1 : end;
    }
    return true;
}

static bool file_error(parse_error *err, const char *path, const char *message)
{
    snprintf(err->file, sizeof err->file, "%s", path);
    err->line = err->col = 0;
    snprintf(err->message, sizeof err->message, "%s", message);
    return false;
}

/* Reads from in until the end, growing *text by doubling; false when it
 * would pass max_bytes or memory runs out. */
static bool read_all(FILE *in, long max_bytes, char **text, size_t *length)
{
    size_t capacity = 4096;
    *text = malloc(capacity);
    *length = 0;
    while (*text != NULL) {
        *length += fread(*text + *length, 1, capacity - *length, in);
        if (*length < capacity || *length > (size_t)max_bytes)
            return *length <= (size_t)max_bytes; /* the end, or too much */
        char *grown = realloc(*text, 2 * capacity);
        if (grown == NULL) {
            free(*text);
            *text = NULL; /* says "out of memory" to the caller */
            break;
        }
        *text = grown;
        capacity *= 2;
    }
    return false;
}

bool parse_read_file(const char *path, long max_bytes, char **text,
                     size_t *length, parse_error *err)
{
    FILE *in = fopen(path, "rb");
    if (in == NULL)
        return file_error(err, path, strerror(errno));
    bool ok = read_all(in, max_bytes, text, length);
    if (ferror(in))
        ok = file_error(err, path, strerror(errno));
    else if (!ok)
        file_error(err, path, *text ? "larger than such a file may be"
                                    : "out of memory");
    fclose(in);
    if (ok) {
        (*text)[*length] = '\0'; /* there is room: length < capacity */
    } else {
        free(*text);
        *text = NULL;
    }
    return ok;
}
