/* ch12_load.c: chapter 12's OBJ reader on every core: the same mesh, bit for
 * bit, arrays and capacities, as chapter 4's reader gives, and the same
 * error at the same line and column, whatever the number of parts; on the
 * project's meshes and on made-up text with every kind of statement,
 * negative indices reaching into earlier parts, mistakes on either side of
 * a part's first line, and budgets crossed anywhere. */
#include <check.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "memory.h"
#include "obj.h"
#include "rng.h"
#include "test_util.h"

static const rng_state RNG_START = {0x0B1u};
static rng_state rng;

static void reseed(void) { rng = RNG_START; }

/* A whole number in [0, n). */
static int below(int n) { return (int)(rng_next(&rng) % (uint64_t)n); }

static const mesh_budget NO_BUDGET = {MESH_MAX_TRIANGLES, 1LL << 60};

/* The first n items of two arrays of size bytes each, alike. */
static void expect_same_items(const void *a, const void *b, int n, size_t size,
                              const char *what)
{
    ck_assert_msg((a == NULL) == (b == NULL), "%s: one is NULL", what);
    if (n > 0)
        ck_assert_msg(memcmp(a, b, (size_t)n * size) == 0, "%s differ", what);
}

static void expect_same_mesh(const mesh *a, const mesh *b)
{
    ck_assert_int_eq(a->vertex_count, b->vertex_count);
    ck_assert_int_eq(a->vertex_capacity, b->vertex_capacity);
    ck_assert_int_eq(a->normal_count, b->normal_count);
    ck_assert_int_eq(a->normal_capacity, b->normal_capacity);
    ck_assert_int_eq(a->triangle_count, b->triangle_count);
    ck_assert_int_eq(a->triangle_capacity, b->triangle_capacity);
    ck_assert_int_eq(a->triangle_normals_capacity,
                     b->triangle_normals_capacity);
    ck_assert_int_eq(a->texcoord_count, b->texcoord_count);
    expect_same_items(a->vertices, b->vertices, a->vertex_count, sizeof(vec3),
                      "vertices");
    expect_same_items(a->normals, b->normals, a->normal_count, sizeof(vec3),
                      "normals");
    expect_same_items(a->triangles, b->triangles, a->triangle_count,
                      sizeof(mesh_triangle), "triangles");
    expect_same_items(a->triangle_normals, b->triangle_normals,
                      a->triangle_count, sizeof(mesh_triangle),
                      "triangle normals");
}

/* Chapter 4's reader of text[0..length) within budget: the text written
 * to a file and read by mesh_load_obj_within. */
static bool read_serially(const char *text, size_t length, mesh_budget budget,
                          mesh *m, parse_error *err)
{
    const char *path = write_bytes("mesh.obj", text, length);
    return mesh_load_obj_within(m, path, budget, err);
}

/* The text read in parts, by one to three threads, gives chapter 4's
 * answer: its success, its mesh, and its error (file, line, column, kind
 * and message). */
static void expect_parts_read_as_chapter_4(const char *text, size_t length,
                                           mesh_budget budget, int parts)
{
    mesh serial = {0}, parallel = {0};
    parse_error e1 = {0}, e2 = {0};
    bool ok1 = read_serially(text, length, budget, &serial, &e1);
    bool ok2 =
        mesh_parse_obj_in_parts(&parallel, text, length, tmp_path("mesh.obj"),
                                budget, parts, 1 + parts % 3, &e2);
    ck_assert_msg(ok1 == ok2, "%d parts: %s", parts,
                  ok1 ? e2.message : e1.message);
    expect_same_mesh(&serial, &parallel);
    if (!ok1) {
        ck_assert_str_eq(e1.file, e2.file);
        ck_assert_int_eq(e1.line, e2.line);
        ck_assert_int_eq(e1.col, e2.col);
        ck_assert_int_eq(e1.kind, e2.kind);
        ck_assert_str_eq(e1.message, e2.message);
    }
    mesh_free(&serial), mesh_free(&parallel);
}

