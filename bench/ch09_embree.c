/* ch09_embree.c: chapter 8's kd-tree against Intel Embree 3, on the same
 * rays, one thread each, timed together.
 *
 *   build/rel/bench/ch09_embree [BUNNY.obj TEAPOT.obj] > figures/ch09-embree.csv
 *
 * Built only where Embree 3 is installed (Debian: libembree-dev); without
 * it, `make charts` draws the chart from this program's own rates and
 * says that Embree was absent.
 *
 * For the Stanford bunny and the teapot, at K = 1 and K = 2.5, the
 * 1024 x 1024 rays of ch08_rays.h are traced by closest hit, by
 * mesh_nearest (the renderer's kd-tree) and by
 * rtcIntersect1 (Embree's BVH, built with RTC_BUILD_QUALITY_HIGH, a device
 * with threads=1). Times come from the harness (bench/timing.h): one
 * operation is one ray, every batch whole passes over the SIDE x SIDE
 * rays, and all eight cases (two programs, two meshes, two K) are timed
 * together, interleaved, in thread CPU time (rtcIntersect1 runs on the
 * calling thread). The builds, one operation each (ours: mesh_build_tree
 * on a copy of the mesh; Embree's: a new scene, rtcCommitScene, release),
 * are timed the same way, the four together, also in thread CPU time:
 * Embree's build with threads=1 runs on the calling thread (its CPU time
 * and wall time agree; the program warns on stderr if they ever do not).
 * The hits and distances come from one pass of each program, untimed.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns),
 * after the "# machine:" line:
 *   kdtree-build|embree-build,MESH,ns_per_build,ms,build_ms,q1,q3,wall
 *   build,MESH,0,kdtree / embree,build_kdtree_over_embree  (of the medians)
 *   kdtree|embree,MESH-K,ns_per_ray,Mrays/s,mrays_per_s,q1,q3,wall
 *   ratio,MESH-K,0,kdtree rate / embree rate,kdtree_over_embree (Embree's
 *       median ns per ray over ours)
 *   hits,MESH-K,0,count,kdtree_hits|embree_hits|rays_that_disagree
 *       (a ray disagrees when one program hits and the other does not,
 *       or both hit at distances more than 1e-5 apart, relatively)
 *   distance,MESH-K,0,sum of the hits' t,kdtree_sum_t|embree_sum_t */
#include <embree3/rtcore.h>
#include <string.h>

#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 1024, N_RAYS = SIDE * SIDE, N_MESHES = 2, N_K = 2 };

static const double K_VALUES[N_K] = {1.0, 2.5};

/* ---------------------------------------------------------------- Embree */

static RTCScene embree_scene(RTCDevice device, const mesh *m)
{
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), (size_t)m->vertex_count);
    for (int k = 0; k < m->vertex_count; k++) {
        v[3 * k] = (float)m->vertices[k].x;
        v[3 * k + 1] = (float)m->vertices[k].y;
        v[3 * k + 2] = (float)m->vertices[k].z;
    }
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)m->triangle_count);
    for (int k = 0; k < m->triangle_count; k++)
        for (int c = 0; c < 3; c++)
            ix[3 * k + c] = (unsigned)m->triangles[k].v[c];
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return scene;
}

/* ---------------------------------------------------------------- one ray each */

/* What both programs trace: a mesh (with its tree) or Embree's scene of
 * it, and the rays of one K. */
typedef struct {
    const mesh *m;
    RTCScene scene;
    const float_ray *rays;
} trace_ctx;

/* Ray k through our kd-tree: its distance (in double), or infinity. */
static double kdtree_ray(const trace_ctx *c, long k, render_stats *stats)
{
    mesh_ray mr = mesh_ray_of(ray_of(&c->rays[k]));
    triangle_hit th;
    return mesh_nearest(c->m, &mr, 0, INFINITY, &th, stats) >= 0 ? th.t : INFINITY;
}

