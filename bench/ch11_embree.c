/* ch11_embree.c: every step of chapters 9 to 11 against Intel Embree 3, on the
 * same rays, one thread each, timed together.
 *
 *   build/rel/bench/ch11_embree [BUNNY.obj TEAPOT.obj] > figures/ch11-embree.csv
 *
 * A quick look (not the chart's CSV): CH11_QUICK=1 traces the bunny at
 * K = 1 alone; CH11_METHODS="bvh4 bvh8-noavx2" times only the methods it
 * names (and no builds); BENCH_ROUNDS sets the rounds (bench/timing.h).
 *
 * Built only where Embree 3 is installed (Debian: libembree-dev); without
 * it, `make charts` draws the chart from chapter 8's rates alone and says
 * that Embree was absent.
 *
 * The meshes: the Stanford bunny, the teapot, the bunny cut into four
 * times as many triangles ("scanned", ch09_meshes.h), and two meshes
 * where a BVH is weak: 4,000 needles across a cube and a cylinder of
 * 4,000 slivers. For each, at K = 1 and K = 2.5 (the failure meshes at
 * K = 1 only, and 256 x 256 rays), the 1024 x 1024 rays of ch08_rays.h
 * are traced by closest
 * hit by every method of METHODS:
 *   kdtree-ch08  chapter 8's kd-tree with chapter 8's leaves (chapter 4's
 *                test called once a triangle, triangle_hit_prepared);
 *   kdtree       the same tree with chapter 10's tightened leaves;
 *   bvh4-double  the BVH 4 wide as first built: leaves of triangles in
 *                double, every one tested (chapter 10's tightened leaves);
 *   bvh4-double-mesh  the same, the corners read from the mesh through
 *                the triangles' indices instead of a copy;
 *   bvh2|4|8     the BVH, binary, 4 and 8 wide, with leaves of packets;
 *   bvh4-noavx2, bvh8-noavx2  the 4- and 8-wide BVHs with the walk kept
 *                from AVX2 (bvh_allow_avx2(false) when built): the
 *                build's own instructions;
 *   bvh8-avx2    the 8-wide BVH with the walk kept to AVX2
 *                (bvh_allow_avx512(false)): where the processor has
 *                AVX-512VL, the walk without its registers and compress;
 *   fast-avx2    the float path (fast, below) kept to AVX2 likewise;
 *                these four timed only in the widths' group: bvh4, bvh8,
 *                fast and these alone, on the bunny and the teapot at
 *                K = 1, as MESH-1.0-widths;
 *   embree       rtcIntersect1 (Embree's BVH, RTC_BUILD_QUALITY_HIGH, its
 *                spatial-split builder, a device with threads=1; the
 *                scene without RTC_SCENE_FLAG_ROBUST, as Embree's
 *                default: its faster, not watertight, traversal);
 *   embree-medium  the same at RTC_BUILD_QUALITY_MEDIUM, Embree's default
 *                build (binned SAH, no spatial splits);
 *   fast         the BVH of the default width, its leaves decided in float
 *                alone (accelerator bvh-float): not the exact answers;
 * and by any hit (shadow rays, to infinity): kdtree-any, bvh-any (the
 * default width), fast-any and embree-any (rtcOccluded1). Times come from the
 * harness (bench/timing.h): one operation is one ray, every batch whole
 * passes over the rays, and all the cases of one mesh are timed together,
 * interleaved, in thread CPU time. The builds (kdtree-build, bvh-build on
 * one thread, embree-build) are timed the same way, per mesh. The hits
 * come from one untimed pass of each method.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns),
 * after the "# machine:" line:
 *   METHOD-build,MESH,ns_per_build,ms,build_ms,q1,q3,wall
 *   METHOD,MESH-K,ns_per_ray,Mrays/s,mrays_per_s,q1,q3,wall
 *   ratio,METHOD@MESH-K,0,its rate / Embree's,over_embree  (medians; the
 *       exact BVH of the default width again as METHOD default)
 *   ratio,METHOD-build@MESH,0,its time / Embree's,build_over_embree
 *   hits,MESH-K,0,count,rays  (traced by each method)
 *   hits,MESH-K,0,count,METHOD_hits
 *   hits,MESH-K,0,mean,METHOD_nodes_per_ray  (a BVH's: nodes whose children
 *       a ray tested, and the triangles of the leaves it met, a ray)
 *   hits,MESH-K,0,mean,METHOD_leaf_triangles_per_ray
 *   hits,MESH-K,0,count,METHOD_disagrees_with_kdtree  (a ray one hits and
 *       the other does not, or a different t, bit for bit)
 *   hits,MESH-K,0,count,rays_that_disagree  (bvh against embree: one hits
 *       and the other not, or distances more than 1e-5 apart, relatively)
 *   hits,MESH-K,0,count,METHOD_other_answers  (fast, embree, embree-medium
 *       against the exact answers, the kd-tree's: a ray one hits and the
 *       other not, or a different triangle)
 *   hits,MESH-K,0,error,METHOD_largest_t_error  (their largest relative
 *       difference of t from the exact one, over the rays where both hit
 *       the same triangle: another triangle counts as another answer)
 *   METHOD,bunny-1.0/KIND,ns_per_ray,...  and  ratio,METHOD@bunny-1.0/KIND
 *       (the bunny's rays at K = 1 of one kind, timed apart: KIND miss-box,
 *       the rays that miss the mesh's box; enter-miss, those that enter it
 *       and hit nothing; hit, those that hit; by the default BVH, fast,
 *       embree and embree-medium), with hits,bunny-1.0/KIND,0,COUNT,rays
 *   vector,WIDTH_NAME,0,0,bvh_vector_width  (the node test's instructions)
 *   default,bvhN,0,0,default_method  (the program's default: N wide, where
 *       bvh-any, fast and fast-any are N wide as well) */