static char *read_whole(const char *path, size_t *length)
{
    parse_error err;
    char *text;
    ck_assert_msg(parse_read_file(path, OBJ_MAX_BYTES, &text, length, &err),
                  "%s", err.message);
    return text;
}

START_TEST(test_parts_read_the_project_s_meshes_as_chapter_4_does)
{
    const char *paths[] = {"meshes/bunny.obj", "meshes/teapot-8.obj",
                           "meshes/icosphere-5.obj"};
    int parts[] = {1, 2, 3, 8, 61};
    for (size_t k = 0; k < sizeof paths / sizeof *paths; k++) {
        size_t length;
        char *text = read_whole(paths[k], &length);
        for (size_t j = 0; j < sizeof parts / sizeof *parts; j++)
            expect_parts_read_as_chapter_4(text, length, NO_BUDGET, parts[j]);
        free(text);
    }
}
END_TEST

START_TEST(test_threads_read_a_file_as_chapter_4_does)
{
    mesh serial = {0};
    parse_error err;
    ck_assert(mesh_load_obj(&serial, "meshes/bunny.obj", &err));
    int threads[] = {0, 1, 2, 3, 8};
    for (size_t k = 0; k < sizeof threads / sizeof *threads; k++) {
        mesh m = {0};
        ck_assert(mesh_load_obj_on(&m, "meshes/bunny.obj", NO_BUDGET,
                                   threads[k], &err));
        expect_same_mesh(&serial, &m);
        mesh_free(&m);
    }
    mesh_free(&serial);
}
END_TEST

/* The project's meshes, read from their files on 1, 2 and 3 threads,
 * take the parallel path: as many parts as their size and the threads
 * give (OBJ_MIN_PART_BYTES of text a part, OBJ_PARTS_A_THREAD parts a
 * thread), not chapter 4's reader, and chapter 4's mesh. */
START_TEST(test_the_project_s_meshes_are_read_in_parts)
{
    const char *paths[] = {"meshes/bunny.obj", "meshes/teapot-8.obj",
                           "meshes/icosphere-5.obj"};
    for (size_t k = 0; k < sizeof paths / sizeof *paths; k++) {
        mesh serial = {0};
        parse_error err;
        ck_assert(mesh_load_obj(&serial, paths[k], &err));
        size_t length;
        free(read_whole(paths[k], &length));
        for (int threads = 1; threads <= 3; threads++) {
            mesh m = {0};
            ck_assert_msg(mesh_load_obj_on(&m, paths[k], NO_BUDGET, threads,
                                           &err),
                          "%s", err.message);
            long most = 1 + (long)(length / OBJ_MIN_PART_BYTES);
            long wanted = (long)threads * OBJ_PARTS_A_THREAD;
            ck_assert_msg(m.parts == (wanted < most ? wanted : most),
                          "%s on %d threads: %d parts, not %ld", paths[k],
                          threads, m.parts, wanted < most ? wanted : most);
            expect_same_mesh(&serial, &m);
            mesh_free(&m);
        }
        mesh_free(&serial);
    }
    /* and in memory, in the parts asked for */
    size_t length;
    char *text = read_whole("meshes/bunny.obj", &length);
    for (int parts = 1; parts <= 61; parts += 20) {
        mesh m = {0};
        parse_error err;
        ck_assert(mesh_parse_obj_in_parts(&m, text, length, "bunny.obj",
                                          NO_BUDGET, parts, 2, &err));
        ck_assert_int_eq(m.parts, parts);
        mesh_free(&m);
    }
    free(text);
}
END_TEST

/* What the test's writer does to a file between its reading and the
 * second look at its size. */
static const char *change;

static void change_the_file(const char *path)
{
    FILE *f = fopen(path, strcmp(change, "grow") == 0 ? "a" : "w");
    ck_assert_ptr_nonnull(f);
    fputs(strcmp(change, "grow") == 0 ? "v 9 9 9\n" : "", f);
    ck_assert_int_eq(fclose(f), 0);
}