/* Ray k through Embree's scene: its distance, or infinity. */
static double embree_ray(const trace_ctx *c, long k, struct RTCIntersectContext *context)
{
    struct RTCRayHit rh;
    const float_ray *r = &c->rays[k];
    rh.ray.org_x = r->o[0], rh.ray.org_y = r->o[1], rh.ray.org_z = r->o[2];
    rh.ray.dir_x = r->d[0], rh.ray.dir_y = r->d[1], rh.ray.dir_z = r->d[2];
    rh.ray.tnear = 0, rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xffffffffu, rh.ray.flags = 0, rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(c->scene, context, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : INFINITY;
}

/* reps rays, whole passes over the rays (the harness's cycle). */
static void run_kdtree(void *ctx, long reps)
{
    render_stats stats = {0}; /* once a batch, as the renderer's once a band */
    double sum = 0;
    for (long k = 0; k < reps; k++)
        sum += kdtree_ray(ctx, k % N_RAYS, &stats) < INFINITY;
    bench_sink += sum;
}

static void run_embree(void *ctx, long reps)
{
    struct RTCIntersectContext context; /* once a batch */
    rtcInitIntersectContext(&context);
    double sum = 0;
    for (long k = 0; k < reps; k++)
        sum += embree_ray(ctx, k % N_RAYS, &context) < INFINITY;
    bench_sink += sum;
}

/* ---------------------------------------------------------------- one build each */

typedef struct {
    const mesh *m;
    RTCDevice device;
} build_ctx;

static void run_kdtree_build(void *ctx, long reps)
{
    const build_ctx *c = ctx;
    for (long r = 0; r < reps; r++) {
        mesh copy = *c->m; /* the tree is built into a copy's members */
        copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
        kdtree_params p = kdtree_default_params();
        if (!mesh_build_tree(&copy, &p))
            exit(1);
        bench_sink += copy.tree.node_count;
        kdtree_free(&copy.tree);
        free(copy.leaf_corners);
    }
}

static void run_embree_build(void *ctx, long reps)
{
    const build_ctx *c = ctx;
    for (long r = 0; r < reps; r++) {
        RTCScene scene = embree_scene(c->device, c->m);
        rtcCommitScene(scene);
        bench_sink += 1;
        rtcReleaseScene(scene);
    }
}

/* ---------------------------------------------------------------- the rows */

/* Warns when a case's thread CPU time falls well short of its wall time:
 * then other threads did its work, and the thread CPU time is not its cost. */
static void check_own_thread(const bench_case *c, const bench_timing *t)
{
    if (t->median < 0.8 * t->wall_median)
        fprintf(stderr, "ch09_embree: %s,%s: CPU %.0f ns but wall %.0f ns: other threads?\n",
                c->method, c->param, t->median, t->wall_median);
}

static long disagreements(const float *a, const float *b, int n)
{
    long count = 0;
    for (int k = 0; k < n; k++) {
        bool hit_a = isfinite(a[k]), hit_b = isfinite(b[k]);
        count += hit_a != hit_b || (hit_a && fabsf(a[k] - b[k]) > 1e-5f * b[k]);
    }
    return count;
}

/* One untimed pass of both programs over c's rays: the hits, distances and
 * disagreements. */
static void print_agreement(const trace_ctx *c, const char *name)
{
    float *a = malloc((size_t)N_RAYS * sizeof *a), *b = malloc((size_t)N_RAYS * sizeof *b);
    long hits_a = 0, hits_b = 0;
    double sum_a = 0, sum_b = 0;
    if (!a || !b)
        exit(1);
    render_stats stats = {0};
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (long k = 0; k < N_RAYS; k++) {
        double ta = kdtree_ray(c, k, &stats), tb = embree_ray(c, k, &context);
        a[k] = (float)ta, b[k] = (float)tb; /* compared in float, as Embree's */
        hits_a += ta < INFINITY, hits_b += tb < INFINITY;
        sum_a += ta < INFINITY ? ta : 0, sum_b += tb < INFINITY ? tb : 0;
    }
    printf("hits,%s,0,%ld,kdtree_hits\nhits,%s,0,%ld,embree_hits\n", name, hits_a, name, hits_b);
    printf("hits,%s,0,%ld,rays_that_disagree\n", name, disagreements(a, b, N_RAYS));
    printf("distance,%s,0,%.6f,kdtree_sum_t\ndistance,%s,0,%.6f,embree_sum_t\n", name, sum_a,
           name, sum_b);
    free(a), free(b);
}

/* The rays of both programs: rows of the timings t of the cases c. */
static void print_rays(const bench_case *c, const bench_timing *t)
{
    bench_row(c[0].method, c[0].param, &t[0], "%.4f", 1e3 / t[0].median, "mrays_per_s");
    bench_row(c[1].method, c[1].param, &t[1], "%.4f", 1e3 / t[1].median, "mrays_per_s");
    printf("ratio,%s,0,%.4f,kdtree_over_embree\n", c[0].param, t[1].median / t[0].median);
}

static void print_builds(const bench_case *c, const bench_timing *t)
{
    bench_row(c[0].method, c[0].param, &t[0], "%.3f", t[0].median / 1e6, "build_ms");
    bench_row(c[1].method, c[1].param, &t[1], "%.3f", t[1].median / 1e6, "build_ms");
    printf("build,%s,0,%.4f,build_kdtree_over_embree\n", c[0].param, t[0].median / t[1].median);
}

/* ---------------------------------------------------------------- main */

static const char *NAMES[N_MESHES] = {"bunny", "teapot"};

/* The builds of both meshes by both programs, interleaved. */
static void time_builds(const mesh *meshes, RTCDevice device, bench_timing *t,
                        bench_case *c)
{
    static build_ctx ctx[2 * N_MESHES];
    for (int k = 0; k < N_MESHES; k++) {
        ctx[2 * k] = (build_ctx){&meshes[k], NULL};
        ctx[2 * k + 1] = (build_ctx){&meshes[k], device};
        c[2 * k] = (bench_case){"kdtree-build", NAMES[k], run_kdtree_build, &ctx[2 * k], 1};
        c[2 * k + 1] =
            (bench_case){"embree-build", NAMES[k], run_embree_build, &ctx[2 * k + 1], 1};
    }
    bench_time_cases(c, 2 * N_MESHES, t);
    for (int k = 0; k < 2 * N_MESHES; k++)
        check_own_thread(&c[k], &t[k]);
}

enum { N_TRACES = N_MESHES * N_K };

/* The rays of every mesh and K by both programs, interleaved; case 2 j is
 * ours and 2 j + 1 Embree's for trace j = mesh N_K + K's index. */
static void time_rays(const trace_ctx *ctx, char names[][32], bench_timing *t, bench_case *c)
{
    for (int j = 0; j < N_TRACES; j++) {
        void *x = (void *)&ctx[j];
        c[2 * j] = (bench_case){"kdtree", names[j], run_kdtree, x, N_RAYS};
        c[2 * j + 1] = (bench_case){"embree", names[j], run_embree, x, N_RAYS};
    }
    bench_time_cases(c, 2 * N_TRACES, t);
    for (int k = 0; k < 2 * N_TRACES; k++)
        check_own_thread(&c[k], &t[k]);
}

int main(int argc, char **argv)
{
    const char *paths[N_MESHES] = {argc > 1 ? argv[1] : "meshes/bunny.obj",
                                   argc > 2 ? argv[2] : "meshes/teapot-8.obj"};
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        fprintf(stderr, "ch09_embree: Embree has no device\n");
        return 1;
    }
    mesh meshes[N_MESHES];
    RTCScene scenes[N_MESHES];
    for (int k = 0; k < N_MESHES; k++)
        load_float_mesh(paths[k], &meshes[k]);
    bench_case build_cases[2 * N_MESHES], ray_cases[2 * N_TRACES];
    bench_timing builds[2 * N_MESHES], rays[2 * N_TRACES];
    time_builds(meshes, device, builds, build_cases);
    trace_ctx ctx[N_TRACES];
    char names[N_TRACES][32];
    for (int k = 0; k < N_MESHES; k++) {
        kdtree_params p = kdtree_default_params();
        if (!mesh_build_tree(&meshes[k], &p))
            return 1;
        scenes[k] = embree_scene(device, &meshes[k]);
        rtcCommitScene(scenes[k]);
        for (int i = 0; i < N_K; i++) {
            int j = k * N_K + i;
            ctx[j] = (trace_ctx){&meshes[k], scenes[k], make_rays(&meshes[k], K_VALUES[i], SIDE)};
            snprintf(names[j], sizeof names[j], "%s-%.1f", NAMES[k], K_VALUES[i]);
        }
    }
    time_rays(ctx, names, rays, ray_cases);
    bench_print_machine();
    bench_csv_header();
    for (int k = 0; k < N_MESHES; k++) {
        print_builds(&build_cases[2 * k], &builds[2 * k]);
        for (int i = 0; i < N_K; i++) {
            int j = k * N_K + i;
            print_rays(&ray_cases[2 * j], &rays[2 * j]);
            print_agreement(&ctx[j], names[j]);
            free((void *)ctx[j].rays);
        }
        rtcReleaseScene(scenes[k]);
        mesh_free(&meshes[k]);
    }
    rtcReleaseDevice(device);
    return 0;
}