#include <embree3/rtcore.h>
#include <string.h>

#include "ch09_meshes.h"
#include "embree_scene.h"
#include "timing.h"

/* The rays a side of the image: the failure meshes, where a ray costs
 * microseconds, get a sixteenth as many. */
enum { SIDE = 1024, FAILURE_SIDE = 256 };

/* ---------------------------------------------------------------- Embree */

/* ---------------------------------------------------------------- the methods */

typedef enum { KDTREE_CH08, KDTREE, BVH, BVH_DOUBLE, BVH_DOUBLE_MESH, EMBREE } kind;

typedef struct {
    const char *name;
    kind kind;
    int width; /* of a BVH; 0: the program's default (default_width) */
    bool any;  /* shadow rays: any hit */
    bool medium; /* Embree: its default build, MEDIUM, not HIGH */
    bool in_float; /* the BVH's leaves decided in float alone */
    bool no_avx2;  /* the walk kept from AVX2 (bvh_allow_avx2(false)) */
    bool no_avx512; /* the walk kept to AVX2 (bvh_allow_avx512(false)) */
} method;

static const method METHODS[] = {
    {"kdtree-ch08", KDTREE_CH08, 0, false, false, false, false, false},
    {"kdtree", KDTREE, 0, false, false, false, false, false},
    {"bvh4-double", BVH_DOUBLE, 4, false, false, false, false, false},
    {"bvh4-double-mesh", BVH_DOUBLE_MESH, 4, false, false, false, false, false},
    {"bvh2", BVH, 2, false, false, false, false, false},
    {"bvh4", BVH, 4, false, false, false, false, false},
    {"bvh8", BVH, 8, false, false, false, false, false},
    {"bvh4-noavx2", BVH, 4, false, false, false, true, false},
    {"bvh8-noavx2", BVH, 8, false, false, false, true, false},
    {"bvh8-avx2", BVH, 8, false, false, false, false, true},
    {"fast", BVH, 0, false, false, true, false, false},
    {"fast-avx2", BVH, 0, false, false, true, false, true},
    {"embree", EMBREE, 0, false, false, false, false, false},
    {"embree-medium", EMBREE, 0, false, true, false, false, false},
    {"kdtree-any", KDTREE, 0, true, false, false, false, false},
    {"bvh-any", BVH, 0, true, false, false, false, false},
    {"fast-any", BVH, 0, true, false, true, false, false},
    {"embree-any", EMBREE, 0, true, false, false, false, false},
};
enum { N_METHODS = sizeof METHODS / sizeof METHODS[0] };

/* The width of how's BVH: its own, or the program's default (eight). */
static int width_of(const method *how)
{
    return how->width ? how->width : bvh_default_params().width;
}

/* Is how the program's default: the exact BVH of the default width? */
static bool is_default(const method *how)
{
    return how->kind == BVH && !how->any && !how->in_float && !how->no_avx2 &&
           !how->no_avx512 && width_of(how) == bvh_default_params().width;
}

/* A mesh and everything built over it: its kd-tree (in m), a copy of it
 * for each BVH width, and Embree's scene. */
typedef struct {
    const char *name;
    mesh m;
    mesh bvh_of_width[9]; /* [2], [4], [8] */
    mesh bvh_no_avx2_of_width[9]; /* [4], [8]: walked with the build's own lanes */
    mesh bvh_avx2_only;   /* 8 wide, walked with AVX2 at most */
    mesh bvh_avx2_float;  /* the same, decided in float */
    mesh bvh_float;       /* the default width's, decided in float */
    mesh bvh_double;      /* 4 wide, leaves of doubles: see double_leaves */
    triangle_corners *corners; /* bvh_double's, lane by lane */
    int *lane_items;           /* the triangle of each lane */
    RTCScene scene, scene_medium; /* HIGH, MEDIUM */
    bool few_methods; /* the failure meshes: kdtree, bvh4, embree */
} subject;