START_TEST(test_a_file_that_changes_while_it_is_read_is_an_error)
{
    const char *ways[] = {"grow", "shrink"};
    for (int k = 0; k < 2; k++) {
        change = ways[k];
        const char *path = write_file("mesh.obj", "v 0 0 5\nv 1 0 5\n"
                                                  "v 0 1 5\nf 1 2 3\n");
        mesh m = {0};
        parse_error err = {0};
        obj_test_after_reading = change_the_file;
        bool read = mesh_load_obj_on(&m, path, NO_BUDGET, 2, &err);
        obj_test_after_reading = NULL;
        ck_assert_msg(!read, "%s: read all the same", ways[k]);
        ck_assert_int_eq(err.kind, PARSE_CANNOT_READ);
        ck_assert_msg(strstr(err.message, "changed while it was read") &&
                          strstr(err.message, "32 bytes before"),
                      "%s: %s", ways[k], err.message);
        mesh_free(&m);
        /* unchanged, it reads; and in a scene, the line naming it says */
        path = write_file("mesh.obj", "v 0 0 5\nv 1 0 5\n"
                                      "v 0 1 5\nf 1 2 3\n");
        ck_assert(mesh_load_obj_on(&m, path, NO_BUDGET, 2, &err));
        mesh_free(&m);
        const char *scene_path = write_file(
            "s.scene", "image 8 6\nsphere\nmesh file mesh.obj\n");
        scene s;
        scene_error e;
        scene_init(&s);
        obj_test_after_reading = change_the_file;
        read = scene_load(&s, scene_path, &e);
        obj_test_after_reading = NULL;
        ck_assert(!read);
        ck_assert_int_eq(e.line, 3);
        ck_assert_msg(strstr(e.message, "mesh.obj") &&
                          strstr(e.message, "changed while it was read"),
                      "%s", e.message);
        scene_free(&s);
    }
}
END_TEST

/* Appends printf's text to buf[*at..size). */
static void put(char *buf, size_t size, size_t *at, const char *format, ...)
    __attribute__((format(printf, 4, 5)));
static void put(char *buf, size_t size, size_t *at, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int n = vsnprintf(buf + *at, size - *at, format, args);
    va_end(args);
    ck_assert(n >= 0 && (size_t)n < size - *at);
    *at += (size_t)n;
}

/* One corner: a vertex among the v so far, by its number or backwards,
 * with a texture coordinate and a normal when there are some. */
static void put_corner(char *buf, size_t size, size_t *at, int v, int vt,
                       int vn)
{
    int pick = below(4), a = 1 + below(v);
    int index = below(2) ? a : a - v - 1; /* -1: the last */
    if (pick == 1 && vt > 0)
        put(buf, size, at, " %d/%d", index, -1 - below(vt));
    else if (pick == 2 && vn > 0)
        put(buf, size, at, " %d//%d", index, 1 + below(vn));
    else if (pick == 3 && vt > 0 && vn > 0)
        put(buf, size, at, " %d/%d/%d", index, 1 + below(vt), -1 - below(vn));
    else
        put(buf, size, at, " %d", index);
}

/* OBJ text of about lines lines with every kind of statement: vertices
 * (some with a w), normals, texture coordinates, faces of 3 to 6 corners
 * in the four forms, by number and backwards, comments, blank lines, CR
 * LF endings, tabs, and statements that are not ours. */
