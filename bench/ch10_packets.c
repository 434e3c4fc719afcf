/* ch10_packets.c: the leaves of chapter 10's BVH, form by form, against
 * the answers each gives: the same binary tree and chapter 9's walk, one
 * thread, the same rays.
 *
 *   build/rel/bench/ch10_packets [BUNNY.obj TEAPOT.obj] \
 *       > figures/ch10-packets.csv
 *
 * The meshes (their vertices rounded to float) and the rays are those of
 * ch08_rays.h: 512 x 512 rays from an eye at K = 1 and K = 2.5 times a
 * mesh's diagonal in front of it. The methods, each a closest hit:
 *   ch09       chapter 9's leaves: chapter 4's test once a triangle,
 *              its corners read from the mesh through the item's index
 *              (a tree whose leaves count their items one by one);
 *   tightened  the same tree, its leaves' corners copied leaf by leaf and
 *              tested by chapter 10's tightened test;
 *   packets    chapter 10's BVH (mesh_build_bvh): leaves of packets, the
 *              float filter, the kept lanes decided in double;
 *   float      the same tree and packets, decided in float alone
 *              (accelerator bvh-float).
 * The exact answers are chapter 8's kd-tree's. All the methods of one
 * mesh and distance are timed together, interleaved (bench/timing.h).
 *
 * Rows, after the "# machine:" line:
 *   METHOD,MESH-K,ns_per_ray,Mrays/s,mrays_per_s,q1,q3,wall
 *   ratio,METHOD@MESH-K,0,its time / packets' time,over_packets
 *   hits,MESH-K,0,count,rays
 *   hits,MESH-K,0,count,METHOD_other_answers  (a ray one hits and the
 *       exact answer not, or another triangle)
 *   hits,MESH-K,0,error,METHOD_largest_t_error  (the largest relative
 *       difference of t from the exact t, over the rays that hit the exact
 *       answer's triangle) */
#include <string.h>

#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 512 };

typedef enum { CH09, TIGHTENED, PACKETS, IN_FLOAT, N_METHODS } method;
static const char *const NAMES[N_METHODS] = {"ch09", "tightened", "packets",
                                             "float"};

/* A mesh, its kd-tree (the exact answers), a binary tree of items one by
 * one with a copy of its leaves' corners, and chapter 10's BVH. */
typedef struct {
    const char *name;
    mesh m;                    /* its kd-tree */
    bvh items;                 /* leaves of items, counted one by one */
    triangle_corners *corners; /* items's corners, in the order of its items */
    mesh packed, in_float;     /* chapter 10's BVH; the same, in float */
} subject;

typedef struct {
    method how;
    const subject *s;
    const float_ray *rays;
    long n_rays;
} trace_ctx;

/* Chapter 9's leaf: chapter 4's test of each triangle, read from the
 * mesh, keeping the tie rule; the triangle's index, or -1. */
static int ch09_leaf(const mesh *m, const watertight_ray *w, const int *items,
                     int count, double t_max, int best, triangle_hit *out)
{
    int nearest = -1;
    double reach = nextafter(t_max, INFINITY); /* t_max itself, for a tie */
    for (int k = 0; k < count; k++) {
        triangle_hit th;
        const int *v = m->triangles[items[k]].v;
        if (triangle_hit_prepared(w, m->vertices[v[0]], m->vertices[v[1]],
                                  m->vertices[v[2]], 0, reach, &th) &&
            (th.t < t_max || items[k] < best)) {
            *out = th, t_max = th.t, best = items[k], nearest = items[k];
            reach = nextafter(t_max, INFINITY);
        }
    }
    return nearest;
}

/* Chapter 9's walk over s->items with the leaves of how (CH09 or
 * TIGHTENED): the nearest t, or infinity; its triangle in *triangle. */
static double items_walk(const subject *s, const mesh_ray *mr, method how,
                         int *triangle)
{
    double near = 0, far = INFINITY, t_max = INFINITY;
    *triangle = -1;
    bvh_ray r;
    if (!box_clip(&s->m.bounds, mr->r.origin, mr->inv_dir, &near, &far) ||
        !bvh_ray_of(mr->r.origin, mr->inv_dir, 0, INFINITY, &r))
        return INFINITY;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    bvh_walk w;
    bvh_leaf leaf;
    triangle_hit th;
    bvh_walk_start(&w, &s->items, &r);
    w.sorted = true;
    while (bvh_walk_next(&w, t_max, &leaf)) {
        const int *items = s->items.items + leaf.first;
        int k = -1;
        if (how == CH09)
            k = ch09_leaf(&s->m, &shear, items, leaf.count, t_max,
                          *triangle, &th);
        else {
            int j = triangle_nearest_of_leaf(&shear,
                                             s->corners + leaf.first, items,
                                             leaf.count, 0, t_max, *triangle,
                                             &th);
            k = j >= 0 ? items[j] : -1;
        }
        if (k >= 0)
            *triangle = k, t_max = th.t;
    }
    return t_max;
}

/* Ray k by c's method: its distance, or infinity; its triangle in
 * *triangle (-1: none). */
static double trace(const trace_ctx *c, long k, render_stats *stats,
                    int *triangle)
{
    mesh_ray mr = mesh_ray_of(ray_of(&c->rays[k]));
    if (c->how == CH09 || c->how == TIGHTENED)
        return items_walk(c->s, &mr, c->how, triangle);
    const mesh *m = c->how == PACKETS ? &c->s->packed : &c->s->in_float;
    triangle_hit th;
    *triangle = mesh_nearest(m, &mr, 0, INFINITY, &th, stats);
    return *triangle >= 0 ? th.t : INFINITY;
}