/* What one case traces: a method over a subject's rays of one K. */
typedef struct {
    const method *how;
    const subject *s;
    const float_ray *rays;
    long n_rays;
} trace_ctx;

/* Chapter 8's leaves: chapter 4's test for each triangle, keeping the tie
 * rule across leaves (a hit at t_max itself wins for a lower index). */
static int chapter8_leaf(const watertight_ray *w, const triangle_corners *c,
                         const int *items, int count, double t_min, double t_max,
                         int best, triangle_hit *out)
{
    int nearest = -1;
    double reach = nextafter(t_max, INFINITY);
    for (int k = 0; k < count; k++) {
        triangle_hit th;
        if (triangle_hit_prepared(w, c[k].p[0], c[k].p[1], c[k].p[2], t_min, reach, &th) &&
            (th.t < t_max || items[k] < best)) {
            *out = th, t_max = th.t, best = items[k], nearest = k;
            reach = nextafter(t_max, INFINITY);
        }
    }
    return nearest;
}

/* Chapter 8's kd-tree walk with chapter 8's leaves: the nearest t, or
 * infinity. */
static double chapter8_ray(const mesh *m, const mesh_ray *mr)
{
    double near = 0, far = INFINITY, t_max = INFINITY;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return INFINITY;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    kdtree_walk w;
    kdtree_leaf leaf;
    int found = -1;
    triangle_hit th;
    kdtree_walk_start(&w, &m->tree, mr->r.origin, mr->inv_dir, near, far);
    while (kdtree_walk_next(&w, t_max, &leaf)) {
        int k = chapter8_leaf(&shear, m->leaf_corners + leaf.first,
                              m->tree.items + leaf.first, leaf.count, 0, t_max, found, &th);
        if (k >= 0)
            found = m->tree.items[leaf.first + k], t_max = th.t;
    }
    return t_max;
}

/* The BVH's walk with the leaves of the BVH's first form: every triangle
 * of a leaf tested by chapter 4's test in double, on corners copied leaf
 * by leaf (chapter 8's leaves, tightened), in a tree built for them
 * (items counted one by one). The nearest t, or infinity. */
/* A leaf of double_leaves_ray with the corners read from the mesh through
 * the lanes' triangles (no copy): chapter 8's tie rule. */
static int mesh_corners_leaf(const mesh *m, const watertight_ray *w, const int *items,
                             int count, double t_max, int best, triangle_hit *out)
{
    int nearest = -1;
    double reach = nextafter(t_max, INFINITY);
    for (int k = 0; k < count; k++) {
        triangle_hit th;
        const int *v = m->triangles[items[k]].v;
        if (triangle_hit_prepared(w, m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]],
                                  0, reach, &th) &&
            (th.t < t_max || items[k] < best)) {
            *out = th, t_max = th.t, best = items[k], nearest = k;
            reach = nextafter(t_max, INFINITY);
        }
    }
    return nearest;
}

/* The walk of search_bvh8 (chapter 11) with these leaves, its nodes
 * tested with AVX2 when avx2, as the program's own walk tests them. */
BVH_INLINE double double_leaves_walk(const subject *s, const mesh_ray *mr, bool from_mesh,
                                     bool avx2)
{
    const mesh *m = &s->bvh_double;
    double t_max = INFINITY, near = 0, far = INFINITY;
    bvh_ray r;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far) ||
        !bvh_ray_of(mr->r.origin, mr->inv_dir, 0, INFINITY, &r))
        return INFINITY;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    unsigned shift = bvh_walk_rows(&r);
    bvh_ray8 v = bvh_ray8_of(&r);
    bvh_ray8_fused(&v, &r); /* the AVX2 test's crossings */
    uint32_t stack[BVH_STACK8], now = 0; /* the root */
    float entry[BVH_STACK8], bound = r.t_max;
    int top = 0, found = -1;
    triangle_hit th;
    for (;;) { /* chapter 11's walk (search_bvh8), its leaves these */
        if (!(now & BVH_LEAF)) {
            const bvh_node8 *n = &m->bvh.nodes8[now];
            float t_near[8];
            int32_t met[8];
            unsigned hit = avx2 ? bvh_node8_lanes_avx2(n, &v, bound, t_near, met)
                                : bvh_node8_test(n, &r, bound, t_near);
            if (hit != 0) {
                if (avx2)
                    top = bvh_push8_avx2(stack, entry, top, n, met, t_near, shift, &now) - 1;
                else {
                    top = bvh_push8(stack, entry, top, n, hit, t_near, shift);
                    now = stack[--top];
                }
                continue;
            }
        } else {
            int first = (int)(now & BVH_FIRST_MASK) * PACKET_W; /* a lane */
            int count = (int)(now >> BVH_COUNT_SHIFT & 15);
            int k = from_mesh ? mesh_corners_leaf(m, &shear, s->lane_items + first,
                                                  count, t_max, found, &th)
                              : triangle_nearest_of_leaf(&shear, s->corners + first,
                                                         s->lane_items + first, count, 0,
                                                         t_max, found, &th);
            if (k >= 0) {
                found = s->lane_items[first + k], t_max = th.t;
                float b = bvh_float_up(t_max * (1 + BVH_SLACK));
                bound = b < r.t_max ? b : r.t_max;
            }
        }
        while (top > 0 && !(entry[top - 1] <= bound))
            top--;
        if (top == 0)
            break;
        now = stack[--top];
    }
    return t_max;
}

