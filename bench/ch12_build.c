/* ch12_build.c: how long the trees take to build, and how much memory
 * they hold, from a thousand triangles to two million.
 *
 *   build/rel/bench/ch12_build > figures/ch12-build.csv
 *
 * The meshes are terrains (ch09_meshes.h) of 2 n^2 triangles, n from 23
 * to 1000 (1,058 to 2,000,000 triangles), and the bunny. Each is built by
 * every structure of STRUCTURES: chapter 8's kd-tree, the BVH of the
 * default width on one thread (bvh) and on one per core (bvh-all-cores), and, where Embree 3 is installed, Embree's
 * high-quality build on one thread. The builds of one mesh are timed
 * together, interleaved, by the harness (bench/timing.h), one build an
 * operation, in wall time for the builds on all threads and in thread CPU
 * time for the others; ROUNDS_SMALL rounds below 100,000 triangles, fewer
 * above, where one build takes a second.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns),
 * after the "# machine:" line:
 *   STRUCTURE,TRIANGLES,ns_per_build,ns per triangle,ns_per_triangle,q1,q3,wall
 *   bytes,STRUCTURE@TRIANGLES,0,bytes per triangle,bytes_per_triangle
 *   ratio,STRUCTURE@TRIANGLES,0,its time / Embree's,over_embree */
#include <string.h>
#include <time.h>

#include "ch09_meshes.h"
#ifdef HAVE_EMBREE
#include "embree_scene.h"
#endif
#include "timing.h"

enum { ROUNDS_SMALL = 11, ROUNDS_LARGE = 5 };

static const int TERRAIN_SIDES[] = {23, 45, 91, 181, 362, 724, 1000};
enum { N_TERRAINS = sizeof TERRAIN_SIDES / sizeof TERRAIN_SIDES[0] };

/* ---------------------------------------------------------------- ours */

/* One build of a structure over a copy of the mesh: the bytes it holds. */
typedef long long (*build_fn)(const mesh *m);

static long long build_kdtree(const mesh *m)
{
    mesh copy = *m; /* the tree is built into a copy's members */
    copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
    copy.bvh = (bvh){0}, copy.bvh_packets = NULL;
    kdtree_params p = kdtree_default_params();
    if (!mesh_build_tree(&copy, &p))
        exit(1);
    long long bytes = mesh_tree_bytes(&copy);
    mesh_free_tree(&copy);
    return bytes;
}

/* The BVH of the default width, built on the given number of threads
 * (0: one per core). */
static long long build_bvh_on(const mesh *m, int threads)
{
    mesh copy = *m;
    copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
    copy.bvh = (bvh){0}, copy.bvh_packets = NULL;
    bvh_params p = {.threads = threads}; /* zeros: the mesh's defaults */
    if (!mesh_build_bvh(&copy, &p))
        exit(1);
    long long bytes = mesh_tree_bytes(&copy);
    mesh_free_tree(&copy);
    return bytes;
}

static long long build_bvh(const mesh *m) { return build_bvh_on(m, 1); }
static long long build_bvh_all(const mesh *m) { return build_bvh_on(m, 0); }

typedef struct {
    const char *name;
    build_fn build;
    bool all_threads; /* timed by the wall clock */
} structure;

static const structure STRUCTURES[] = {
    {"kdtree", build_kdtree, false},
    {"bvh", build_bvh, false},
    {"bvh-all-cores", build_bvh_all, true},
};
enum { N_OURS = sizeof STRUCTURES / sizeof STRUCTURES[0] };

typedef struct {
    const mesh *m;
    const structure *s;
} build_ctx;

static void run_build(void *ctx, long reps)
{
    const build_ctx *c = ctx;
    for (long r = 0; r < reps; r++)
        bench_sink += (double)c->s->build(c->m);
}

/* ---------------------------------------------------------------- Embree */

#ifdef HAVE_EMBREE
static long long embree_bytes_now; /* what Embree's device holds */

static bool count_bytes(void *unused, ssize_t bytes, bool post)
{
    (void)unused, (void)post;
    embree_bytes_now += bytes;
    return true;
}

typedef struct {
    const mesh *m;
    RTCDevice device;
} embree_ctx;

/* The bytes of Embree's tree: what the device holds once the scene is
 * committed, less what it held with the scene's buffers alone (the
 * vertices and indices, which our structures do not count either). */
static long long embree_build(const embree_ctx *c)
{
    RTCScene scene = embree_scene(c->device, c->m, RTC_BUILD_QUALITY_HIGH);
    long long before = embree_bytes_now;
    rtcCommitScene(scene);
    long long bytes = embree_bytes_now - before;
    rtcReleaseScene(scene);
    return bytes;
}