static void run_rays(void *ctx, long reps)
{
    const trace_ctx *c = ctx;
    render_stats stats = {0};
    double sum = 0;
    int triangle;
    for (long k = 0; k < reps; k++)
        sum += trace(c, k % c->n_rays, &stats, &triangle) < INFINITY;
    bench_sink += sum;
}

/* The answers of each method against the kd-tree's, the exact ones. */
static void print_answers(const trace_ctx *c, const char *param)
{
    long n = c[0].n_rays, other[N_METHODS] = {0};
    double worst[N_METHODS] = {0};
    for (long k = 0; k < n; k++) {
        mesh_ray mr = mesh_ray_of(ray_of(&c[0].rays[k]));
        render_stats stats = {0};
        triangle_hit exact;
        int want = mesh_nearest(&c[0].s->m, &mr, 0, INFINITY, &exact, &stats);
        for (int j = 0; j < N_METHODS; j++) {
            int got;
            double t = trace(&c[j], k, &stats, &got);
            if (got != want) {
                other[j]++;
                continue;
            }
            double e = want >= 0 ? fabs(t - exact.t) / exact.t : 0;
            worst[j] = e > worst[j] ? e : worst[j];
        }
    }
    printf("hits,%s,0,%ld,rays\n", param, n);
    for (int j = 0; j < N_METHODS; j++)
        printf("hits,%s,0,%ld,%s_other_answers\n", param, other[j], NAMES[j]);
    for (int j = 0; j < N_METHODS; j++)
        printf("hits,%s,0,%.3g,%s_largest_t_error\n", param, worst[j],
               NAMES[j]);
}

static void time_rays(const subject *s, double K)
{
    char param[48];
    snprintf(param, sizeof param, "%s-%.1f", s->name, K);
    long n_rays = (long)SIDE * SIDE;
    float_ray *rays = make_rays(&s->m, K, SIDE);
    trace_ctx c[N_METHODS];
    bench_case cases[N_METHODS];
    bench_timing t[N_METHODS];
    for (int j = 0; j < N_METHODS; j++) {
        c[j] = (trace_ctx){(method)j, s, rays, n_rays};
        cases[j] = (bench_case){NAMES[j], param, run_rays, &c[j], n_rays};
    }
    bench_time_cases(cases, N_METHODS, t);
    for (int j = 0; j < N_METHODS; j++)
        bench_row(NAMES[j], param, &t[j], "%.4f", 1e3 / t[j].median,
                  "mrays_per_s");
    for (int j = 0; j < N_METHODS; j++)
        printf("ratio,%s@%s,0,%.4f,over_packets\n", NAMES[j], param,
               t[j].median / t[PACKETS].median);
    print_answers(c, param);
    fflush(stdout);
    free(rays);
}

/* The kd-tree, the tree of items with its copied corners, and chapter
 * 10's BVH, exact and in float, of s->m. */
static void prepare(subject *s)
{
    kdtree_params kp = kdtree_default_params();
    if (!mesh_build_tree(&s->m, &kp))
        exit(1);
    const mesh *m = &s->m;
    box *bounds = malloc((size_t)m->triangle_count * sizeof *bounds);
    if (bounds == NULL)
        exit(1);
    for (int i = 0; i < m->triangle_count; i++) {
        const int *v = m->triangles[i].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]];
        vec3 c = m->vertices[v[2]];
        bounds[i] = (box){vec3_min(a, vec3_min(b, c)),
                          vec3_max(a, vec3_max(b, c))};
    }
    bvh_params bp = {.width = 2, .item_group = 1}; /* chapter 9's tree */
    if (!bvh_build(&s->items, m->triangle_count, bounds, &bp))
        exit(1);
    free(bounds);
    s->corners = malloc((size_t)s->items.item_count * sizeof *s->corners);
    if (s->corners == NULL)
        exit(1);
    for (int k = 0; k < s->items.item_count; k++) {
        const int *v = m->triangles[s->items.items[k]].v;
        for (int c = 0; c < 3; c++)
            s->corners[k].p[c] = m->vertices[v[c]];
    }
    s->packed = s->m;
    s->packed.tree = (kdtree){0}, s->packed.leaf_corners = NULL;
    if (!mesh_build_bvh(&s->packed, &(bvh_params){.width = 2}))
        exit(1);
    s->in_float = s->packed; /* the same tree, shared */
    s->in_float.bvh_in_float = true;
}

static void release(subject *s)
{
    mesh_free_tree(&s->packed);
    bvh_free(&s->items);
    free(s->corners);
    mesh_free(&s->m);
}

int main(int argc, char **argv)
{
    subject subjects[2] = {{.name = "bunny"}, {.name = "teapot"}};
    load_float_mesh(argc > 1 ? argv[1] : "meshes/bunny.obj", &subjects[0].m);
    load_float_mesh(argc > 2 ? argv[2] : "meshes/teapot-8.obj",
                    &subjects[1].m);
    bench_print_machine();
    bench_csv_header();
    for (int k = 0; k < 2; k++) {
        prepare(&subjects[k]);
        time_rays(&subjects[k], 1.0);
        time_rays(&subjects[k], 2.5);
        release(&subjects[k]);
    }
    return 0;
}