BVH_AVX2_TARGET __attribute__((flatten)) static double
double_leaves_avx2(const subject *s, const mesh_ray *mr, bool from_mesh)
{
    return double_leaves_walk(s, mr, from_mesh, true);
}

static double double_leaves_plain(const subject *s, const mesh_ray *mr, bool from_mesh)
{
    return double_leaves_walk(s, mr, from_mesh, false);
}

/* The double leaves' walk, with AVX2 where the program's walk takes it. */
static double double_leaves_ray(const subject *s, const mesh_ray *mr, bool from_mesh)
{
    return s->bvh_double.bvh.avx2 ? double_leaves_avx2(s, mr, from_mesh)
                                  : double_leaves_plain(s, mr, from_mesh);
}

/* Ray k by Embree: its distance, or infinity (any: 0 for a hit); the
 * triangle hit in *triangle (-1: none), unless NULL. */
static double embree_ray(const trace_ctx *c, long k, struct RTCIntersectContext *context,
                         int *triangle)
{
    const float_ray *f = &c->rays[k];
    RTCScene scene = c->how->medium ? c->s->scene_medium : c->s->scene;
    struct RTCRayHit rh;
    rh.ray.org_x = f->o[0], rh.ray.org_y = f->o[1], rh.ray.org_z = f->o[2];
    rh.ray.dir_x = f->d[0], rh.ray.dir_y = f->d[1], rh.ray.dir_z = f->d[2];
    rh.ray.tnear = 0, rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xffffffffu, rh.ray.flags = 0, rh.ray.time = 0;
    if (c->how->any) {
        rtcOccluded1(scene, context, &rh.ray);
        return rh.ray.tfar < 0 ? 0 : INFINITY; /* -inf marks a hit */
    }
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, context, &rh);
    bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    if (triangle != NULL)
        *triangle = hit ? (int)rh.hit.primID : -1;
    return hit ? rh.ray.tfar : INFINITY;
}

/* Ray k by one of ours: its distance, or infinity (any: 0 for a hit);
 * the triangle hit in *triangle where the method says (else -1), unless
 * NULL. */
static double our_ray(const trace_ctx *c, long k, render_stats *stats, int *triangle)
{
    const mesh *m = c->how->kind != BVH ? &c->s->m
                    : c->how->in_float  ? (c->how->no_avx512 ? &c->s->bvh_avx2_float
                                                             : &c->s->bvh_float)
                    : c->how->no_avx2   ? &c->s->bvh_no_avx2_of_width[width_of(c->how)]
                    : c->how->no_avx512 ? &c->s->bvh_avx2_only
                                        : &c->s->bvh_of_width[width_of(c->how)];
    if (triangle != NULL)
        *triangle = -1;
    mesh_ray mr = mesh_ray_of(ray_of(&c->rays[k]));
    if (c->how->kind == KDTREE_CH08)
        return chapter8_ray(m, &mr);
    if (c->how->kind == BVH_DOUBLE || c->how->kind == BVH_DOUBLE_MESH)
        return double_leaves_ray(c->s, &mr, c->how->kind == BVH_DOUBLE_MESH);
    if (c->how->any)
        return mesh_occluded(m, &mr, 0, INFINITY, stats) ? 0 : INFINITY;
    triangle_hit th;
    int found = mesh_nearest(m, &mr, 0, INFINITY, &th, stats);
    if (triangle != NULL)
        *triangle = found;
    return found >= 0 ? th.t : INFINITY;
}

