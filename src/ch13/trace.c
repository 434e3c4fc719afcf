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
    /* <<shares mixed over the mirror>> ch07 */
    share *= 1 - m->transparency; /* the clear part is mixed over it */
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
/* <<secondary rays of other materials>> ch07 */

/* F_R by the material's model, for light from eta1 into eta2 at cos_i. */
static double reflectance(const material *m, double cos_i, double eta1,
                          double eta2)
{
    if (m->fresnel == FRESNEL_SCHLICK)
        return fresnel_schlick_tir(cos_i, eta1, eta2);
    return fresnel_exact(cos_i, eta1, eta2);
}

/* The surface at h as a ray along dir crosses it: the normal on the ray's
 * side, the index the ray comes from and the one it goes into. */
typedef struct {
    vec3 n;
    double eta1, eta2;
} crossing;

static crossing crossing_at(const hit *h, const material *m, vec3 dir)
{
    /* inside or out: by the geometric normal, as the hit says */
    double eta1 = h->inside ? m->ior : 1, eta2 = h->inside ? 1 : m->ior;
    /* the shading normal turned to face the ray, so that cos_i >= 0 */
    vec3 n = vec3_dot(h->normal, dir) < 0 ? h->normal
                                          : vec3_scale(h->normal, -1);
    return (crossing){n, eta1, eta2};
}

/* What a secondary ray of weight w leaving h along dir sees, or fallback
 * when it has no share of the light or is not worth tracing. */
static vec3 trace_branch(const scene *s, const hit *h, vec3 dir, int depth,
                         double w, vec3 fallback, ray_counters counts,
                         ray_tree *tree)
{
    if (!(w > 0))
        return fallback; /* no share of the light: not a ray at all */
    if (!branch_is_traced(s, depth, w, counts, tree))
        return fallback;
    return trace_path(s, ray_leaving(h, dir), depth + 1, w, tree);
}

/* color mixed with what the clear part of the surface at h passes on:
 * the reflected and the refracted light, shared by Fresnel. */
static vec3 add_refraction(const scene *s, const hit *h, ray r, int depth,
                           double weight, vec3 color, ray_tree *tree)
{
    render_stats *stats = tree->stats;
    const material *m = scene_material(s, h->material);
    double tau = m->transparency;
    if (tau == 0)
        return color; /* opaque: no ray, nothing counted */
    crossing x = crossing_at(h, m, r.dir);
    refraction t = refract_standard(r.dir, x.n, x.eta1 / x.eta2);
    double F = t.total ? 1 : reflectance(m, t.cos_i, x.eta1, x.eta2);
    stats->total_reflections += t.total;
    ray_counters mirror = {&stats->reflection_rays,
                           &stats->reflection_skipped_depth,
                           &stats->reflection_skipped_weight};
    ray_counters through = {&stats->refraction_rays,
                            &stats->refraction_skipped_depth,
                            &stats->refraction_skipped_weight};
    vec3 I_r = trace_branch(s, h, vec3_reflect(r.dir, x.n), depth,
                            weight * tau * F, color, mirror, tree);
    vec3 I_t = t.total ? color
                       : trace_branch(s, h, t.dir, depth,
                                      weight * tau * (1 - F), color,
                                      through, tree);
    vec3 clear = vec3_lerp(I_t, I_r, F); /* F I_r + (1 - F) I_t */
    return vec3_lerp(color, clear, tau);
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
    /* <<add the light of secondary rays>> += ch07 */
    color = add_refraction(s, &h, r, depth, weight, color, tree);
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
    /* <<trace a ray>> ch13 */
    long shadows = scene_shadow_rays(s); /* at most the scene's budget */
    long budget = s->ray_budget > 0 && s->ray_budget < TRACE_RAY_BUDGET
                      ? (long)s->ray_budget
                      : TRACE_RAY_BUDGET;
    ray_tree tree = {.rays_left = budget - shadows, /* its own hit's */
                     .ray_cost = 1 + shadows, .stats = stats};
    return trace_path(s, r, depth, 1.0, &tree);
}
