/* ch08_embree.c: this program's kd-tree against Intel Embree 3, on the same
 * rays, one thread each, in turns.
 *
 *   build/rel/bench/ch08_embree [BUNNY.obj TEAPOT.obj] > figures/ch08-embree.csv
 *
 * Built only where Embree 3 is installed (Debian: libembree-dev); without
 * it, `make charts` draws the chart from this program's own rates and
 * says that Embree was absent.
 *
 * For the Stanford bunny and the teapot, at K = 1 and K = 2.5, the
 * 1024 x 1024 rays of ch08_rays.h are traced by closest hit, by
 * mesh_nearest (the renderer's kd-tree) and by rtcIntersect1 (Embree's
 * BVH, built with RTC_BUILD_QUALITY_HIGH, a device with threads=1), in
 * ROUNDS rounds, each program tracing all the rays in turn, so that a
 * slow spell of the machine hits both. The builds are timed the same way,
 * BUILDS times each. Rows (method,param,ns_per_op,error,error_kind):
 *
 *   kdtree|embree,MESH-K,ns_per_ray,Mrays/s,mrays_per_s       (the median
 *       round; _min and _max: the slowest and the fastest round)
 *   ratio,MESH-K,0,kdtree rate / embree rate,kdtree_over_embree (median of
 *       the rounds' ratios; _min, _max)
 *   hits,MESH-K,0,count,kdtree_hits|embree_hits|rays_that_disagree
 *       (a ray disagrees when one program hits and the other does not,
 *       or both hit at distances more than 1e-5 apart, relatively)
 *   distance,MESH-K,0,sum of the hits' t,kdtree_sum_t|embree_sum_t
 *   build,MESH,ms,ms,kdtree_build_ms|embree_build_ms (medians)
 *   build,MESH,0,kdtree / embree,build_kdtree_over_embree */
#include <embree3/rtcore.h>
#include <string.h>

#include "ch08_rays.h"

enum { SIDE = 1024, ROUNDS = 7, BUILDS = 5 };

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

static batch trace_embree(RTCScene scene, const float_ray *rays, int n, float *t_out)
{
    batch b = {0, 0, 0};
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    double start = cpu_seconds();
    for (int k = 0; k < n; k++) {
        struct RTCRayHit rh;
        const float_ray *r = &rays[k];
        rh.ray.org_x = r->o[0], rh.ray.org_y = r->o[1], rh.ray.org_z = r->o[2];
        rh.ray.dir_x = r->d[0], rh.ray.dir_y = r->d[1], rh.ray.dir_z = r->d[2];
        rh.ray.tnear = 0, rh.ray.tfar = INFINITY;
        rh.ray.mask = 0xffffffffu, rh.ray.flags = 0, rh.ray.time = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        b.hits += hit;
        b.sum_t += hit ? rh.ray.tfar : 0;
        if (t_out)
            t_out[k] = hit ? rh.ray.tfar : INFINITY;
    }
    b.seconds = cpu_seconds() - start;
    return b;
}

/* ---------------------------------------------------------------- builds */

static double median_build_ms(const mesh *m, RTCDevice device)
{
    double ms[BUILDS];
    for (int b = 0; b < BUILDS; b++) {
        double start = cpu_seconds();
        if (device == NULL) {
            mesh copy = *m; /* the tree is built into a copy's members */
            copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
            kdtree_params p = kdtree_default_params();
            if (!mesh_build_tree(&copy, &p))
                exit(1);
            ms[b] = 1e3 * (cpu_seconds() - start);
            kdtree_free(&copy.tree);
            free(copy.leaf_corners);
        } else {
            RTCScene scene = embree_scene(device, m);
            rtcCommitScene(scene);
            ms[b] = 1e3 * (cpu_seconds() - start);
            rtcReleaseScene(scene);
        }
    }
    return median_of(ms, BUILDS);
}

/* ---------------------------------------------------------------- one case */