/* reps rays, whole passes over the rays (the harness's cycle). */
static void run_rays(void *ctx, long reps)
{
    const trace_ctx *c = ctx;
    render_stats stats = {0}; /* once a batch, as the renderer's once a band */
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    double sum = 0;
    for (long k = 0; k < reps; k++)
        sum += (c->how->kind == EMBREE ? embree_ray(c, k % c->n_rays, &context, NULL)
                                       : our_ray(c, k % c->n_rays, &stats, NULL)) < INFINITY;
    bench_sink += sum;
}

/* ---------------------------------------------------------------- the builds */

typedef struct {
    const mesh *m;
    RTCDevice device;
    kind kind;
    enum RTCBuildQuality quality; /* Embree's */
} build_ctx;

static void run_build(void *ctx, long reps)
{
    const build_ctx *c = ctx;
    for (long r = 0; r < reps; r++) {
        if (c->kind == EMBREE) {
            RTCScene scene = embree_scene(c->device, c->m, c->quality);
            rtcCommitScene(scene);
            rtcReleaseScene(scene);
            continue;
        }
        mesh copy = *c->m; /* the tree is built into a copy's members */
        copy.tree = (kdtree){0}, copy.leaf_corners = NULL;
        copy.bvh = (bvh){0}, copy.bvh_packets = NULL;
        kdtree_params kp = kdtree_default_params();
        bvh_params bp = {0}; /* zeros: the mesh's defaults, on one thread */
        if (!(c->kind == KDTREE ? mesh_build_tree(&copy, &kp) : mesh_build_bvh(&copy, &bp)))
            exit(1);
        bench_sink += copy.triangle_count;
        mesh_free_tree(&copy);
    }
}

static void time_builds(const subject *s, RTCDevice device)
{
    enum { N = 4, YARDSTICK = 2 };
    const char *names[N] = {"kdtree-build", "bvh-build", "embree-build",
                            "embree-medium-build"};
    const kind kinds[N] = {KDTREE, BVH, EMBREE, EMBREE};
    build_ctx ctx[N];
    bench_case c[N];
    bench_timing t[N];
    for (int k = 0; k < N; k++) {
        ctx[k] = (build_ctx){&s->m, device, kinds[k],
                             k == 3 ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH};
        c[k] = (bench_case){names[k], s->name, run_build, &ctx[k], 1};
    }
    bench_time_cases(c, N, t);
    for (int k = 0; k < N; k++)
        bench_row(c[k].method, s->name, &t[k], "%.3f", t[k].median / 1e6, "build_ms");
    for (int k = 0; k < N; k++)
        if (k != YARDSTICK)
            printf("ratio,%s@%s,0,%.4f,build_over_embree\n", names[k], s->name,
                   t[k].median / t[YARDSTICK].median);
    fflush(stdout);
}

/* ---------------------------------------------------------------- the rows */

/* Is how among the methods that $CH11_METHODS names (a list of names
 * separated by spaces), or is $CH11_METHODS unset? For a quick look. */
static bool is_chosen(const method *how)
{
    const char *list = getenv("CH11_METHODS");
    if (list == NULL)
        return true;
    size_t n = strlen(how->name);
    for (const char *at = strstr(list, how->name); at != NULL; at = strstr(at + 1, how->name))
        if ((at == list || at[-1] == ' ') && (at[n] == '\0' || at[n] == ' '))
            return true;
    return false;
}

/* The methods of the widths' own group: the exact BVH 4 and 8 wide, with
 * the widest instructions and kept from them, and the float path with and
 * without AVX-512VL, timed apart from the rest (a close comparison). */
static bool in_widths(const method *how)
{
    return how->kind == BVH && !how->any && (how->in_float || how->width >= 4);
}

static bool is_used(const subject *s, const method *how, bool widths)
{
    if (!is_chosen(how))
        return false;
    if (widths || how->no_avx2 || how->no_avx512)
        return widths && in_widths(how);
    return !s->few_methods || how->kind == EMBREE ||
           (how->kind == KDTREE && !how->any) ||
           (how->kind == BVH && !how->no_avx2 && !how->no_avx512 &&
            width_of(how) == bvh_default_params().width);
}

/* Where method j's answers are not the exact ones (the kd-tree's, kd): a
 * ray that one hits and the other does not, or that they see hit
 * different triangles; and the largest relative difference of their t
 * over the rays where both hit the same triangle (the others are
 * counted apart, as other answers). */
static void print_inexactness(const trace_ctx *c, int j, int kd, double *const t[],
                              int *const id[], const char *param)
{
    long n_rays = c[0].n_rays, other = 0;
    double largest = 0;
    for (long k = 0; k < n_rays; k++) {
        double a = t[j][k], b = t[kd][k];
        if (id[j][k] != id[kd][k]) {
            other++;
            continue;
        }
        if (isfinite(a) && isfinite(b) && fabs(a - b) > largest * b)
            largest = fabs(a - b) / b;
    }
    printf("hits,%s,0,%ld,%s_other_answers\n", param, other, c[j].how->name);
    printf("hits,%s,0,%.3g,%s_largest_t_error\n", param, largest, c[j].how->name);
}

