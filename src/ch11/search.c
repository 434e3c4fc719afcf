/* search.c: the search for what a ray hits, and the hit record of the
 * winner (chapter 2). See search.h. */
#include "search.h"
/* <<search.c includes>> ch06 */
#include "offset.h"

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
    /* <<search members>> += ch06 */
    bool any_hit; /* a shadow ray's search: the first hit settles it */
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
    /* <<a shadow ray's test of a shape>> ch08 */
    if (q->any_hit && o->kind == SHAPE_MESH) {
        q->stats->mesh_occlusion_tests++;
        if (mesh_occluded(&q->scene->meshes[o->mesh], prepared_ray(q), q->t_min,
                          q->best.t, q->stats))
            q->best.object = o; /* any hit settles a shadow ray */
        return;
    }
    double t, t_max = q->best.t; /* only a nearer hit counts */
    /* <<the tie rule for objects>> ch08 */
    if (q->best.object != NULL && o < q->best.object)
        t_max = nextafter(t_max, INFINITY); /* a tie at best.t goes to o */
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
    /* <<a shadow ray's shortcuts>> ch06 */
    if (q->any_hit && q->best.object != NULL) {
        q->stats->shadow_objects_skipped++;
        return; /* an occluder is found: no other object can change that */
    }
    /* <<search an object in its own space>> ch05 */
    if (o->transform != 0) {
        search_placed_object(o, q);
        return;
    }
    shape_intersect(o, q);
}

/* <<the walk of the objects' tree>> ch08 */
/* Tests the objects in the leaves of the objects' tree that q's ray
 * passes through, nearest first. */
static void search_object_tree(scene_search *q)
{
    const scene *s = q->scene;
    const kdtree *t = &s->object_tree;
    const mesh_ray *mr = prepared_ray(q);
    double near = q->t_min, far = q->best.t;
    vec3 thick = {t->thickness, t->thickness, t->thickness};
    box reach = {vec3_sub(t->bounds.lo, thick), vec3_add(t->bounds.hi, thick)};
    q->stats->box_tests++;
    if (!box_clip(&reach, q->r.origin, mr->inv_dir, &near, &far))
        return;
    kdtree_walk w;
    kdtree_leaf leaf;
    kdtree_walk_start(&w, t, q->r.origin, mr->inv_dir, near, far);
    while (kdtree_walk_next(&w, q->best.t, &leaf))
        for (int k = 0; k < leaf.count; k++)
            object_intersect(&s->objects[t->items[leaf.first + k]], q);
    q->stats->kd_nodes += w.visited;
}

/* <<surface patterns>> ch07 */
/* True where the checker of tile size s takes its second colour. */
static bool checker_is_odd(vec3 p, double s)
{
    /* cubes centred on multiples of s: floors at y = 0 fall mid-cube */
    double sum = floor(p.x / s + 0.5) + floor(p.y / s + 0.5) +
                 floor(p.z / s + 0.5);
    return fabs(fmod(sum, 2)) == 1;
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
/* <<bringing a hit into the world>> += ch06 */

/* The refined object-space point p, with error e, taken to the world by
 * t: its image M p and the bound of that image. */
static void place_hit_point(const transform *t, vec3 p, vec3 e, hit *h)
{
    const double(*m)[4] = t->m.m;
    const double pc[3] = {p.x, p.y, p.z}, ec[3] = {e.x, e.y, e.z};
    double bound[3];
    for (int i = 0; i < 3; i++) {
        double carried = 0, product = fabs(m[i][3]);
        for (int j = 0; j < 3; j++) {
            carried += fabs(m[i][j]) * ec[j];
            product += fabs(m[i][j] * pc[j]);
        }
        bound[i] = (1 + gamma_bound(4)) * carried + gamma_bound(4) * product;
    }
    h->point = mat4_mul_point(t->m, p);
    h->error = (vec3){bound[0], bound[1], bound[2]};
}

/* <<the hit point's error bound>> ch06 */
static void refine_hit_point(const scene *s, const nearest_hit *best, hit *h)
{
    const object *o = best->object;
    switch (o->kind) {
    case SHAPE_SPHERE:
        sphere_refine_hit(&o->sphere, h);
        break;
    case SHAPE_TRIANGLE: {
        const vec3 *c = o->corners;
        triangle_refine_hit(c[0], c[1], c[2], best->b, h);
        break;
    }
    case SHAPE_MESH:
        mesh_refine_hit(&s->meshes[o->mesh], best->primitive, best->b, h);
        break;
    }
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
    /* <<bound the rounding of the hit point>> ch06 */
    refine_hit_point(q->scene, &q->best, h);
    vec3 object_point = h->point, object_error = h->error;
    /* <<bring the hit back into the world>> ch05 */
    if (placed != NULL)
        hit_to_world(placed, q->r, h);
    /* <<bring the hit back into the world>> += ch06 */
    if (placed != NULL)
        place_hit_point(placed, object_point, object_error, h);
    h->color = o->color;
    /* <<fill the object's part of the hit>> ch03 */
    h->material = o->material;
    /* <<fill the object's part of the hit>> += ch07 */
    if (o->checkered && checker_is_odd(h->point, o->tile > 0 ? o->tile : 1))
        h->color = o->checker;
}

/* Tests every object in turn. */
static void search_objects(scene_search *q)
{
    const scene *s = q->scene;
    /* <<search the objects' tree>> ch08 */
    if (s->object_tree.node_count > 0) {
        search_object_tree(q);
        return;
    }
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
/* <<the any-hit search>> ch06 */

bool scene_occluded(const scene *s, ray r, double t_min, double t_max,
                    render_stats *stats)
{
    scene_search q = {.scene = s, .r = r, .t_min = t_min, .stats = stats,
                      .best = {.object = NULL, .t = t_max},
                      .any_hit = true};
    search_objects(&q);
    return q.best.object != NULL;
}
