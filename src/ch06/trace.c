/* trace.c: what a ray sees (chapter 1). See trace.h. */
#include "trace.h"

/* <<trace includes>> ch02 */
#include "search.h"
/* <<trace includes>> += ch03 */
#include "shade.h"

/* <<trace helpers>> ch06 */
static vec3 trace_path(const scene *s, ray r, int depth, double weight,
                       render_stats *stats);

/* Where --stats counts one kind of secondary ray. */
typedef struct {
    long long *traced, *too_deep, *too_light;
} ray_counters;

/* Is a secondary ray of weight w, after depth bounces, worth tracing?
 * Counts the answer in counts. */
static bool branch_is_traced(const scene *s, int depth, double w,
                             ray_counters counts)
{
    if (depth >= s->max_depth) {
        (*counts.too_deep)++;
        return false;
    }
    if (w < s->cutoff) {
        (*counts.too_light)++;
        return false;
    }
    (*counts.traced)++;
    return true;
}

/* color mixed with what the mirror at h reflects, when it is a mirror and
 * the reflected ray is worth tracing; color alone otherwise. */
static vec3 add_reflection(const scene *s, const hit *h, ray r, int depth,
                           double weight, vec3 color, render_stats *stats)
{
    double alpha = scene_material(s, h->material)->reflect;
    if (alpha == 0)
        return color; /* not a mirror: no ray, nothing counted */
    ray_counters mirror = {&stats->reflection_rays,
                           &stats->reflection_skipped_depth,
                           &stats->reflection_skipped_weight};
    if (!branch_is_traced(s, depth, weight * alpha, mirror))
        return color;
    vec3 dir = vec3_reflect(r.dir, h->normal);
    vec3 seen = trace_path(s, ray_leaving(h, dir), depth + 1,
                           weight * alpha, stats);
    return vec3_lerp(color, seen, alpha);
}

/* What the ray r sees, when its colour counts weight times in the pixel's
 * and depth bounces led to it. */
static vec3 trace_path(const scene *s, ray r, int depth, double weight,
                       render_stats *stats)
{
    hit h;
    if (!scene_intersect(s, r, 0.0, INFINITY, &h, stats))
        return background_color(&s->bg, r.dir);
    /* <<shade the hit>> ch03 */
    vec3 color = shade(s, &h, vec3_scale(r.dir, -1), stats);
    /* <<add the light of secondary rays>> ch06 */
    color = add_reflection(s, &h, r, depth, weight, color, stats);
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
    return trace_path(s, r, depth, 1.0, stats);
}