/* One untimed pass of every case over its rays: the hits, and where each
 * method disagrees with the kd-tree (ours) or with ours (Embree's); for
 * the float path and Embree, how far they are from the exact answers. */
static void print_agreement(const trace_ctx *c, int n, const char *param)
{
    long n_rays = c[0].n_rays;
    printf("hits,%s,0,%ld,rays\n", param, n_rays);
    double *t[N_METHODS];
    int *id[N_METHODS];
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    render_stats stats = {0};
    int kd = -1, ours = -1;
    for (int j = 0; j < n; j++) {
        long hits = 0;
        t[j] = malloc((size_t)n_rays * sizeof *t[j]);
        id[j] = malloc((size_t)n_rays * sizeof *id[j]);
        if (t[j] == NULL || id[j] == NULL)
            exit(1);
        for (long k = 0; k < n_rays; k++) {
            double d = c[j].how->kind == EMBREE ? embree_ray(&c[j], k, &context, &id[j][k])
                                                : our_ray(&c[j], k, &stats, &id[j][k]);
            t[j][k] = d, hits += d < INFINITY;
        }
        printf("hits,%s,0,%ld,%s_hits\n", param, hits, c[j].how->name);
        if (c[j].how->kind == BVH) /* what a ray of the walk visits */
            printf("hits,%s,0,%.2f,%s_nodes_per_ray\n"
                   "hits,%s,0,%.2f,%s_leaf_triangles_per_ray\n",
                   param, (double)stats.bvh_nodes / (double)n_rays, c[j].how->name, param,
                   (double)stats.triangle_tests / (double)n_rays, c[j].how->name);
        stats = (render_stats){0};
        kd = strcmp(c[j].how->name, "kdtree") == 0 ? j : kd;
        ours = is_default(c[j].how) ? j : ours;
    }
    for (int j = 0; j < n && kd >= 0; j++) {
        if (c[j].how->any || c[j].how->kind == EMBREE || c[j].how->in_float || j == kd)
            continue;
        long differ = 0;
        for (long k = 0; k < n_rays; k++) { /* as float, bit for bit */
            float a = (float)t[j][k], b = (float)t[kd][k];
            differ += memcmp(&a, &b, sizeof a) != 0;
        }
        printf("hits,%s,0,%ld,%s_disagrees_with_kdtree\n", param, differ, c[j].how->name);
    }
    for (int j = 0; j < n && kd >= 0; j++)
        if ((c[j].how->kind == EMBREE || c[j].how->in_float) && !c[j].how->any)
            print_inexactness(c, j, kd, t, id, param);
    for (int j = 0; j < n && ours >= 0; j++)
        if (c[j].how->kind == EMBREE && !c[j].how->any && !c[j].how->medium) {
            long differ = 0;
            for (long k = 0; k < n_rays; k++) {
                float a = (float)t[ours][k], b = (float)t[j][k];
                bool hit_a = isfinite(a), hit_b = isfinite(b);
                differ += hit_a != hit_b || (hit_a && fabsf(a - b) > 1e-5f * b);
            }
            printf("hits,%s,0,%ld,rays_that_disagree\n", param, differ);
        }
    for (int j = 0; j < n; j++)
        free(t[j]), free(id[j]);
}

static void print_rays(const trace_ctx *c, const bench_case *cases, const bench_timing *t, int n)
{
    for (int j = 0; j < n; j++)
        bench_row(cases[j].method, cases[j].param, &t[j], "%.4f", 1e3 / t[j].median,
                  "mrays_per_s");
    for (int j = 0; j < n; j++) {
        const char *yardstick = c[j].how->any ? "embree-any" : "embree";
        if (strcmp(c[j].how->name, yardstick) == 0)
            continue;
        for (int e = 0; e < n; e++)
            if (strcmp(c[e].how->name, yardstick) == 0)
                printf("ratio,%s@%s,0,%.4f,over_embree\n", c[j].how->name, cases[j].param,
                       t[e].median / t[j].median);
        if (is_default(c[j].how)) /* the program's default, named as such */
            for (int e = 0; e < n; e++)
                if (strcmp(c[e].how->name, yardstick) == 0)
                    printf("ratio,default@%s,0,%.4f,over_embree\n", cases[j].param,
                           t[e].median / t[j].median);
    }
}

/* The kind of ray f for s: 0, it misses the mesh's box; 1, it enters the
 * box and hits nothing; 2, it hits (the kd-tree's exact answer). */
