/*
 * check_book.c -- check that the woven HTML book is whole and works offline.
 *
 * Build: gcc -std=c11 -Wall -Wextra -Werror -O2 -o build/check_book tools/checks/check_book.c
 * Run:   build/check_book build/book.html
 *        build/check_book --code-width 80 build/book.html
 *
 * It reads the page with a small tag scanner (not a full HTML parser) and
 * prints one "FILE: error: ..." line per problem, exiting with 1, when:
 *   - an internal link href="#x" has no element with id="x";
 *   - an image (<img src>, <source src>, <image href> or xlink:href in an
 *     inline SVG) is neither a data: URI nor an existing file relative to
 *     the HTML file's directory;
 *   - the page has no <math> element (formulas must be MathML);
 *   - a <script src> or <link href> points at the network (http:, https:,
 *     or //host), so the page would not work offline.
 * With --code-width N it checks one more thing, alone (`make check-code-width`):
 *   - a line of program code (in a <pre class="chunk-code"> that
 *     tools/book/weave.lua writes) is wider than N columns: the message names the
 *     chunk (data-chunk, or data-file for a file) and its chapter
 *     (data-chapter), the line's number
 *     in the box and the line itself, e.g.
 *       book.html: error: chunk <<vector operations>> (Chapter 1), line 3:
 *       91 columns, more than 80: static inline vec3 vec3_add(...
 *     Columns are characters (UTF-8 code points); a tab goes to the next
 *     multiple of 8.  A box must fit the text column without scrolling.
 * On success it prints
 *   check_book: N internal links, M images, K math elements: ok
 * or, with --code-width,
 *   check_book: N lines of code in M chunks, none wider than 80 columns: ok
 * Attribute values may be double-quoted, single-quoted or unquoted.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A string found in the page, and where (byte offset) for messages. */
typedef struct {
    char *text;
    size_t offset;
} book_item;

typedef struct {
    book_item *items;
    size_t count;
    size_t capacity;
} ItemList;

/* Everything the scan collects; checked once the whole page is read. */
typedef struct {
    const char *path;      /* the HTML file, for messages */
    char *directory;       /* its directory, images are relative to it */
    const char *html;      /* the whole page */
    size_t length;
    ItemList ids;
    ItemList links;        /* targets of href="#..." without the '#' */
    ItemList images;
    size_t math_count;
    size_t error_count;
    /* --code-width: 0 when off */
    size_t code_width;
    char *chunk_name;      /* data-chunk (or data-file) of the latest <div> */
    int chunk_is_file;     /* it was data-file */
    char *chunk_chapter;   /* its data-chapter */
    size_t code_lines;
    size_t code_boxes;
} book_page;

/* ---------------------------------------------------------------- */
/* Memory and strings                                                */
/* ---------------------------------------------------------------- */

static void *allocate(size_t size)
{
    void *memory = malloc(size ? size : 1);
    if (!memory) {
        fputs("check_book: out of memory\n", stderr);
        exit(2);
    }
    return memory;
}

static char *copy_string(const char *text, size_t length)
{
    char *copy = allocate(length + 1);
    memcpy(copy, text, length);
    copy[length] = '\0';
    return copy;
}

static void list_add(ItemList *list, char *text, size_t offset)
{
    if (list->count == list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 64;
        book_item *items = realloc(list->items, capacity * sizeof *items);
        if (!items) {
            fputs("check_book: out of memory\n", stderr);
            exit(2);
        }
        list->items = items;
        list->capacity = capacity;
    }
    list->items[list->count].text = text;
    list->items[list->count].offset = offset;
    list->count++;
}

static void list_free(ItemList *list)
{
    for (size_t i = 0; i < list->count; i++)
        free(list->items[i].text);
    free(list->items);
}

static int starts_with_ignoring_case(const char *text, const char *prefix)
{
    for (; *prefix; text++, prefix++)
        if (tolower((unsigned char)*text) != tolower((unsigned char)*prefix))
            return 0;
    return 1;
}

/* ---------------------------------------------------------------- */
/* Decoding attribute values                                         */
/* ---------------------------------------------------------------- */

