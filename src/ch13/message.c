/* message.c: errors on standard error, escaped (chapter 1). */
#include "message.h"

#include <stdbool.h>
#include <stdio.h>

/* <<printing errors>> ch01 */
/* The length of the UTF-8 sequence at s if it encodes a printable
 * character beyond ASCII (U+00A0 and up), else 0. */
static int printable_utf8(const unsigned char *s)
{
    static const unsigned long least[] = {0, 0, 0xA0, 0x800, 0x10000};
    int n = s[0] >= 0xF0 ? 4 : s[0] >= 0xE0 ? 3 : s[0] >= 0xC2 ? 2 : 0;
    if (n == 0 || s[0] > 0xF4)
        return 0;
    unsigned long c = s[0] & (0x7Fu >> n);
    for (int k = 1; k < n; k++) {
        if ((s[k] & 0xC0) != 0x80) /* also stops at the NUL */
            return 0;
        c = c << 6 | (s[k] & 0x3Fu);
    }
    bool surrogate = c >= 0xD800 && c <= 0xDFFF;
    return c >= least[n] && c <= 0x10FFFF && !surrogate ? n : 0;
}

void message_print_escaped(const char *text)
{
    for (const unsigned char *c = (const unsigned char *)text; *c != '\0';) {
        int n = *c >= 0x20 && *c < 0x7F ? 1 : printable_utf8(c);
        if (n == 0)
            fprintf(stderr, "\\x%02x", *c++);
        else
            fwrite(c, 1, (size_t)n, stderr), c += n;
    }
}

void message_print_error(const char *name, int line, int col,
                         const char *message)
{
    message_print_escaped(name);
    if (line > 0)
        fprintf(stderr, ":%d:%d", line, col);
    fputs(": error: ", stderr);
    message_print_escaped(message);
    fputc('\n', stderr);
}

void message_print_warning(const char *name, const char *message)
{
    message_print_escaped(name);
    fputs(": warning: ", stderr);
    message_print_escaped(message);
    fputc('\n', stderr);
}