static int kind_of(const subject *s, const float_ray *f)
{
    ray r = ray_of(f);
    mesh_ray mr = mesh_ray_of(r);
    double near = 0, far = INFINITY;
    if (!box_clip(&s->m.bounds, r.origin, mr.inv_dir, &near, &far))
        return 0;
    render_stats stats = {0};
    triangle_hit th;
    return mesh_nearest(&s->m, &mr, 0, INFINITY, &th, &stats) >= 0 ? 2 : 1;
}

/* Is how timed on each kind of ray apart: the default BVH, the float
 * path and Embree's two builds, by closest hit? */
static bool in_kinds(const method *how)
{
    return !how->any && (is_default(how) || strcmp(how->name, "fast") == 0 ||
                          how->kind == EMBREE);
}

/* The n rays of s at distance K sorted by kind, each kind timed apart by
 * the methods of in_kinds, as MESH-K/KIND (miss-box, enter-miss, hit). */
static void time_kinds(const subject *s, const float_ray *rays, long n, double K)
{
    static const char *const KINDS[] = {"miss-box", "enter-miss", "hit"};
    float_ray *kept = malloc((size_t)n * sizeof *kept);
    int *kind = malloc((size_t)n * sizeof *kind);
    if (kept == NULL || kind == NULL)
        exit(1);
    for (long k = 0; k < n; k++)
        kind[k] = kind_of(s, &rays[k]);
    for (int which = 0; which < 3; which++) {
        long count = 0;
        for (long k = 0; k < n; k++)
            if (kind[k] == which)
                kept[count++] = rays[k];
        char param[64];
        snprintf(param, sizeof param, "%s-%.1f/%s", s->name, K, KINDS[which]);
        trace_ctx c[N_METHODS];
        bench_case cases[N_METHODS];
        bench_timing t[N_METHODS];
        int m = 0;
        for (int j = 0; j < N_METHODS && count > 0; j++)
            if (in_kinds(&METHODS[j])) {
                c[m] = (trace_ctx){&METHODS[j], s, kept, count};
                cases[m] = (bench_case){METHODS[j].name, param, run_rays, &c[m], count};
                m++;
            }
        printf("hits,%s,0,%ld,rays\n", param, count);
        bench_time_cases(cases, m, t);
        print_rays(c, cases, t, m);
        fflush(stdout);
    }
    free(kept), free(kind);
}

/* Every method's rays of subject s at distance K, timed together (widths:
 * the widths' group alone, as MESH-K-widths). */
static void time_rays(const subject *s, double K, bool widths)
{
    char param[48];
    snprintf(param, sizeof param, "%s-%.1f%s", s->name, K, widths ? "-widths" : "");
    int side = s->few_methods ? FAILURE_SIDE : SIDE;
    long n_rays = (long)side * side;
    float_ray *rays = make_rays(&s->m, K, side);
    trace_ctx c[N_METHODS];
    bench_case cases[N_METHODS];
    bench_timing t[N_METHODS];
    int n = 0;
    for (int j = 0; j < N_METHODS; j++)
        if (is_used(s, &METHODS[j], widths)) {
            c[n] = (trace_ctx){&METHODS[j], s, rays, n_rays};
            cases[n] = (bench_case){METHODS[j].name, param, run_rays, &c[n], n_rays};
            n++;
        }
    bench_time_cases(cases, n, t);
    print_rays(c, cases, t, n);
    print_agreement(c, n, param);
    fflush(stdout);
    if (strcmp(s->name, "bunny") == 0 && K == 1.0 && !widths)
        time_kinds(s, rays, n_rays, K);
    free(rays);
}

/* ---------------------------------------------------------------- main */

/* s's BVH of the first form: items counted one by one, its leaves' corners
 * copied lane by lane of its packets (an empty lane's are never read). */
static void double_leaves(subject *s)
{
    mesh *copy = &s->bvh_double;
    *copy = s->m;
    copy->tree = (kdtree){0}, copy->leaf_corners = NULL;
    bvh_params bp = bvh_default_params();
    bp.width = 4, bp.item_group = 1;
    if (!mesh_build_bvh(copy, &bp))
        exit(1);
    size_t lanes = (size_t)copy->bvh_packet_count * PACKET_W;
    s->corners = calloc(lanes, sizeof *s->corners);
    s->lane_items = calloc(lanes, sizeof *s->lane_items);
    if (s->corners == NULL || s->lane_items == NULL)
        exit(1);
    for (size_t j = 0; j < lanes; j++) {
        int i = copy->bvh_packets[j / PACKET_W].triangle[j % PACKET_W];
        s->lane_items[j] = i;
        for (int c = 0; c < 3 && i >= 0; c++)
            s->corners[j].p[c] = copy->vertices[copy->triangles[i].v[c]];
    }
}

