/* ch10_bvh_packets.c: chapter 10's BVH with leaves of packets, walked by
 * chapter 9's binary walk: the same answers as brute force and as chapter
 * 8's kd-tree, bit for bit; packets that hold their leaves' triangles;
 * the BVH's bytes; and the accelerator bvh-float. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "memory.h"
#include "mesh.h"
#include "rng.h"
#include "scene_file.h"
#include "test_util.h"

/* From tests/ch09_bvh.c. */
mesh ch09_load(const char *path);
mesh ch09_bare(const mesh *m);
mesh ch09_with_bvh(const mesh *m, const bvh_params *p);
void ch09_expect_agreement(const mesh *m, int count, const char *what,
                           const bvh_params *p);
mesh ch09_plane_mesh(int n, vec3 offset, double size);
mesh ch09_fan_mesh(int n, vec3 centre);
void ch09_expect_edges_and_faces(const bvh_params *p);

/* The binary tree, whatever a later chapter makes the default width. */
static const bvh_params BINARY = {.width = 2};

/* ------------------------------------------------------------ agreement */

/* Brute force, the kd-tree and the binary BVH of packets: one answer. */
START_TEST(test_packet_leaves_agree_on_the_teapot)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    ch09_expect_agreement(&m, 400, "teapot", &BINARY);
    mesh_free(&m);
}
END_TEST

START_TEST(test_packet_leaves_agree_on_the_bunny)
{
    mesh m = ch09_load("meshes/bunny.obj");
    /* brute force: 1 ms a ray */
    ch09_expect_agreement(&m, 30, "bunny", &BINARY);
    mesh_free(&m);
}
END_TEST

START_TEST(test_packet_leaves_agree_on_coincident_planes_and_fans)
{
    const vec3 at[3] = {{0, 0, 0}, {1e6, -1e6, 1e6}, {3e-3, 0, 0}};
    const double size[3] = {1, 10, 1e-5};
    for (int k = 0; k < 3; k++) {
        mesh m = ch09_plane_mesh(12, at[k], size[k]);
        ch09_expect_agreement(&m, 300, "coincident planes", &BINARY);
        mesh_free(&m);
    }
    mesh m = ch09_fan_mesh(300, (vec3){0.25, -0.5, 4});
    ch09_expect_agreement(&m, 300, "fan", &BINARY);
    mesh_free(&m);
}
END_TEST

START_TEST(test_packet_leaves_find_rays_along_edges_and_faces)
{
    ch09_expect_edges_and_faces(&BINARY);
}
END_TEST

/* The teapot, most of whose corners are not floats, and the same teapot
 * rounded to float: only the second is decided on its packets' corners,
 * and its BVH gives brute force's and the kd-tree's answers, bit for bit,
 * at the binary width and at the default. */
START_TEST(test_a_mesh_of_floats_is_decided_on_its_packets_corners)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    mesh b = ch09_with_bvh(&m, &BINARY);
    ck_assert(!b.bvh_corners_in_float);
    mesh_free_tree(&b);
    for (int k = 0; k < m.vertex_count; k++) {
        vec3 v = m.vertices[k];
        m.vertices[k] = (vec3){(float)v.x, (float)v.y, (float)v.z};
    }
    mesh_compute_bounds(&m);
    b = ch09_with_bvh(&m, &BINARY);
    ck_assert(b.bvh_corners_in_float);
    mesh_free_tree(&b);
    ch09_expect_agreement(&m, 400, "teapot in float", &BINARY);
    ch09_expect_agreement(&m, 400, "teapot in float", &(bvh_params){0});
    mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------ packets */

/* The leaf of node k of t (count 0: none): its first packet and its
 * triangles. A binary node is its own one reference (c is 0). */
static uint32_t leaf_of(const bvh *t, int k, int c, uint32_t *count)
{
    (void)c;
    return *count = t->nodes[k].count, t->nodes[k].index;
}

/* Each triangle of m in exactly one lane of b's packets, found through
 * the refs leaves a node of b's tree that leaf_of reads, each lane's
 * corner the mesh's rounded to float, and no packet besides (chapter 11's
 * suite calls it for the wide trees). */
void ch10_expect_packets_hold_each_triangle(
    const mesh *m, const mesh *b, int refs,
    uint32_t (*leaf_of)(const bvh *, int, int, uint32_t *))
{
    int *seen = memory_alloc((size_t)m->triangle_count, sizeof *seen);
    ck_assert_ptr_nonnull(seen);
    memset(seen, 0, (size_t)m->triangle_count * sizeof *seen);
    int packets = 0;
    for (int k = 0; k < b->bvh.node_count; k++)
        for (int c = 0; c < refs; c++) {
            uint32_t count, first = leaf_of(&b->bvh, k, c, &count);
            int n = (int)(count + PACKET_W - 1) / PACKET_W;
            for (int lane = 0; lane < n * PACKET_W; lane++) {
                const triangle_packet *q =
                    &b->bvh_packets[first + lane / PACKET_W];
                int i = q->triangle[lane % PACKET_W];
                ck_assert_int_eq(i >= 0, lane < (int)count);
                if (i < 0)
                    continue;
                seen[i]++;
                vec3 v = m->vertices[m->triangles[i].v[2]];
                ck_assert(q->corner[2][1][lane % PACKET_W] == (float)v.y);
            }
            packets += n;
        }
    for (int i = 0; i < m->triangle_count; i++)
        ck_assert_int_eq(seen[i], 1); /* each in exactly one lane */
    ck_assert_int_eq(packets, b->bvh_packet_count);
    free(seen);
}

