/* scene.c: the scene's defaults, its contents, and the queries over them
 * (chapter 01). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

#include "array.h"
#include <time.h>

void scene_init(scene *s)
{
    memset(s, 0, sizeof *s);
    s->cam.fov_deg = 60.0;
    s->cam.width = 320;
    s->cam.height = 240;
    s->bg.kind = BACKGROUND_GRADIENT;
    s->bg.bottom = (vec3){1.0, 1.0, 1.0};
    s->bg.top = (vec3){0.3, 0.5, 1.0};
    s->ambient = (vec3){1, 1, 1};
    s->tone.alpha = s->tone.beta = 1;
    s->default_material = material_default();
    s->default_light = (light){.kind = LIGHT_DIRECTIONAL,
                               .direction = vec3_normalize((vec3){1, -1, 1}),
                               .intensity = {1, 1, 1}};
    s->tree_params = kdtree_default_params();
}

void scene_free(scene *s)
{
    free(s->objects);
    free(s->materials);
    free(s->lights);
    for (int k = 0; k < s->mesh_count; k++)
        mesh_free(&s->meshes[k]);
    free(s->meshes);
    kdtree_free(&s->object_tree);
    memset(s, 0, sizeof *s); /* a second scene_free finds nothing to free */
}

bool scene_add_object(scene *s, object o)
{
    object *grown = array_grow(s->objects, s->object_count,
                               &s->object_capacity, SCENE_MAX_OBJECTS,
                               sizeof o);
    if (grown == NULL)
        return false;
    s->objects = grown;
    s->objects[s->object_count++] = o;
    return true;
}

/* What the search keeps of the nearest hit so far. */
typedef struct {
    const object *object; /* NULL: nothing hit yet */
    double t;             /* its distance: the search's t_max */
    int primitive;        /* which triangle of a mesh; 0 otherwise */
    double b[3];          /* where on that triangle: barycentrics */
} nearest_hit;

typedef struct {
    ray r;
    double t_min;
    nearest_hit best;
    render_stats *stats;
    mesh_ray prepared; /* valid once is_prepared is set */
    bool is_prepared;
} scene_search;

/* The search's ray with its per-ray constants, made on first use. */
static const mesh_ray *prepared_ray(scene_search *q)
{
    if (!q->is_prepared)
        q->prepared = mesh_ray_of(q->r), q->is_prepared = true;
    return &q->prepared;
}

static void object_intersect(const scene *s, const object *o,
                             scene_search *q);

/* Tests the objects in the leaves of the objects' tree that q's ray
 * passes through, nearest first. */
static void search_object_tree(const scene *s, scene_search *q)
{
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
            object_intersect(s, &s->objects[t->items[leaf.first + k]], q);
    q->stats->kd_nodes += w.visited;
}

/* Narrows q->best when q->r, the ray in o's own space, hits o's shape
 * nearer than q->best.t. */
static void shape_intersect(const scene *s, const object *o, scene_search *q)
{
    (void)s; /* chapter 04's meshes live in the scene */
    double t;
    switch (o->kind) {
    case SHAPE_SPHERE:
        q->stats->sphere_tests++;
        if (sphere_hit_t(&o->sphere, q->r, q->t_min, q->best.t, &t))
            q->best = (nearest_hit){.object = o, .t = t};
        break;
    case SHAPE_TRIANGLE: {
        triangle_hit th;
        q->stats->triangle_tests++;
        const vec3 *c = o->corners;
        if (triangle_hit_prepared(&prepared_ray(q)->shear, c[0], c[1], c[2],
                                  q->t_min, q->best.t, &th))
            q->best = (nearest_hit){o, th.t, 0, {th.b[0], th.b[1], th.b[2]}};
        break;
    }
    case SHAPE_MESH: {
        triangle_hit th;
        int k = mesh_nearest(&s->meshes[o->mesh], prepared_ray(q), q->t_min,
                             q->best.t, &th, q->stats);
        if (k >= 0)
            q->best = (nearest_hit){o, th.t, k, {th.b[0], th.b[1], th.b[2]}};
        break;
    }
    }
}