static void print_rates(const char *method, const char *name, const double *rate)
{
    double r[ROUNDS];
    memcpy(r, rate, sizeof r);
    double mid = median_of(r, ROUNDS);
    printf("%s,%s,%.2f,%.4f,mrays_per_s\n", method, name, 1e3 / mid, mid);
    printf("%s,%s,%.2f,%.4f,mrays_per_s_min\n", method, name, 1e3 / r[0], r[0]);
    printf("%s,%s,%.2f,%.4f,mrays_per_s_max\n", method, name, 1e3 / r[ROUNDS - 1],
           r[ROUNDS - 1]);
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

static void compare(const mesh *m, RTCScene scene, const char *mesh_name, double K)
{
    int n = SIDE * SIDE;
    float_ray *rays = make_rays(m, K, SIDE);
    float *t_ours = malloc((size_t)n * sizeof *t_ours), *t_embree = malloc((size_t)n * sizeof *t_embree);
    double ours[ROUNDS], theirs[ROUNDS], ratio[ROUNDS];
    batch a = {0, 0, 0}, b = {0, 0, 0};
    for (int round = 0; round < ROUNDS; round++) {
        a = trace_kdtree(m, rays, n, round == 0 ? t_ours : NULL);
        b = trace_embree(scene, rays, n, round == 0 ? t_embree : NULL);
        ours[round] = 1e-6 * n / a.seconds, theirs[round] = 1e-6 * n / b.seconds;
        ratio[round] = ours[round] / theirs[round];
    }
    char name[64];
    snprintf(name, sizeof name, "%s-%.1f", mesh_name, K);
    print_rates("kdtree", name, ours);
    print_rates("embree", name, theirs);
    double mid = median_of(ratio, ROUNDS);
    printf("ratio,%s,0,%.4f,kdtree_over_embree\n", name, mid);
    printf("ratio,%s,0,%.4f,kdtree_over_embree_min\n", name, ratio[0]);
    printf("ratio,%s,0,%.4f,kdtree_over_embree_max\n", name, ratio[ROUNDS - 1]);
    printf("hits,%s,0,%ld,kdtree_hits\nhits,%s,0,%ld,embree_hits\n", name, a.hits, name, b.hits);
    printf("hits,%s,0,%ld,rays_that_disagree\n", name, disagreements(t_ours, t_embree, n));
    printf("distance,%s,0,%.6f,kdtree_sum_t\ndistance,%s,0,%.6f,embree_sum_t\n", name, a.sum_t,
           name, b.sum_t);
    free(rays), free(t_ours), free(t_embree);
}

int main(int argc, char **argv)
{
    const char *paths[2] = {argc > 1 ? argv[1] : "meshes/bunny.obj",
                            argc > 2 ? argv[2] : "meshes/teapot-8.obj"};
    const char *names[2] = {"bunny", "teapot"};
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        fprintf(stderr, "ch08_embree: Embree has no device\n");
        return 1;
    }
    printf("method,param,ns_per_op,error,error_kind\n");
    for (int k = 0; k < 2; k++) {
        mesh m;
        load_float_mesh(paths[k], &m);
        double ours = median_build_ms(&m, NULL), theirs = median_build_ms(&m, device);
        printf("build,%s,%.3f,%.3f,kdtree_build_ms\n", names[k], ours, ours);
        printf("build,%s,%.3f,%.3f,embree_build_ms\n", names[k], theirs, theirs);
        printf("build,%s,0,%.4f,build_kdtree_over_embree\n", names[k], ours / theirs);
        kdtree_params p = kdtree_default_params();
        if (!mesh_build_tree(&m, &p))
            return 1;
        RTCScene scene = embree_scene(device, &m);
        rtcCommitScene(scene);
        compare(&m, scene, names[k], 1.0);
        compare(&m, scene, names[k], 2.5);
        rtcReleaseScene(scene);
        mesh_free(&m);
        fflush(stdout);
    }
    rtcReleaseDevice(device);
    return 0;
}