/* The walks a tree may take: every one, AVX2 at most, the build's own. */
typedef enum { WALK_WIDEST, WALK_AVX2, WALK_PLAIN } walk_limit;

/* *copy: m with a BVH of width w of its own, its walk chosen (when the
 * tree is built) within limit; exits when it cannot be built. */
static void bvh_copy(const mesh *m, mesh *copy, int w, walk_limit limit)
{
    *copy = *m;
    copy->tree = (kdtree){0}, copy->leaf_corners = NULL;
    bvh_params bp = {.width = w}; /* zeros: the mesh's defaults */
    bvh_allow_avx2(limit != WALK_PLAIN);
    bvh_allow_avx512(limit == WALK_WIDEST);
    bool built = mesh_build_bvh(copy, &bp);
    bvh_allow_avx2(true), bvh_allow_avx512(true);
    if (!built)
        exit(1);
}

static void prepare(subject *s, RTCDevice device)
{
    kdtree_params kp = kdtree_default_params();
    if (!mesh_build_tree(&s->m, &kp))
        exit(1);
    for (int w = 2; w <= 8; w *= 2)
        bvh_copy(&s->m, &s->bvh_of_width[w], w, WALK_WIDEST);
    for (int w = 4; w <= 8; w *= 2)
        bvh_copy(&s->m, &s->bvh_no_avx2_of_width[w], w, WALK_PLAIN);
    bvh_copy(&s->m, &s->bvh_avx2_only, 8, WALK_AVX2);
    s->bvh_avx2_float = s->bvh_avx2_only; /* shares its tree */
    s->bvh_avx2_float.bvh_in_float = true;
    s->bvh_float = s->bvh_of_width[bvh_default_params().width]; /* shared */
    s->bvh_float.bvh_in_float = true;
    double_leaves(s);
    s->scene = embree_scene(device, &s->m, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(s->scene);
    s->scene_medium = embree_scene(device, &s->m, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitScene(s->scene_medium);
}

static void release(subject *s)
{
    for (int w = 2; w <= 8; w *= 2)
        mesh_free_tree(&s->bvh_of_width[w]);
    mesh_free_tree(&s->bvh_double);
    for (int w = 4; w <= 8; w *= 2)
        mesh_free_tree(&s->bvh_no_avx2_of_width[w]);
    mesh_free_tree(&s->bvh_avx2_only);
    free(s->corners), free(s->lane_items);
    rtcReleaseScene(s->scene), rtcReleaseScene(s->scene_medium);
    mesh_free(&s->m);
}

int main(int argc, char **argv)
{
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        fprintf(stderr, "ch11_embree: Embree has no device\n");
        return 1;
    }
    enum { N_SUBJECTS = 5 };
    static subject subjects[N_SUBJECTS] = {{.name = "bunny"},
                                           {.name = "teapot"},
                                           {.name = "scanned"},
                                           {.name = "needles", .few_methods = true},
                                           {.name = "slivers", .few_methods = true}};
    load_float_mesh(argc > 1 ? argv[1] : "meshes/bunny.obj", &subjects[0].m);
    load_float_mesh(argc > 2 ? argv[2] : "meshes/teapot-8.obj", &subjects[1].m);
    load_float_mesh(argc > 1 ? argv[1] : "meshes/bunny.obj", &subjects[2].m);
    subdivided(&subjects[2].m, 1);
    subjects[3].m = needles_mesh(4000, 1e-3);
    subjects[4].m = slivers_mesh(4000);
    bench_print_machine();
    bench_csv_header();
    printf("vector,%s,0,0,bvh_vector_width\n",
           bvh_walks_with_avx512() ? "AVX-512VL chosen at run time"
           : bvh_walks_with_avx2() ? "AVX2 chosen at run time"
                                   : "the build's own instructions");
    printf("default,bvh%d,0,0,default_method\n", bvh_default_params().width);
    /* CH11_QUICK=1: the bunny at K = 1 alone, no builds (a quick look) */
    bool quick = getenv("CH11_QUICK") != NULL || getenv("CH09_QUICK") != NULL;
    for (int k = 0; k < (quick ? 1 : N_SUBJECTS); k++) {
        subject *s = &subjects[k];
        if (!s->few_methods && !quick && getenv("CH11_METHODS") == NULL)
            time_builds(s, device);
        prepare(s, device);
        time_rays(s, 1.0, false);
        if (k < 2) /* the bunny and the teapot */
            time_rays(s, 1.0, true);
        if (!s->few_methods && !quick)
            time_rays(s, 2.5, false);
        release(s);
    }
    rtcReleaseDevice(device);
    return 0;
}