/* Writes code point as UTF-8 into out; returns the number of bytes. */
static size_t put_utf8(unsigned long code, char *out)
{
    if (code < 0x80) {
        out[0] = (char)code;
        return 1;
    }
    if (code < 0x800) {
        out[0] = (char)(0xC0 | (code >> 6));
        out[1] = (char)(0x80 | (code & 0x3F));
        return 2;
    }
    if (code < 0x10000) {
        out[0] = (char)(0xE0 | (code >> 12));
        out[1] = (char)(0x80 | ((code >> 6) & 0x3F));
        out[2] = (char)(0x80 | (code & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | ((code >> 18) & 0x07));
    out[1] = (char)(0x80 | ((code >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((code >> 6) & 0x3F));
    out[3] = (char)(0x80 | (code & 0x3F));
    return 4;
}

/* Decodes one "&...;" at text; returns bytes consumed, 0 if not one. */
static size_t decode_entity(const char *text, size_t length, char *out, size_t *written)
{
    static const struct { const char *name; char value; } named[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''},
    };
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++) {
        size_t name_length = strlen(named[i].name);
        if (name_length <= length && memcmp(text, named[i].name, name_length) == 0) {
            out[0] = named[i].value;
            *written = 1;
            return name_length;
        }
    }
    if (length < 4 || text[1] != '#')
        return 0;
    int hex = text[2] == 'x' || text[2] == 'X';
    size_t i = hex ? 3 : 2;
    unsigned long code = 0;
    size_t digits = 0;
    for (; i < length && digits < 8; i++, digits++) {
        int c = (unsigned char)text[i];
        if (hex ? !isxdigit(c) : !isdigit(c))
            break;
        code = code * (hex ? 16 : 10) + (unsigned long)(isdigit(c) ? c - '0' : tolower(c) - 'a' + 10);
    }
    if (digits == 0 || i >= length || text[i] != ';' || code == 0 || code > 0x10FFFF)
        return 0;
    *written = put_utf8(code, out);
    return i + 1;
}

/* An attribute value as the browser sees it: character references decoded. */
static char *decode_attribute(const char *text, size_t length)
{
    char *out = allocate(length + 1);  /* decoding never makes it longer */
    size_t used = 0;
    for (size_t i = 0; i < length;) {
        size_t written = 0;
        size_t consumed = text[i] == '&' ? decode_entity(text + i, length - i, out + used, &written) : 0;
        if (consumed) {
            used += written;
            i += consumed;
        } else {
            out[used++] = text[i++];
        }
    }
    out[used] = '\0';
    return out;
}

static int hex_value(int c)
{
    return isdigit(c) ? c - '0' : tolower(c) - 'a' + 10;
}

/* "my%20figure.png" -> "my figure.png", in place. */
static void percent_decode(char *text)
{
    char *out = text;
    for (char *in = text; *in; out++) {
        if (in[0] == '%' && isxdigit((unsigned char)in[1]) && isxdigit((unsigned char)in[2])) {
            *out = (char)(hex_value((unsigned char)in[1]) * 16 + hex_value((unsigned char)in[2]));
            in += 3;
        } else {
            *out = *in++;
        }
    }
    *out = '\0';
}

/* ---------------------------------------------------------------- */
/* Reporting                                                         */
/* ---------------------------------------------------------------- */

static long line_of(const book_page *book, size_t offset)
{
    long line = 1;
    for (size_t i = 0; i < offset && i < book->length; i++)
        if (book->html[i] == '\n')
            line++;
    return line;
}

/* One "FILE: error: line N: ..." line; format and arguments as printf. */
static void report(book_page *book, size_t offset, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    fprintf(stderr, "%s: error: line %ld: ", book->path, line_of(book, offset));
    vfprintf(stderr, format, arguments);
    fputc('\n', stderr);
    va_end(arguments);
    book->error_count++;
}

/* ---------------------------------------------------------------- */
/* What each attribute means                                         */
/* ---------------------------------------------------------------- */

static int is_network_url(const char *url)
{
    return starts_with_ignoring_case(url, "http://") || starts_with_ignoring_case(url, "https://")
        || strncmp(url, "//", 2) == 0;  /* protocol-relative: also the network */
}

/* Which attribute of which tag names an image the page shows. */
static int is_image_source(const char *tag, const char *attribute)
{
    if (strcmp(attribute, "src") == 0)
        return strcmp(tag, "img") == 0 || strcmp(tag, "source") == 0;
    if (strcmp(attribute, "href") == 0 || strcmp(attribute, "xlink:href") == 0)
        return strcmp(tag, "image") == 0;
    return 0;
}

static int is_link_attribute(const char *attribute)
{
    return strcmp(attribute, "href") == 0 || strcmp(attribute, "xlink:href") == 0;
}

/* Takes ownership of value. */
static void note_attribute(book_page *book, const char *tag, const char *attribute, char *value, size_t offset)
{
    /* <a name="x"> is the old way to make a link target. */
    if (strcmp(attribute, "id") == 0 || (strcmp(tag, "a") == 0 && strcmp(attribute, "name") == 0)) {
        list_add(&book->ids, value, offset);
        return;
    }
    int loads_code = (strcmp(tag, "script") == 0 && (strcmp(attribute, "src") == 0 || is_link_attribute(attribute)))
        || (strcmp(tag, "link") == 0 && strcmp(attribute, "href") == 0);
    if (loads_code && is_network_url(value))
        report(book, offset, "<%s> loads \"%s\" from the network; the page must work offline", tag, value);

    if (is_image_source(tag, attribute)) {
        list_add(&book->images, value, offset);
        return;
    }
    if (is_link_attribute(attribute) && value[0] == '#' && value[1] != '\0') {
        memmove(value, value + 1, strlen(value));  /* drop the '#' */
        list_add(&book->links, value, offset);
        return;
    }
    free(value);
}

/* ---------------------------------------------------------------- */
/* The tag scanner                                                   */
/* ---------------------------------------------------------------- */

static int is_name_char(int c)
{
    return c != '\0' && !isspace(c) && c != '=' && c != '>' && c != '/' && c != '"' && c != '\'';
}

static size_t skip_spaces(const book_page *book, size_t pos)
{
    while (pos < book->length && isspace((unsigned char)book->html[pos]))
        pos++;
    return pos;
}

/* Position just after the next occurrence of marker, or the end. */
static size_t skip_past(const book_page *book, size_t pos, const char *marker)
{
    const char *found = strstr(book->html + pos, marker);
    return found ? (size_t)(found - book->html) + strlen(marker) : book->length;
}

/* Contents of <script> and <style> are text, not tags: jump to the end tag. */
static size_t skip_raw_text(const book_page *book, size_t pos, const char *tag)
{
    for (; pos < book->length; pos++)
        if (book->html[pos] == '<' && book->html[pos + 1] == '/'
            && starts_with_ignoring_case(book->html + pos + 2, tag))
            return pos;
    return book->length;
}

/* Reads name into buffer (lower case, cut to size); returns the new position. */
static size_t read_name(const book_page *book, size_t pos, char *name, size_t size)
{
    size_t used = 0;
    for (; pos < book->length && is_name_char((unsigned char)book->html[pos]); pos++)
        if (used + 1 < size)
            name[used++] = (char)tolower((unsigned char)book->html[pos]);
    name[used] = '\0';
    return pos;
}

/* Reads a quoted or unquoted value; returns it decoded via *value. */
static size_t read_value(const book_page *book, size_t pos, char **value)
{
    const char *html = book->html;
    size_t start, end;
    if (html[pos] == '"' || html[pos] == '\'') {
        char quote = html[pos];
        start = pos + 1;
        const char *close = strchr(html + start, quote);
        end = close ? (size_t)(close - html) : book->length;
        pos = end < book->length ? end + 1 : end;
    } else {
        start = pos;
        while (pos < book->length && !isspace((unsigned char)html[pos]) && html[pos] != '>')
            pos++;
        end = pos;
    }
    *value = decode_attribute(html + start, end - start);
    return pos;
}

/* ---------------------------------------------------------------- */
/* The width of code lines (--code-width)                            */
/* ---------------------------------------------------------------- */

/* Columns of one line: UTF-8 code points, a tab to the next multiple of 8. */
static size_t columns_of(const char *line, size_t length)
{
    size_t columns = 0;
    for (size_t i = 0; i < length; i++) {
        unsigned char c = (unsigned char)line[i];
        if (c == '\t')
            columns = (columns / 8 + 1) * 8;
        else if ((c & 0xC0) != 0x80)
            columns++;
    }
    return columns;
}

/* The text of html[start, end) with its tags removed and entities decoded. */
static char *text_without_tags(const book_page *book, size_t start, size_t end)
{
    char *kept = allocate(end - start + 1);
    size_t used = 0;
    int in_tag = 0;
    for (size_t i = start; i < end; i++) {
        char c = book->html[i];
        if (c == '<')
            in_tag = 1;
        else if (c == '>' && in_tag)
            in_tag = 0;
        else if (!in_tag)
            kept[used++] = c;
    }
    char *text = decode_attribute(kept, used);
    free(kept);
    return text;
}

/* Names the chunk, not the page's line: the chunk is what the author edits. */
static void report_wide_line(book_page *book, size_t number, const char *line, size_t length,
                             size_t columns)
{
    fprintf(stderr, "%s: error: %s%s%s (%s), line %zu: %zu columns, more than %zu: %.*s\n",
            book->path, book->chunk_is_file ? "file " : "chunk <<",
            book->chunk_name ? book->chunk_name : "?", book->chunk_is_file ? "" : ">>",
            book->chunk_chapter ? book->chunk_chapter : "?", number, columns,
            book->code_width, (int)length, line);
    book->error_count++;
}

/* Checks the code box whose content starts at pos; returns its end. */
static size_t check_code_box(book_page *book, size_t pos)
{
    const char *close = strstr(book->html + pos, "</pre>");
    size_t end = close ? (size_t)(close - book->html) : book->length;
    char *text = text_without_tags(book, pos, end);
    size_t number = 0;
    for (const char *line = text; line;) {
        const char *newline = strchr(line, '\n');
        size_t length = newline ? (size_t)(newline - line) : strlen(line);
        size_t columns = columns_of(line, length);
        number++;
        if (columns > book->code_width)
            report_wide_line(book, number, line, length, columns);
        line = newline ? newline + 1 : NULL;
    }
    book->code_lines += number;
    book->code_boxes++;
    free(text);
    return end;
}

/* Keeps the chunk's name (or file's path) and chapter from
   <div data-chunk=... (or data-file=...) data-chapter=...>.
   Takes ownership of value; returns 1 if it kept it. */
static int note_chunk_attribute(book_page *book, const char *tag, const char *attribute, char *value)
{
    char **slot = NULL;
    if (strcmp(tag, "div") != 0)
        return 0;
    if (strcmp(attribute, "data-chunk") == 0 || strcmp(attribute, "data-file") == 0) {
        slot = &book->chunk_name;
        book->chunk_is_file = strcmp(attribute, "data-file") == 0;
    } else if (strcmp(attribute, "data-chapter") == 0) {
        slot = &book->chunk_chapter;
    }
    if (!slot)
        return 0;
    free(*slot);
    *slot = value;
    return 1;
}

/* Does this class attribute's value, a list of names, hold wanted? */
static int has_class(const char *value, const char *wanted)
{
    size_t length = strlen(wanted);
    for (const char *found = strstr(value, wanted); found; found = strstr(found + 1, wanted)) {
        int starts = found == value || isspace((unsigned char)found[-1]);
        int ends = found[length] == '\0' || isspace((unsigned char)found[length]);
        if (starts && ends)
            return 1;
    }
    return 0;
}

/* Scans the tag starting at "<name"; returns the position after its '>'. */
static size_t scan_tag(book_page *book, size_t pos)
{
    char tag[64], attribute[64];
    size_t tag_offset = pos;
    int is_code_box = 0;
    pos = read_name(book, pos + 1, tag, sizeof tag);
    if (strcmp(tag, "math") == 0)
        book->math_count++;
    for (;;) {
        pos = skip_spaces(book, pos);
        if (pos >= book->length)
            return pos;
        if (book->html[pos] == '>')
            break;
        if (!is_name_char((unsigned char)book->html[pos])) {
            pos++;  /* a stray '/', quote or '=': not part of a name */
            continue;
        }
        pos = read_name(book, pos, attribute, sizeof attribute);
        pos = skip_spaces(book, pos);
        if (pos < book->length && book->html[pos] == '=') {
            char *value;
            pos = read_value(book, skip_spaces(book, pos + 1), &value);
            if (strcmp(tag, "pre") == 0 && strcmp(attribute, "class") == 0)
                is_code_box = has_class(value, "chunk-code");
            if (!note_chunk_attribute(book, tag, attribute, value))
                note_attribute(book, tag, attribute, value, tag_offset);
        }
    }
    pos++;  /* past '>' */
    /* Scene files are data, a statement a line: the rule is for C code. */
    static const char scene_code[] = "<code class=\"language-scene\"";
    bool is_scene = strncmp(book->html + pos, scene_code, sizeof scene_code - 1) == 0;
    if (is_code_box && book->code_width > 0 && !is_scene)
        pos = check_code_box(book, pos);
    if (strcmp(tag, "script") == 0 || strcmp(tag, "style") == 0)
        pos = skip_raw_text(book, pos, tag);
    return pos;
}

static void scan_page(book_page *book)
{
    const char *html = book->html;
    size_t pos = 0;
    while (pos < book->length) {
        const char *next = strchr(html + pos, '<');
        if (!next)
            break;
        pos = (size_t)(next - html);
        if (strncmp(next, "<!--", 4) == 0)
            pos = skip_past(book, pos + 4, "-->");
        else if (strncmp(next, "<![CDATA[", 9) == 0)
            pos = skip_past(book, pos + 9, "]]>");
        else if (next[1] == '!' || next[1] == '?' || next[1] == '/')
            pos = skip_past(book, pos + 1, ">");
        else if (isalpha((unsigned char)next[1]))
            pos = scan_tag(book, pos);
        else
            pos++;  /* a lone '<' in text */
    }
}

/* ---------------------------------------------------------------- */
/* The checks                                                        */
/* ---------------------------------------------------------------- */

static int compare_items(const void *a, const void *b)
{
    return strcmp(((const book_item *)a)->text, ((const book_item *)b)->text);
}

static int has_id(const book_page *book, const char *id)
{
    book_item key = {(char *)id, 0};
    if (book->ids.count == 0)
        return 0;  /* bsearch must not get a null array */
    return bsearch(&key, book->ids.items, book->ids.count, sizeof key, compare_items) != NULL;
}

static void check_links(book_page *book)
{
    if (book->ids.count > 0)
        qsort(book->ids.items, book->ids.count, sizeof(book_item), compare_items);
    for (size_t i = 0; i < book->links.count; i++) {
        const book_item *link = &book->links.items[i];
        if (has_id(book, link->text))
            continue;
        char *decoded = copy_string(link->text, strlen(link->text));
        percent_decode(decoded);  /* "#caf%C3%A9" may name id="café" */
        if (!has_id(book, decoded))
            report(book, link->offset, "link to \"#%s\" but no element has id=\"%s\"", link->text, link->text);
        free(decoded);
    }
}

static int file_exists(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return 0;
    fclose(file);
    return 1;
}

/* The file an image URL names: query and fragment dropped, %xx decoded,
   relative to the page's directory. */
static char *image_file_path(const book_page *book, const char *url)
{
    if (starts_with_ignoring_case(url, "file://"))
        url += strlen("file://");
    size_t length = strcspn(url, "?#");
    char *relative = copy_string(url, length);
    percent_decode(relative);
    if (relative[0] == '/' || book->directory[0] == '\0')
        return relative;
    size_t size = strlen(book->directory) + 1 + strlen(relative) + 1;
    char *full = allocate(size);
    snprintf(full, size, "%s/%s", book->directory, relative);
    free(relative);
    return full;
}

static void check_images(book_page *book)
{
    for (size_t i = 0; i < book->images.count; i++) {
        const book_item *image = &book->images.items[i];
        if (starts_with_ignoring_case(image->text, "data:"))
            continue;
        if (is_network_url(image->text)) {
            report(book, image->offset, "image \"%s\" is on the network; the page must work offline", image->text);
            continue;
        }
        char *path = image_file_path(book, image->text);
        if (image->text[0] == '\0' || !file_exists(path))
            report(book, image->offset, "image \"%s\" is not embedded and there is no such file", image->text);
        free(path);
    }
}

static void check_math(book_page *book)
{
    if (book->math_count == 0) {
        fprintf(stderr, "%s: error: no <math> element: formulas must be MathML (pandoc --mathml)\n", book->path);
        book->error_count++;
    }
}

/* ---------------------------------------------------------------- */
/* Reading the file and main                                         */
/* ---------------------------------------------------------------- */

/* The whole file as a NUL-terminated string, or NULL. */
static char *read_file(const char *path, size_t *length)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    size_t used = 0, capacity = 1 << 16;
    char *text = allocate(capacity);
    size_t got;
    while ((got = fread(text + used, 1, capacity - used - 1, file)) > 0) {
        used += got;
        if (capacity - used - 1 == 0) {
            char *bigger = realloc(text, capacity * 2);
            if (!bigger) {
                fputs("check_book: out of memory\n", stderr);
                exit(2);
            }
            text = bigger;
            capacity *= 2;
        }
    }
    int failed = ferror(file);
    fclose(file);
    if (failed) {
        free(text);
        return NULL;
    }
    text[used] = '\0';
    *length = used;
    return text;
}

/* "build/book.html" -> "build"; "book.html" -> "" (the current directory). */
static char *directory_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return copy_string("", 0);
    if (slash == path)
        return copy_string("/", 1);
    return copy_string(path, (size_t)(slash - path));
}