static void run_embree_build(void *ctx, long reps)
{
    for (long r = 0; r < reps; r++)
        bench_sink += (double)embree_build(ctx);
}
#endif

/* ---------------------------------------------------------------- one mesh */

static void print_mesh(const char *name, const mesh *m, const bench_case *c,
                       const bench_timing *t, const long long *bytes, int n)
{
    double tris = m->triangle_count;
    char param[64];
    for (int k = 0; k < n; k++) {
        const bench_timing *x = &t[k];
        bench_row(c[k].method, name, x, "%.1f", x->median / tris, "ns_per_triangle");
        snprintf(param, sizeof param, "%s@%s", c[k].method, name);
        printf("bytes,%s,0,%.2f,bytes_per_triangle\n", param, bytes[k] / tris);
        if (strcmp(c[n - 1].method, "embree") == 0 && k < n - 1)
            printf("ratio,%s,0,%.4f,over_embree\n", param, x->median / t[n - 1].median);
    }
}

#ifdef HAVE_EMBREE
static RTCDevice device;
#endif

/* A build on all threads, timed by the wall clock (the thread CPU time of
 * the harness sees only the calling thread's part): rounds builds, after
 * one to warm up. */
static void time_by_the_wall(const bench_case *c, int rounds, bench_timing *t)
{
    double ns[ROUNDS_SMALL];
    c->run(c->ctx, 1);
    for (int r = 0; r < rounds; r++) {
        struct timespec a, b;
        clock_gettime(CLOCK_MONOTONIC, &a);
        c->run(c->ctx, 1);
        clock_gettime(CLOCK_MONOTONIC, &b);
        ns[r] = 1e9 * (double)(b.tv_sec - a.tv_sec) + (double)(b.tv_nsec - a.tv_nsec);
    }
    bench_timing_of_samples(ns, rounds, t);
}

/* Times every structure's builds of m: those on one thread together,
 * interleaved, in thread CPU time; those on all threads by the wall
 * clock. Rows named name. */
static void time_mesh(const char *name, const mesh *m)
{
    bench_case c[N_OURS + 1], together[N_OURS + 1];
    bench_timing t[N_OURS + 1], timed[N_OURS + 1];
    long long bytes[N_OURS + 1];
    build_ctx ctx[N_OURS];
    int n = 0, in_turns[N_OURS + 1], n_together = 0;
    for (int k = 0; k < N_OURS; k++, n++) {
        ctx[k] = (build_ctx){m, &STRUCTURES[k]};
        c[n] = (bench_case){STRUCTURES[k].name, name, run_build, &ctx[k], 1};
        bytes[n] = STRUCTURES[k].build(m);
    }
#ifdef HAVE_EMBREE
    embree_ctx e = {m, device};
    c[n] = (bench_case){"embree", name, run_embree_build, &e, 1};
    bytes[n++] = embree_build(&e);
#endif
    for (int k = 0; k < n; k++)
        if (k >= N_OURS || !STRUCTURES[k].all_threads)
            in_turns[n_together] = k, together[n_together++] = c[k];
    int rounds = m->triangle_count < 100000 ? ROUNDS_SMALL : ROUNDS_LARGE;
    bench_time_cases_rounds(together, n_together, rounds, timed);
    for (int j = 0; j < n_together; j++)
        t[in_turns[j]] = timed[j];
    for (int k = 0; k < N_OURS; k++)
        if (STRUCTURES[k].all_threads)
            time_by_the_wall(&c[k], rounds, &t[k]);
    print_mesh(name, m, c, t, bytes, n);
}

int main(int argc, char **argv)
{
#ifdef HAVE_EMBREE
    device = rtcNewDevice("threads=1");
    if (device == NULL)
        return 1;
    rtcSetDeviceMemoryMonitorFunction(device, count_bytes, NULL);
#endif
    bench_print_machine();
    bench_csv_header();
    for (int k = 0; k < N_TERRAINS; k++) {
        mesh m = terrain_mesh(TERRAIN_SIDES[k]);
        char name[32];
        snprintf(name, sizeof name, "%d", m.triangle_count);
        time_mesh(name, &m);
        mesh_free(&m);
        fflush(stdout);
    }
    mesh bunny;
    load_float_mesh(argc > 1 ? argv[1] : "meshes/bunny.obj", &bunny);
    time_mesh("bunny", &bunny);
    mesh_free(&bunny);
#ifdef HAVE_EMBREE
    rtcReleaseDevice(device);
#endif
    return 0;
}