static void object_intersect(const scene *s, const object *o, scene_search *q)
{
    shape_intersect(s, o, q);
}

/* Fills the geometry of h for the nearest hit best, found along r. */
static void shape_fill_hit(const scene *s, const nearest_hit *best, ray r,
                           hit *h)
{
    (void)s;
    const object *o = best->object;
    switch (o->kind) {
    case SHAPE_SPHERE:
        sphere_fill_hit(&o->sphere, r, best->t, h);
        break;
    case SHAPE_TRIANGLE: {
        const vec3 *c = o->corners;
        triangle_fill_hit(c[0], c[1], c[2], r, best->t, h);
        break;
    }
    case SHAPE_MESH: {
        triangle_hit th = {best->t, {best->b[0], best->b[1], best->b[2]}};
        mesh_fill_hit(&s->meshes[o->mesh], best->primitive, r, &th, h);
        break;
    }
    }
}

static void object_fill_hit(const scene *s, const nearest_hit *best, ray r,
                            hit *h)
{
    const object *o = best->object;
    ray local = r; /* the ray in o's own space: the same until chapter 05 */
    shape_fill_hit(s, best, local, h);
    h->color = o->color;
    h->material = o->material;
}

/* Tests every object in turn. */
static void search_objects(const scene *s, scene_search *q)
{
    if (s->object_tree.node_count > 0) {
        search_object_tree(s, q);
        return;
    }
    for (int k = 0; k < s->object_count; k++)
        object_intersect(s, &s->objects[k], q);
}

bool scene_intersect(const scene *s, ray r, double t_min, double t_max,
                     hit *h, render_stats *stats)
{
    scene_search q = {.r = r, .t_min = t_min, .stats = stats,
                      .best = {.object = NULL, .t = t_max}};
    search_objects(s, &q);
    if (q.best.object == NULL)
        return false;
    object_fill_hit(s, &q.best, r, h);
    return true;
}

const material *scene_material(const scene *s, int index)
{
    return index == 0 ? &s->default_material : &s->materials[index - 1];
}

bool scene_add_material(scene *s, material m)
{
    material *grown = array_grow(s->materials, s->material_count,
                                 &s->material_capacity, SCENE_MAX_MATERIALS,
                                 sizeof m);
    if (grown == NULL)
        return false;
    s->materials = grown;
    s->materials[s->material_count++] = m;
    return true;
}

bool scene_add_light(scene *s, light L)
{
    light *grown = array_grow(s->lights, s->light_count, &s->light_capacity,
                              SCENE_MAX_LIGHTS, sizeof L);
    if (grown == NULL)
        return false;
    s->lights = grown;
    s->lights[s->light_count++] = L;
    return true;
}

int scene_add_mesh(scene *s, mesh m)
{
    mesh *grown = array_grow(s->meshes, s->mesh_count, &s->mesh_capacity,
                             SCENE_MAX_MESHES, sizeof m);
    if (grown == NULL)
        return -1;
    s->meshes = grown;
    s->meshes[s->mesh_count] = m;
    return s->mesh_count++;
}

/* The box around o, in the world. */
static box object_bounds(const scene *s, const object *o)
{
    box b = {{0, 0, 0}, {0, 0, 0}};
    switch (o->kind) {
    case SHAPE_SPHERE: {
        double r = o->sphere.radius;
        vec3 c = o->sphere.center, e = {r, r, r};
        b = (box){vec3_sub(c, e), vec3_add(c, e)};
        break;
    }
    case SHAPE_TRIANGLE: {
        const vec3 *p = o->corners;
        b = (box){vec3_min(p[0], vec3_min(p[1], p[2])),
                  vec3_max(p[0], vec3_max(p[1], p[2]))};
        break;
    }
    case SHAPE_MESH:
        b = s->meshes[o->mesh].bounds;
        break;
    }
    return b;
}

