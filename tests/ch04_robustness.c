/* ch04_robustness.c: mesh files that are not what the scene meant, and an
 * output that would destroy one (chapter 04).
 *
 * Runs against the program of every chapter from 4 on, which all read OBJ
 * files. */
#include <check.h>
#include <fcntl.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "test_util.h"

static size_t read_bytes(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, size, f) : 0;
    if (f)
        fclose(f);
    return n;
}

START_TEST(test_the_output_may_not_be_a_mesh)
{
    /* -o onto the mesh the scene read, by its name and through a link */
    const char obj[] = "v 0 0 5\nv 1 0 5\nv 0 1 5\nf 1 2 3\n";
    char mesh_path[192], scene_path[192], link_path[192], errors[2048];
    snprintf(mesh_path, sizeof mesh_path, "%s", write_file("m.obj", obj));
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("s.scene", "image 8 6\nmesh file m.obj\n"));
    snprintf(link_path, sizeof link_path, "%s", tmp_path("link.png"));
    ck_assert_int_eq(symlink("m.obj", link_path), 0);
    const char *outs[] = {mesh_path, link_path};
    for (int k = 0; k < 2; k++) {
        const char *args[] = {scene_path, "-o", outs[k], NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, "error: the output is an input:") &&
                          strstr(errors, "m.obj"),
                      "%s", errors);
        char now[128];
        ck_assert_int_eq(read_bytes(mesh_path, now, sizeof now), strlen(obj));
        ck_assert(memcmp(now, obj, strlen(obj)) == 0);
    }
}
END_TEST

START_TEST(test_a_binary_mesh_stops_at_its_first_nul)
{
    /* 512 MiB of NUL bytes (a sparse file: no disk is used), within the
     * OBJ size limit. The NUL at 1:1 is reported after the first piece is
     * read: under a 256 MiB address-space limit there is no room to read
     * the whole file, so an error about memory means it tried. */
    char scene_path[192], errors[2048];
    int fd = open(tmp_path("zeros.obj"), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(ftruncate(fd, 512L << 20), 0);
    close(fd);
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("s.scene", "image 8 6\nmesh file zeros.obj\n"));
    const char *args[] = {scene_path, "-o", tmp_path("out.png"), NULL};
#if defined(TEST_ASAN)
    run_limits limits = {
        0}; /* AddressSanitizer reserves terabytes of addresses */
#else
    run_limits limits = {.max_memory_bytes = 256L << 20};
#endif
    ck_assert_int_eq(run_bin_limited(args, errors, sizeof errors, limits), 1);
    ck_assert_msg(strstr(errors, "zeros.obj:1:1: error: unexpected NUL byte"),
                  "%s", errors);
}
END_TEST

START_TEST(test_an_obj_with_no_face_is_warned_of_and_costs_nothing)
{
    /* The scene itself named as its mesh: a valid OBJ of unknown
     * statements, with no face */
    char scene_path[192], errors[2048];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("self.scene", "image 8 6\nmesh file self.scene\n"));
    const char *args[] = {scene_path, "-o", tmp_path("out.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert_msg(
        strstr(errors, "self.scene: warning: no face in this OBJ file"), "%s",
        errors);
    /* a thousand empty meshes, each placed differently: no object, so no
     * ray tests a box */
    static char text[64 * 1000 + 64];
    int n = snprintf(text, sizeof text, "image 8 6\n");
    for (int k = 0; k < 1000; k++)
        n += snprintf(text + n, sizeof text - (size_t)n,
                      "mesh file empty.obj scale %d\n", k + 1);
    write_file("empty.obj", "v 0 0 1\nv 1 0 1\n# no face\n");
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("many.scene", text));
    scene s;
    scene_error err;
    scene_init(&s);
    ck_assert_msg(scene_load(&s, scene_path, &err), "%s", err.message);
    ck_assert_int_eq(s.object_count, 0);
    image img;
    ck_assert(image_init(&img, 8, 6));
    render_stats st = {0};
    render(&s, &img, &st);
    ck_assert_int_eq(st.box_tests, 0);
    image_free(&img);
    scene_free(&s);
    const char *many[] = {scene_path, "-o", tmp_path("out.png"), NULL};
    ck_assert_int_eq(run_bin(many, errors, sizeof errors), 0);
    ck_assert_msg(
        strstr(errors, "empty.obj: warning: no face in this OBJ file: it shows "
                       "nothing (nor 999 more meshes like it)\n"),
        "%s", errors);
}
END_TEST

Suite *ch04_robustness_suite(void)
{
    Suite *s = suite_create("ch04 robustness");
    TCase *files = tcase_create("hostile input files");
    tcase_add_checked_fixture(files, make_tmpdir, remove_tmpdir);
    tcase_add_test(files, test_the_output_may_not_be_a_mesh);
    tcase_add_test(files, test_a_binary_mesh_stops_at_its_first_nul);
    tcase_add_test(files,
                   test_an_obj_with_no_face_is_warned_of_and_costs_nothing);
    suite_add_tcase(s, files);
    return s;
}