static size_t every_kind_of_statement(char *buf, size_t size, int lines)
{
    size_t at = 0;
    int v = 0, vn = 0, vt = 0;
    for (int k = 0; k < lines; k++) {
        int kind = v < 3 ? 0 : below(10);
        double x = rng_uniform(&rng, -0.5, 0.5), y = rng_uniform01(&rng);
        if (kind <= 2)
            put(buf, size, &at,
                kind ? "v %.17g %.9g %g\n" : "v\t%.17g %.9g %g 1\r\n", x, y,
                x * y),
                v++;
        else if (kind == 3)
            put(buf, size, &at, "vn %g %g 1\n", x, y), vn++;
        else if (kind == 4)
            put(buf, size, &at, "vt %g %g\n", y, x), vt++;
        else if (kind == 5)
            put(buf, size, &at, below(2) ? "# a comment\n" : "\n");
        else if (kind == 6)
            put(buf, size, &at, "g part%d\ns off\nusemtl m\n", k);
        else {
            int corners = 3 + below(4);
            put(buf, size, &at, "f");
            for (int c = 0; c < corners; c++)
                put_corner(buf, size, &at, v, vt, vn);
            put(buf, size, &at, below(2) ? "\n" : " # f\r\n");
        }
    }
    return at;
}

START_TEST(test_parts_read_every_kind_of_statement_as_chapter_4_does)
{
    static char text[1 << 20];
    size_t length = every_kind_of_statement(text, sizeof text, 12000);
    mesh m = {0};
    parse_error err;
    ck_assert_msg(read_serially(text, length, NO_BUDGET, &m, &err), "%d:%d: %s",
                  err.line, err.col, err.message);
    ck_assert_int_gt(m.triangle_count, 5000); /* and it is not empty */
    ck_assert_int_gt(m.normal_count, 500);
    mesh_free(&m);
    for (int parts = 1; parts <= 17; parts++)
        expect_parts_read_as_chapter_4(text, length, NO_BUDGET, parts);
}
END_TEST

/* Where part k of n begins, by the rule of chapter 12: the first line that
 * starts at or after k/n of the text, not with a byte order mark. */
static size_t start_of_part(const char *text, size_t length, int k, int n)
{
    if (k == 0)
        return 0;
    size_t at = length * (size_t)k / (size_t)n;
    for (at = at > 0 ? at : 1; at < length; at++)
        if (text[at - 1] == '\n' &&
            !(length - at >= 3 && memcmp(text + at, "\xEF\xBB\xBF", 3) == 0))
            break;
    return at;
}

/* text with line inserted at byte at, in out; its length. */
static size_t insert(char *out, const char *text, size_t length, size_t at,
                     const char *line)
{
    size_t n = strlen(line);
    memcpy(out, text, at);
    memcpy(out + at, line, n);
    memcpy(out + at + n, text + at, length - at);
    return length + n;
}

/* A line before the first line of part k, or the first line itself, is
 * a mistake: each kind of mistake, at each of n parts' boundaries. */
START_TEST(test_a_mistake_at_a_part_s_first_line_is_chapter_4_s)
{
    static char text[1 << 18], wrong[(1 << 18) + 256];
    size_t length = every_kind_of_statement(text, sizeof text, 3000);
    const char *mistakes[] = {
        "v 1 2 x\n",
        "f 1 2 99999\n",
        "f -1 -2 -99999\n",
        "f 1 2\n",
        "f 1/1/1/1 2 3\n",
        "vn 1 nan 0\n",
        "f 0 1 2\n",
        "v 1 2 3\0\n",
        "\357\273\277f -1 -2 0\n", /* after a byte order mark */
    };
    int n = 5;
    for (int k = 1; k < n; k++) {
        size_t b = start_of_part(text, length, k, n);
        size_t before = b - 1; /* inside the last line of part k - 1 */
        while (before > 0 && text[before - 1] != '\n')
            before--;
        for (size_t j = 0; j < sizeof mistakes / sizeof *mistakes; j++) {
            const char *m = mistakes[j];
            size_t len = j == 7 ? 9 : strlen(m); /* one has a NUL */
            char line[64];
            memcpy(line, m, len), line[len] = '\0';
            for (int side = 0; side < 2; side++) {
                size_t at = side ? b : before, w;
                if (j == 7) { /* insert's strlen stops at the NUL */
                    memcpy(wrong, text, at);
                    memcpy(wrong + at, m, len);
                    memcpy(wrong + at + len, text + at, length - at);
                    w = length + len;
                } else {
                    w = insert(wrong, text, length, at, line);
                }
                expect_parts_read_as_chapter_4(wrong, w, NO_BUDGET, n);
            }
        }
    }
}
END_TEST