/* Reads "[--code-width N] FILE.html" into book; returns 0 if malformed. */
static int parse_arguments(int argc, char **argv, book_page *book)
{
    int next = 1;
    if (argc == 4 && strcmp(argv[1], "--code-width") == 0) {
        char *end;
        long width = strtol(argv[2], &end, 10);
        if (*argv[2] == '\0' || *end != '\0' || width < 1)
            return 0;
        book->code_width = (size_t)width;
        next = 3;
    }
    if (argc != next + 1)
        return 0;
    book->path = argv[next];
    return 1;
}

/* The checks of a plain run, or only the code width with --code-width. */
static void check_and_summarise(book_page *book)
{
    if (book->code_width > 0) {
        if (book->error_count == 0)
            printf("check_book: %zu lines of code in %zu chunks, none wider than %zu columns: ok\n",
                   book->code_lines, book->code_boxes, book->code_width);
        else
            fprintf(stderr, "check_book: %zu code lines are wider than %zu columns; shorten them "
                    "in the chunks named above (chapters/NN-*.md)\n",
                    book->error_count, book->code_width);
        return;
    }
    check_links(book);
    check_images(book);
    check_math(book);
    if (book->error_count == 0)
        printf("check_book: %zu internal links, %zu images, %zu math elements: ok\n",
               book->links.count, book->images.count, book->math_count);
}

int main(int argc, char **argv)
{
    book_page book = {0};
    if (!parse_arguments(argc, argv, &book)) {
        fprintf(stderr, "usage: %s [--code-width COLUMNS] FILE.html\n", argv[0]);
        return 2;
    }
    size_t length = 0;
    char *html = read_file(book.path, &length);
    if (!html) {
        fprintf(stderr, "%s: error: cannot read the file\n", book.path);
        return 1;
    }
    if (strlen(html) != length)
        fprintf(stderr, "%s: warning: NUL bytes in the file; only the part before the first is checked\n", book.path);
    book.html = html;
    book.length = strlen(html);
    book.directory = directory_of(book.path);

    scan_page(&book);
    check_and_summarise(&book);
    int status = book.error_count == 0 ? 0 : 1;
    list_free(&book.ids);
    list_free(&book.links);
    list_free(&book.images);
    free(book.chunk_name);
    free(book.chunk_chapter);
    free(book.directory);
    free(html);
    return status;
}
