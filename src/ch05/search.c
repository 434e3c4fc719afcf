/* search.c: the search for what a ray hits, and the hit record of the
 * winner (chapter 2). See search.h. */
#include "search.h"

/* <<the search for the nearest hit>> ch02 */
/* What the search keeps of the nearest hit so far. */
typedef struct {
    const object *object; /* NULL: nothing hit yet */
    double t;             /* its distance: the search's t_max */
    int primitive;        /* which triangle of a mesh; 0 otherwise */
    double b[3];          /* where on that triangle: barycentrics */
    ray r;                /* the ray that found it, in the object's space */
} nearest_hit;

typedef struct {
    const scene *scene; /* what is searched */
    ray r;
    double t_min;
    nearest_hit best;
    render_stats *stats;
    /* <<search members>> ch04 */
    mesh_ray prepared;    /* valid once is_prepared is set */
    watertight_ray shear; /* valid once is_sheared is set */
    bool is_prepared, is_sheared;
} scene_search;

/* <<per-ray constants of the search>> ch04 */
/* The search's ray with its per-ray constants, made on first use. */
static const mesh_ray *prepared_ray(scene_search *q)
{
    if (!q->is_prepared)
        q->prepared = mesh_ray_of(q->r), q->is_prepared = true;
    return &q->prepared;
}

/* The search's ray sheared for the triangles, made on first use. */
static const watertight_ray *prepared_shear(scene_search *q)
{
    if (!q->is_sheared)
        q->shear = watertight_ray_of(q->r), q->is_sheared = true;
    return &q->shear;
}

/* <<searching a placed object>> ch05 */
static void shape_intersect(const object *o, scene_search *q);

/* r in the object's space: o' = M^-1 o, d' = M^-1 d. d' is not
 * normalised, so that o' + t d' = M^-1 (o + t d): the same t. */
static ray ray_to_object(const transform *t, ray r)
{
    return (ray){mat4_mul_point(t->inv, r.origin),
                 mat4_mul_dir(t->inv, r.dir)};
}

/* Tests the placed object o with q's ray taken into its space; q's best
 * hit narrows when o is hit nearer. */
static void search_placed_object(const object *o, scene_search *q)
{
    scene_search local = *q;
    local.r = ray_to_object(scene_transform(q->scene, o->transform), q->r);
    /* the world ray's constants are not this ray's */
    local.is_prepared = local.is_sheared = false;
    q->stats->object_space_rays++;
    shape_intersect(o, &local);
    q->best = local.best;
}

/* Narrows q->best when q->r, the ray in o's own space, hits o's shape
 * nearer than q->best.t. */
static void shape_intersect(const object *o, scene_search *q)
{
    double t, t_max = q->best.t; /* only a nearer hit counts */
    switch (o->kind) {
    case SHAPE_SPHERE:
        q->stats->sphere_tests++;
        if (sphere_hit_t(&o->sphere, q->r, q->t_min, t_max, &t))
            q->best = (nearest_hit){.object = o, .t = t, .r = q->r};
        break;
    /* <<intersect the other shapes>> ch04 */
    case SHAPE_TRIANGLE: {
        triangle_hit th;
        q->stats->triangle_tests++;
        const vec3 *c = o->corners;
        if (triangle_hit_prepared(prepared_shear(q), c[0], c[1], c[2], q->t_min,
                                  t_max, &th))
            q->best = (nearest_hit){o, th.t, 0, {th.b[0], th.b[1], th.b[2]},
                                    q->r};
        break;
    }
    case SHAPE_MESH: {
        triangle_hit th = {0}; /* filled whenever k >= 0 */
        int k = mesh_nearest(&q->scene->meshes[o->mesh], prepared_ray(q),
                             q->t_min, t_max, &th, q->stats);
        if (k >= 0)
            q->best = (nearest_hit){o, th.t, k, {th.b[0], th.b[1], th.b[2]},
                                    q->r};
        break;
    }
    }
}

static void object_intersect(const object *o, scene_search *q)
{
    /* <<search an object in its own space>> ch05 */
    if (o->transform != 0) {
        search_placed_object(o, q);
        return;
    }
    shape_intersect(o, q);
}



/* <<bringing a hit into the world>> ch05 */
/* (M^-1)^T n, normalised: a normal of the object's space in the world. */
static vec3 normal_to_world(const transform *t, vec3 n)
{
    return vec3_normalize(mat4_mul_normal(t->inv, n));
}

/* h, filled in the object's space, brought into the world for the world
 * ray r: the point at the same t, the normals by the inverse transpose. */
static void hit_to_world(const transform *t, ray r, hit *h)
{
    h->point = ray_at(r, h->t);
    h->normal = normal_to_world(t, h->normal);
    h->geometric_normal = normal_to_world(t, h->geometric_normal);
    h->inside = vec3_dot(r.dir, h->geometric_normal) > 0;
}


/* Fills the geometry of h for q's nearest hit, along the ray that found it. */
static void shape_fill_hit(const scene_search *q, hit *h)
{
    const nearest_hit *best = &q->best;
    const object *o = best->object;
    switch (o->kind) {
    case SHAPE_SPHERE:
        sphere_fill_hit(&o->sphere, best->r, best->t, h);
        break;
    /* <<fill the hits of the other shapes>> ch04 */
    case SHAPE_TRIANGLE: {
        const vec3 *c = o->corners;
        triangle_fill_hit(c[0], c[1], c[2], best->r, best->t, h);
        break;
    }
    case SHAPE_MESH: {
        triangle_hit th = {best->t, {best->b[0], best->b[1], best->b[2]}};
        mesh_fill_hit(&q->scene->meshes[o->mesh], best->primitive, best->r, &th,
                      h);
        break;
    }
    }
}

/* Fills h for q's nearest hit, found along q's ray in the world. */
static void object_fill_hit(const scene_search *q, hit *h)
{
    const object *o = q->best.object;
    /* <<find the object's transform>> ch05 */
    const transform *placed =
        o->transform != 0 ? scene_transform(q->scene, o->transform) : NULL;
    shape_fill_hit(q, h);
    /* <<bring the hit back into the world>> ch05 */
    if (placed != NULL)
        hit_to_world(placed, q->r, h);
    h->color = o->color;
    /* <<fill the object's part of the hit>> ch03 */
    h->material = o->material;
}

/* Tests every object in turn. */
static void search_objects(scene_search *q)
{
    const scene *s = q->scene;
    for (int k = 0; k < s->object_count; k++)
        object_intersect(&s->objects[k], q);
}

bool scene_intersect(const scene *s, ray r, double t_min, double t_max,
                     hit *h, render_stats *stats)
{
    scene_search q = {.scene = s, .r = r, .t_min = t_min, .stats = stats,
                      .best = {.object = NULL, .t = t_max}};
    search_objects(&q);
    if (q.best.object == NULL)
        return false;
    stats->hits++;
    object_fill_hit(&q, h);
    return true;
}