START_TEST(test_the_first_of_two_mistakes_wins)
{
    static char text[1 << 18], once[(1 << 18) + 64], twice[(1 << 18) + 128];
    size_t length = every_kind_of_statement(text, sizeof text, 3000);
    int n = 4;
    size_t b1 = start_of_part(text, length, 1, n);
    size_t b3 = start_of_part(text, length, 3, n);
    /* the later mistake first, so that the earlier one's place holds */
    size_t l1 = insert(once, text, length, b3, "v 1 2\n");
    size_t l2 = insert(twice, once, l1, b1, "f 1 2 3 -9999999\n");
    expect_parts_read_as_chapter_4(twice, l2, NO_BUDGET, n);
    expect_parts_read_as_chapter_4(once, l1, NO_BUDGET, n);
}
END_TEST

START_TEST(test_a_budget_is_crossed_where_chapter_4_crosses_it)
{
    static char text[1 << 17];
    size_t length = every_kind_of_statement(text, sizeof text, 1500);
    mesh whole = {0};
    parse_error err;
    ck_assert_msg(read_serially(text, length, NO_BUDGET, &whole, &err),
                  "%d:%d: %s", err.line, err.col, err.message);
    long long bytes = mesh_bytes(&whole);
    long triangles = whole.triangle_count;
    mesh_free(&whole);
    for (long long b = 0; b <= bytes + 64; b += 1 + bytes / 97)
        for (int parts = 1; parts <= 4; parts += 3)
            expect_parts_read_as_chapter_4(
                text, length, (mesh_budget){MESH_MAX_TRIANGLES, b}, parts);
    for (int parts = 1; parts <= 4; parts += 3) {
        expect_parts_read_as_chapter_4(
            text, length, (mesh_budget){MESH_MAX_TRIANGLES, bytes}, parts);
        expect_parts_read_as_chapter_4(
            text, length, (mesh_budget){MESH_MAX_TRIANGLES, bytes - 1}, parts);
        for (long t = triangles - 2; t <= triangles; t++)
            expect_parts_read_as_chapter_4(text, length,
                                           (mesh_budget){t, 1LL << 60}, parts);
    }
}
END_TEST

/* A line that starts with a byte order mark is a statement of no kind of
 * ours, wherever it is but at the start of the file: not a part's start. */
START_TEST(test_a_byte_order_mark_is_skipped_at_the_file_s_start_only)
{
    static char text[1 << 16], marked[(1 << 16) + 64];
    size_t length = every_kind_of_statement(text, sizeof text, 600);
    for (int n = 2; n <= 6; n++) {
        size_t b = start_of_part(text, length, n / 2, n);
        size_t l = insert(marked, text, length, b, "\xEF\xBB\xBFv 9 9 9\n");
        expect_parts_read_as_chapter_4(marked, l, NO_BUDGET, n);
        l = insert(marked, text, length, 0, "\xEF\xBB\xBFv 9 9 9\n");
        expect_parts_read_as_chapter_4(marked, l, NO_BUDGET, n);
    }
}
END_TEST

/* A number of OBJ_LONG_NUMBER characters or more is read from a copy in
 * memory, which only the calling thread may take: such a file is read as
 * chapter 4 reads it, wherever the number is. */
START_TEST(test_a_long_number_is_read_as_chapter_4_reads_it)
{
    static char text[1 << 16], longer[(1 << 16) + 256];
    char line[256] = "v 0.";
    memset(line + 4, '5', OBJ_LONG_NUMBER);
    strcpy(line + 4 + OBJ_LONG_NUMBER, " 1 2\n");
    size_t length = every_kind_of_statement(text, sizeof text, 600);
    for (int k = 0; k < 4; k++) {
        size_t at = start_of_part(text, length, k, 4);
        size_t l = insert(longer, text, length, at, line);
        expect_parts_read_as_chapter_4(longer, l, NO_BUDGET, 4);
    }
}
END_TEST