START_TEST(test_every_leaf_s_packets_hold_its_triangles)
{
    mesh m = ch09_load("meshes/teapot-8.obj");
    mesh b = ch09_with_bvh(&m, &BINARY);
    ch10_expect_packets_hold_each_triangle(&m, &b, 1, leaf_of);
    mesh_free_tree(&b);
    mesh_free(&m);
}
END_TEST

START_TEST(test_the_bvh_of_a_mesh_stays_within_its_bytes)
{
    const char *paths[] = {"meshes/bunny.obj", "meshes/teapot-8.obj"};
    for (int k = 0; k < 2; k++) {
        mesh m = ch09_load(paths[k]);
        mesh b = ch09_bare(&m);
        ck_assert(mesh_build_bvh(&b, &BINARY));
        double bytes = (double)mesh_tree_bytes(&b) / m.triangle_count;
        ck_assert_msg(bytes <= MESH_BVH_MAX_BYTES_PER_TRIANGLE,
                      "%s: %.1f bytes a triangle", paths[k], bytes);
        mesh_free_tree(&b);
        mesh_free(&m);
    }
}
END_TEST

/* ------------------------------------------------------------ in float */

START_TEST(test_bvh_float_decides_the_bvh_s_leaves_in_float)
{
    link_meshes();
    /* the statement, and --accelerator bvh over it */
    for (int k = 0; k < 2; k++) {
        scene s;
        scene_error err;
        char *path = (char *)write_file(
            "choose.scene",
            "accelerator bvh-float\nmesh file meshes/teapot-8.obj\n");
        scene_init(&s);
        if (k == 1)
            s.accelerator_option = MESH_ACCELERATOR_BVH;
        ck_assert_msg(scene_load(&s, path, &err), "%s", err.message);
        ck_assert(s.meshes[0].bvh.node_count > 0);
        ck_assert_int_eq(s.meshes[0].bvh_in_float, k == 0);
        scene_free(&s);
    }
}
END_TEST

START_TEST(test_bad_accelerator_words_name_all_three)
{
    expect_parse_error("accelerator bvh-double\n", 1, 13,
                       "accelerator (kdtree, bvh, bvh-float)");
    char errors[1024];
    const char *out = tmp_path("never.png");
    const char *args[] = {"--accelerator", "bvh-floats", "-o", out, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "--accelerator expects kdtree, bvh or "
                                 "bvh-float"),
                  "%s", errors);
    ck_assert(!file_exists(out));
}
END_TEST

START_TEST(test_a_kd_tree_heat_map_over_float_bvhs_is_refused)
{
    char errors[1024], out[200], scene[200]; /* tmp_path's buffer is reused */
    snprintf(scene, sizeof scene, "%s",
             write_file("heat.scene", "kdtree heatmap 60\n"));
    snprintf(out, sizeof out, "%s", tmp_path("never.png"));
    const char *args[] = {scene, "--accelerator", "bvh-float", "-o", out,
                          NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "--accelerator bvh-float gives the meshes"),
                  "%s", errors);
    ck_assert(!file_exists(out));
    expect_parse_error("kdtree heatmap 60\naccelerator bvh-float\n", 2, 1,
                       "heat map draws kd-tree nodes");
}
END_TEST

Suite *ch10_bvh_packets_suite(void)
{
    Suite *s = suite_create("ch10 bvh packets");
    TCase *agree = tcase_create("agreement");
    tcase_set_timeout(agree, 120);
    tcase_add_test(agree, test_packet_leaves_agree_on_the_teapot);
    tcase_add_slow_test(agree, test_packet_leaves_agree_on_the_bunny);
    tcase_add_test(agree,
                   test_packet_leaves_agree_on_coincident_planes_and_fans);
    tcase_add_test(agree, test_packet_leaves_find_rays_along_edges_and_faces);
    tcase_add_test(agree,
                   test_a_mesh_of_floats_is_decided_on_its_packets_corners);
    suite_add_tcase(s, agree);
    TCase *packets = tcase_create("packets");
    tcase_set_timeout(packets, 120);
    tcase_add_test(packets, test_every_leaf_s_packets_hold_its_triangles);
    tcase_add_test(packets, test_the_bvh_of_a_mesh_stays_within_its_bytes);
    suite_add_tcase(s, packets);
    TCase *in_float = tcase_create("in float");
    tcase_add_checked_fixture(in_float, make_tmpdir, remove_tmpdir);
    tcase_add_test(in_float, test_bvh_float_decides_the_bvh_s_leaves_in_float);
    tcase_add_test(in_float, test_bad_accelerator_words_name_all_three);
    tcase_add_test(in_float,
                   test_a_kd_tree_heat_map_over_float_bvhs_is_refused);
    suite_add_tcase(s, in_float);
    return s;
}
