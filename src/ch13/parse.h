/* parse.h: reading text files line by line, with located errors
 * (chapter 1).
 *
 * A parser walks a text one line at a time, cutting each line into tokens
 * separated by blanks; '#' outside a token ends the line. Every function
 * that reads returns false on bad input and fills the parse_error with the
 * file, line, column and message; nothing here prints. */
#ifndef PARSE_H
#define PARSE_H

#include <stdbool.h>
#include <stddef.h>
#include "vec.h"

#define PARSE_MAX_NAME 4096 /* bytes of a path and its NUL: PATH_MAX on Linux */

typedef enum {
    PARSE_BAD_INPUT,   /* the text is wrong at line:col */
    PARSE_CANNOT_READ, /* line 0: the file cannot be read, or is too large */
    PARSE_OVER_BUDGET, /* valid input that asks for more than is allowed */
    PARSE_NO_MEMORY,   /* the machine ran out of memory, not the input */
} parse_error_kind;

typedef struct {
    char file[PARSE_MAX_NAME]; /* ends in "..." if the name was longer */
    int line, col; /* 1-based; line 0: the problem is the file as a whole */
    parse_error_kind kind;
    char message[PARSE_MAX_NAME + 256]; /* room to name a file in full */
} parse_error;

typedef struct {
    const char *name;        /* file name, for errors */
    const char *line, *end;  /* current line [line, end) */
    const char *next;        /* where the next token search starts */
    int line_number;
    const char *token; /* last token read: [token, token + token_length) */
    int token_length;
    parse_error *err;
} parser;

/* <<parser declarations>> ch01 */
/* Fills p->err at the column of at, formatted like printf; returns false. */
bool parse_fail_at(parser *p, const char *at, const char *format, ...);

/* The same, for an error of another kind than PARSE_BAD_INPUT. */
bool parse_fail_with(parser *p, parse_error_kind kind, const char *at,
                     const char *format, ...);

/* "EXPECTATION, found 'TOKEN'", located at the token just read; false. */
bool parse_expected(parser *p, const char *format, ...);

/* An array of count items that could not grow, located at at: "more than
 * MAX PLURAL" once count has reached max, else out of memory; false. */
bool parse_no_room(parser *p, const char *at, int count, int max,
                   const char *plural);

/* An error found once the parse is over, about line `line` of the file
 * called name (0: the file as a whole), at its first column; false. */
bool parse_fail_on_line(parse_error *err, const char *name, int line,
                        parse_error_kind kind, const char *format, ...);

/* Copies name into to[size], ending it in "..." when it does not fit. */
void parse_copy_name(char *to, size_t size, const char *name);

bool parse_is_blank(char c);

/* Moves to the next token of the line; false (and an empty token) at its
 * end or at a comment. */
bool parse_next_token(parser *p);

/* Is the token just read exactly word? */
bool parse_token_is(const parser *p, const char *word);

/* The next token as a finite number, or a colour (three numbers from 0 to
 * PARSE_MAX_INTENSITY). */
bool parse_number(parser *p, const char *what, double *out);
bool parse_color(parser *p, const char *what, vec3 *out);

/* Light adds up and is multiplied; keeping every colour and intensity at
 * most 1e6 keeps any sum of products far from overflowing to infinity. */
#define PARSE_MAX_INTENSITY 1e6

/* The next token as a number from lo to hi, a number from lo up to but
 * not including hi, or a whole number from lo to hi; else "expected WHAT
 * from LO to HI". */
bool parse_number_in(parser *p, const char *what, double lo, double hi,
                     double *out);
bool parse_number_below(parser *p, const char *what, double lo, double hi,
                        double *out);
bool parse_int_in(parser *p, const char *what, long lo, long hi, long *out);

typedef bool (*line_parser)(parser *p, void *target);

/* Calls parse_line on every line of text[0..length), stopping at the first
 * error; name is the file name for errors. */
bool parse_lines(const char *text, size_t length, const char *name,
                 parse_error *err, line_parser parse_line, void *target);

/* The whole regular file at path, at most max_bytes, in a malloc'ed *text
 * that is NUL-terminated (only up to its first NUL byte, if it holds one:
 * it is then no text, and parse_lines says where); false with err filled
 * (line 0) when it cannot be read, is not a regular file, or is too
 * large. */
bool parse_read_file(const char *path, long max_bytes, char **text,
                     size_t *length, parse_error *err);
/* <<parser declarations>> += ch02 */

/* A point: three numbers within +-PARSE_MAX_COORDINATE. */
bool parse_point(parser *p, const char *what, vec3 *out);

#define PARSE_MAX_COORDINATE 1e50 /* fourth powers of coordinates stay finite */
/* <<parser declarations>> += ch03 */

/* A coefficient rho in [0, 1], as the sheet requires of rho_a, rho_d,
 * rho_s; a number greater than 0; a direction: three numbers, not all
 * zero, returned as a unit vector. */
bool parse_coefficient(parser *p, const char *what, double *out);
bool parse_positive(parser *p, const char *what, double *out);
bool parse_direction(parser *p, const char *what, vec3 *out);

#endif
