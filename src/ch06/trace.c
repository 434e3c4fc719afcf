/* trace.c: what a ray sees (chapter 1). See trace.h. */
#include "trace.h"

/* <<trace includes>> ch02 */
#include "search.h"
/* <<trace includes>> += ch03 */
#include "shade.h"
/* <<trace includes>> += ch06 */
#include "offset.h"

/* <<trace helpers>> ch06 */
/* 2^16 rays for one primary ray, shadow rays counted: ten times the 6,400
 * secondary rays that the default depth and cutoff allow, so it bounds
 * only what they cannot. */
#define TRACE_RAY_BUDGET 65536

/* The rays one primary ray may still spawn, and where they are counted. */
typedef struct {
    long rays_left;
    long ray_cost; /* a secondary ray and the shadow rays of its hit */
    bool cut;      /* the budget ran out */
    render_stats *stats;
} ray_tree;

/* Takes a secondary ray, with its shadow rays, from the tree's budget;
 * false when they do not fit (counted once for the tree). */
static bool ray_tree_take(ray_tree *tree)
{
    if (tree->rays_left >= tree->ray_cost) {
        tree->rays_left -= tree->ray_cost;
        return true;
    }
    tree->stats->ray_trees_cut += !tree->cut;
    tree->cut = true;
    return false;
}

/* The share of what a hit on m shows that comes from its mirror. */
static double mirror_share(const material *m)
{
    double share = m->reflect;
    return share;
}

static vec3 trace_path(const scene *s, ray r, int depth, double weight,
                       ray_tree *tree);

/* Where --stats counts one kind of secondary ray. */
typedef struct {
    long long *traced, *too_deep, *too_light;
} ray_counters;

/* Is a secondary ray of weight w, after depth bounces, worth tracing, and
 * is it within the tree's budget? Counts the answer in counts. */
static bool branch_is_traced(const scene *s, int depth, double w,
                             ray_counters counts, ray_tree *tree)
{
    if (depth >= s->max_depth) {
        (*counts.too_deep)++;
        return false;
    }
    if (w < s->cutoff) {
        (*counts.too_light)++;
        return false;
    }
    if (!ray_tree_take(tree))
        return false; /* past the budget: counted once, for the tree */
    (*counts.traced)++;
    return true;
}

/* color mixed with what the mirror at h reflects, when it is a mirror and
 * the reflected ray is worth tracing; color alone otherwise. */
static vec3 add_reflection(const scene *s, const hit *h, ray r, int depth,
                           double weight, vec3 color, ray_tree *tree)
{
    const material *m = scene_material(s, h->material);
    double w = weight * mirror_share(m); /* the reflected ray's weight */
    if (w == 0)
        return color; /* no mirror to show: no ray, nothing counted */
    render_stats *stats = tree->stats;
    ray_counters mirror = {&stats->reflection_rays,
                           &stats->reflection_skipped_depth,
                           &stats->reflection_skipped_weight};
    if (!branch_is_traced(s, depth, w, mirror, tree))
        return color;
    vec3 dir = vec3_reflect(r.dir, h->normal);
    vec3 seen = trace_path(s, ray_leaving(h, dir), depth + 1, w, tree);
    return vec3_lerp(color, seen, m->reflect);
}

/* What the ray r sees, when its colour counts weight times in the pixel's
 * and depth bounces led to it. */
static vec3 trace_path(const scene *s, ray r, int depth, double weight,
                       ray_tree *tree)
{
    render_stats *stats = tree->stats; /* for the hooks of chapter 3 on */
    hit h;
    if (!scene_intersect(s, r, 0.0, INFINITY, &h, stats))
        return background_color(&s->bg, r.dir);
    /* <<shade the hit>> ch03 */
    vec3 color = shade(s, &h, vec3_scale(r.dir, -1), stats);
    /* <<add the light of secondary rays>> ch06 */
    color = add_reflection(s, &h, r, depth, weight, color, tree);
    return color;
}

vec3 background_color(const background *bg, vec3 dir)
{
    if (bg->kind == BACKGROUND_SOLID)
        return bg->bottom;
    double t = 0.5 * (dir.y + 1.0); /* dir.y in [-1, 1] -> t in [0, 1] */
    return vec3_lerp(bg->bottom, bg->top, t);
}

vec3 trace(const scene *s, ray r, int depth, render_stats *stats)
{
    /* <<trace a ray>> ch06 */
    long shadows = scene_shadow_rays(s); /* at most the scene's budget */
    ray_tree tree = {.rays_left = TRACE_RAY_BUDGET - shadows, /* its own hit's */
                     .ray_cost = 1 + shadows, .stats = stats};
    return trace_path(s, r, depth, 1.0, &tree);
}