/* An object cut to a cell: its box cut to the cell (context: the boxes). */
static bool clip_object(const void *context, int item, const box *cell,
                        box *out)
{
    const box *b = (const box *)context + item;
    *out = (box){vec3_max(b->lo, cell->lo), vec3_min(b->hi, cell->hi)};
    return out->lo.x <= out->hi.x && out->lo.y <= out->hi.y &&
           out->lo.z <= out->hi.z;
}

static bool build_object_tree(scene *s)
{
    kdtree_params p = s->tree_params;
    p.min_items = p.min_items > 0 ? p.min_items : SCENE_TREE_MIN_OBJECTS;
    box *bounds = malloc(((size_t)s->object_count + 1) * sizeof *bounds);
    for (int k = 0; bounds != NULL && k < s->object_count; k++)
        bounds[k] = object_bounds(s, &s->objects[k]);
    bool ok = bounds != NULL && kdtree_build(&s->object_tree, s->object_count,
                                             bounds, clip_object, bounds, &p);
    free(bounds);
    return ok;
}

bool scene_build_trees(scene *s)
{
    struct timespec start, end;
    clock_gettime(CLOCK_MONOTONIC, &start);
    bool ok = true;
    for (int k = 0; ok && k < s->mesh_count; k++)
        ok = mesh_build_tree(&s->meshes[k], &s->tree_params);
    ok = ok && build_object_tree(s);
    clock_gettime(CLOCK_MONOTONIC, &end);
    s->tree_seconds = (double)(end.tv_sec - start.tv_sec) +
                      1e-9 * (double)(end.tv_nsec - start.tv_nsec);
    return ok;
}

static void add_tree(scene_tree_summary *sum, const kdtree *t)
{
    if (t->node_count == 0)
        return;
    sum->trees++;
    sum->nodes += t->node_count;
    sum->leaves += t->leaf_count;
    sum->references += t->item_count;
    sum->depth = t->depth > sum->depth ? t->depth : sum->depth;
}

scene_tree_summary scene_trees(const scene *s)
{
    scene_tree_summary sum = {0};
    for (int k = 0; k < s->mesh_count; k++) {
        add_tree(&sum, &s->meshes[k].tree);
        sum.items += s->meshes[k].tree.node_count ? s->meshes[k].triangle_count
                                                  : 0;
    }
    add_tree(&sum, &s->object_tree);
    sum.items += s->object_tree.node_count ? s->object_count : 0;
    return sum;
}

/* Where p, in front of the eye, falls on the image: pixel coordinates. */
static void pixel_of(const camera_view *v, vec3 p, double *u, double *w)
{
    *u = (p.x / p.z - v->left) / v->pixel_size;
    *w = (v->top - p.y / p.z) / v->pixel_size;
}

double scene_object_pixels(const scene *s, const object *o)
{
    box b = object_bounds(s, o);
    camera_view view = camera_view_of(&s->cam);
    double u0 = INFINITY, u1 = -INFINITY, w0 = INFINITY, w1 = -INFINITY;
    for (int k = 0; k < 8; k++) {
        vec3 p = {k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y,
                  k & 4 ? b.hi.z : b.lo.z};
        double u, w;
        if (!(p.z > 0))
            return 0;
        pixel_of(&view, p, &u, &w);
        u0 = fmin(u0, u), u1 = fmax(u1, u), w0 = fmin(w0, w), w1 = fmax(w1, w);
    }
    u0 = fmax(u0, 0), u1 = fmin(u1, s->cam.width);
    w0 = fmax(w0, 0), w1 = fmin(w1, s->cam.height);
    return u1 > u0 && w1 > w0 ? (u1 - u0) * (w1 - w0) : 0;
}