/* Texts shorter than their parts, each in memory of its own length, so
 * that the sanitizers see a part that reads past the text's end. */
START_TEST(test_texts_shorter_than_their_parts_read_as_chapter_4_reads_them)
{
    const char *texts[] = {"", "\n", "v 1 2 3", "v 1 2 3\n",
                           "v 1 2 3\nv 4 5 6\nv 7 8 9\nf 1 2 -1",
                           "v 1 2 3\n\n\nf 1 1 1\n"};
    for (size_t k = 0; k < sizeof texts / sizeof *texts; k++) {
        size_t length = strlen(texts[k]);
        char *text = malloc(length); /* of 0 bytes too: none to read */
        ck_assert(text != NULL || length == 0);
        if (length > 0)
            memcpy(text, texts[k], length);
        for (int parts = 1; parts <= 9; parts++)
            expect_parts_read_as_chapter_4(text, length, NO_BUDGET, parts);
        free(text);
    }
}
END_TEST

/* With memory for only the first n allocations, the reader in parts
 * fails as chapter 4's does, with no memory, and leaves no mesh; or it
 * reads chapter 4's mesh (its threads take no memory of their own). */
START_TEST(test_running_out_of_memory_in_parts_is_reported)
{
    static char text[1 << 16];
    size_t length = every_kind_of_statement(text, sizeof text, 600);
    mesh whole = {0};
    parse_error err;
    ck_assert(read_serially(text, length, NO_BUDGET, &whole, &err));
    bool read = false;
    for (long n = 0; n < 40 && !read; n++) {
        mesh m = {0};
        memory_fail_after(n);
        read = mesh_parse_obj_in_parts(&m, text, length, "mesh.obj",
                                       NO_BUDGET, 4, 2, &err);
        memory_fail_after(-1);
        if (read)
            expect_same_mesh(&whole, &m);
        else
            ck_assert_int_eq(err.kind, PARSE_NO_MEMORY);
        mesh_free(&m);
    }
    ck_assert_msg(read, "never read with 40 allocations");
    mesh_free(&whole);
}
END_TEST

Suite *ch12_load_suite(void)
{
    Suite *s = suite_create("ch12 load");
    TCase *same = tcase_create("the same mesh");
    tcase_add_checked_fixture(same, reseed, NULL);
    tcase_add_checked_fixture(same, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(same, 120);
    tcase_add_test(same,
                   test_parts_read_the_project_s_meshes_as_chapter_4_does);
    tcase_add_threaded_test(same, test_threads_read_a_file_as_chapter_4_does);
    tcase_add_threaded_test(same, test_the_project_s_meshes_are_read_in_parts);
    tcase_add_test(same, test_a_long_number_is_read_as_chapter_4_reads_it);
    tcase_add_test(
        same, test_texts_shorter_than_their_parts_read_as_chapter_4_reads_them);
    tcase_add_test(same,
                   test_parts_read_every_kind_of_statement_as_chapter_4_does);
    suite_add_tcase(s, same);
    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, reseed, NULL);
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(bad, 120);
    tcase_add_test(bad, test_a_mistake_at_a_part_s_first_line_is_chapter_4_s);
    tcase_add_test(bad, test_the_first_of_two_mistakes_wins);
    tcase_add_test(bad, test_a_budget_is_crossed_where_chapter_4_crosses_it);
    tcase_add_test(bad,
                   test_a_byte_order_mark_is_skipped_at_the_file_s_start_only);
    tcase_add_test(bad, test_running_out_of_memory_in_parts_is_reported);
    tcase_add_test(bad,
                   test_a_file_that_changes_while_it_is_read_is_an_error);
    suite_add_tcase(s, bad);
    return s;
}
