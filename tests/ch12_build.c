/* ch12_build.c: chapter 12's BVH build on every core: the same nodes,
 * items and packets, byte for byte, on any number of threads, over a
 * mesh and over boxes enough for the top's passes to be shared; and no
 * more threads started than the build has tasks. */
#include <check.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "mesh.h"
#include "rng.h"
#include "test_util.h"

/* From tests/ch09_bvh.c. */
mesh ch09_load(const char *path);
mesh ch09_with_bvh(const mesh *m, const bvh_params *p);
mesh ch09_fan_mesh(int n, vec3 centre);

static const rng_state RNG_START = {0xB7Bu};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

static mesh with_bvh(const mesh *m, int width, int threads)
{
    return ch09_with_bvh(m, &(bvh_params){.width = width, .threads = threads});
}

static size_t node_bytes(const bvh *t)
{
    size_t size = t->width == 2 ? sizeof(bvh_node) : sizeof(bvh_node8);
    return (size_t)t->node_count * size;
}

static const void *node_array(const bvh *t)
{
    return t->width == 2 ? (const void *)t->nodes : (const void *)t->nodes8;
}

START_TEST(test_thread_counts_build_the_same_tree)
{
    mesh m = ch09_load("meshes/bunny.obj");
    for (int width = 2; width <= 8; width *= 2) {
        mesh one = with_bvh(&m, width, 1);
        const int threads[] = {2, 3, 8, 0};
        for (int k = 0; k < 4; k++) {
            mesh many = with_bvh(&m, width, threads[k]);
            ck_assert_int_eq(many.bvh.node_count, one.bvh.node_count);
            ck_assert_msg(memcmp(node_array(&many.bvh), node_array(&one.bvh),
                                 node_bytes(&one.bvh)) == 0,
                          "width %d, %d threads: other nodes", width,
                          threads[k]);
            ck_assert(memcmp(many.bvh.items, one.bvh.items,
                             (size_t)m.triangle_count * sizeof(int)) == 0);
            ck_assert_int_eq(many.bvh_packet_count, one.bvh_packet_count);
            ck_assert(memcmp(many.bvh_packets, one.bvh_packets,
                             (size_t)one.bvh_packet_count *
                                 sizeof(triangle_packet)) == 0);
            mesh_free_tree(&many);
        }
        mesh_free_tree(&one);
    }
    mesh_free(&m);
}
END_TEST

/* Boxes enough for the top's passes to be shared (three times
 * BVH_SHARED_ITEMS and more: four slices at the root, fewer than five
 * threads ask for and more than two or three get; two in its children),
 * on a coarse grid so that many centers coincide, some
 * at the origin with either sign of zero: the slices' boxes, bins and
 * partitions make the tree that one thread makes, to the bit. */
START_TEST(test_thread_counts_build_the_same_tree_over_many_items)
{
    int n = 3 * BVH_SHARED_ITEMS + 17;
    box *b = malloc((size_t)n * sizeof *b);
    ck_assert_ptr_nonnull(b);
    for (int k = 0; k < n; k++) {
        vec3 c = {(double)(rng_next(&rng) % 64) - 32,
                  (double)(rng_next(&rng) % 8),
                  rng_uniform(&rng, -1, 1)};
        c = k % 7 == 0 ? (vec3){k % 2 ? -0.0 : 0.0, k % 3 ? -0.0 : 0.0,
                                k % 5 ? -0.0 : 0.0}
                       : c;
        b[k] = (box){c, vec3_add(c, (vec3){0.5, k % 11 ? 0.25 : 0, 0})};
    }
    for (int width = 2; width <= 8; width *= 2) {
        bvh one, many;
        ck_assert(bvh_build(&one, n, b,
                            &(bvh_params){.width = width, .threads = 1}));
        const int threads[] = {2, 3, 5};
        for (int k = 0; k < 3; k++) {
            ck_assert(bvh_build(&many, n, b,
                                &(bvh_params){.width = width,
                                              .threads = threads[k]}));
            ck_assert_int_eq(many.node_count, one.node_count);
            ck_assert_msg(memcmp(node_array(&many), node_array(&one),
                                 node_bytes(&one)) == 0,
                          "width %d, %d threads: other nodes", width,
                          threads[k]);
            ck_assert(memcmp(many.items, one.items,
                             (size_t)n * sizeof(int)) == 0);
            bvh_free(&many);
        }
        bvh_free(&one);
    }
    free(b);
}
END_TEST

START_TEST(test_a_build_starts_no_more_threads_than_tasks)
{
    /* eight triangles are one task: the calling thread alone, whatever
     * the count asked for; the bunny's tasks share out over the threads */
    mesh small = ch09_fan_mesh(8, (vec3){0.25, -0.5, 4});
    for (int width = 2; width <= 8; width *= 2) {
        mesh b = with_bvh(&small, width, 256);
        ck_assert_msg(b.bvh.build_threads == 1,
                      "8 triangles, %d wide: %d threads", width,
                      b.bvh.build_threads);
        mesh_free_tree(&b);
    }
    mesh_free(&small);
    mesh bunny = ch09_load("meshes/bunny.obj");
    mesh b = with_bvh(&bunny, 4, 3);
    ck_assert_int_eq(b.bvh.build_threads, 3);
    mesh_free_tree(&b);
    mesh_free(&bunny);
}
END_TEST

Suite *ch12_build_suite(void)
{
    Suite *s = suite_create("ch12 build");
    TCase *tc = tcase_create("threads");
    tcase_add_checked_fixture(tc, reseed, NULL);
    tcase_set_timeout(tc, 120);
    tcase_add_threaded_test(tc, test_thread_counts_build_the_same_tree);
    tcase_add_test(tc, test_thread_counts_build_the_same_tree_over_many_items);
    tcase_add_test(tc, test_a_build_starts_no_more_threads_than_tasks);
    suite_add_tcase(s, tc);
    return s;
}
