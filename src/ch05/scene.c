/* scene.c: the scene's defaults, its contents, and the queries over them
 * (chapter 1). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

/* <<scene helpers>> ch02 */
#include "array.h"

void scene_init(scene *s)
{
    memset(s, 0, sizeof *s);
    s->cam.fov_deg = 60.0;
    s->cam.width = 320;
    s->cam.height = 240;
    s->bg.kind = BACKGROUND_GRADIENT;
    s->bg.bottom = (vec3){1.0, 1.0, 1.0};
    s->bg.top = (vec3){0.3, 0.5, 1.0};
    /* <<scene member defaults>> ch03 */
    s->ambient = (vec3){1, 1, 1};
    s->tone.alpha = s->tone.beta = 1;
    s->default_material = material_default();
    s->default_light = (light){.kind = LIGHT_DIRECTIONAL,
                               .direction = vec3_normalize((vec3){1, -1, 1}),
                               .intensity = {1, 1, 1}};
    /* <<scene member defaults>> += ch04 */
    s->triangle_budget = SCENE_MAX_TRIANGLES;
    s->geometry_budget = SCENE_MAX_GEOMETRY_BYTES;
    /* <<scene member defaults>> += ch05 */
    s->cam.look_at = (vec3){0, 0, 1}; /* where chapter 1's camera looks */
    s->cam.up = (vec3){0, 1, 0};
}

void scene_free(scene *s)
{
    /* <<free scene members>> ch02 */
    free(s->objects);
    /* <<free scene members>> += ch03 */
    free(s->materials);
    free(s->lights);
    /* <<free scene members>> += ch04 */
    for (int k = 0; k < s->mesh_count; k++)
        mesh_free(&s->meshes[k]);
    free(s->meshes);
    free(s->mesh_index);
    /* <<free scene members>> += ch05 */
    free(s->transforms);
    memset(s, 0, sizeof *s); /* a second scene_free finds nothing to free */
}

/* <<scene contents>> ch02 */
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

/* <<the search for the nearest hit>> ch02 */
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
    /* <<search members>> ch04 */
    mesh_ray prepared; /* valid once is_prepared is set */
    bool is_prepared;
} scene_search;

/* <<search helpers>> ch04 */
/* The search's ray with its per-ray constants, made on first use. */
static const mesh_ray *prepared_ray(scene_search *q)
{
    if (!q->is_prepared)
        q->prepared = mesh_ray_of(q->r), q->is_prepared = true;
    return &q->prepared;
}
/* <<search helpers>> += ch05 */

static void shape_intersect(const scene *s, const object *o,
                            scene_search *q);

/* r in the object's space: o' = M^-1 o, d' = M^-1 d. d' is not
 * normalised, so that o' + t d' = M^-1 (o + t d): the same t. */
static ray ray_to_object(const transform *t, ray r)
{
    return (ray){mat4_mul_point(t->inv, r.origin),
                 mat4_mul_dir(t->inv, r.dir)};
}

/* Tests the placed object o with q's ray taken into its space; q's best
 * hit narrows when o is hit nearer. */
static void search_placed_object(const scene *s, const object *o,
                                 scene_search *q)
{
    scene_search local = *q;
    local.r = ray_to_object(scene_transform(s, o->transform), q->r);
    local.is_prepared = false; /* the world ray's shear is not this ray's */
    q->stats->object_space_rays++;
    shape_intersect(s, o, &local);
    q->best = local.best;
}

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

/* Narrows q->best when q->r, the ray in o's own space, hits o's shape
 * nearer than q->best.t. */
static void shape_intersect(const scene *s, const object *o, scene_search *q)
{
    (void)s; /* chapter 4's meshes live in the scene */
    double t;
    switch (o->kind) {
    case SHAPE_SPHERE:
        q->stats->sphere_tests++;
        if (sphere_hit_t(&o->sphere, q->r, q->t_min, q->best.t, &t))
            q->best = (nearest_hit){.object = o, .t = t};
        break;
    /* <<intersect the other shapes>> ch04 */
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
        triangle_hit th = {0}; /* filled whenever k >= 0 */
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
    /* <<search an object in its own space>> ch05 */
    if (o->transform != 0) {
        search_placed_object(s, o, q);
        return;
    }
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
    /* <<fill the hits of the other shapes>> ch04 */
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
    ray local = r; /* the ray in o's own space: the same until chapter 5 */
    /* <<take the ray into the object's space>> ch05 */
    const transform *placed =
        o->transform != 0 ? scene_transform(s, o->transform) : NULL;
    if (placed != NULL)
        local = ray_to_object(placed, r);
    shape_fill_hit(s, best, local, h);
    /* <<bring the hit back into the world>> ch05 */
    if (placed != NULL)
        hit_to_world(placed, r, h);
    h->color = o->color;
    /* <<fill the object's part of the hit>> ch03 */
    h->material = o->material;
}

/* Tests every object in turn. */
static void search_objects(const scene *s, scene_search *q)
{
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
    stats->hits++;
    object_fill_hit(s, &q.best, r, h);
    return true;
}
/* <<scene contents>> += ch03 */

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
/* <<scene contents>> += ch04 */

/* FNV-1a over n bytes, continuing from h. */
static unsigned long long fnv1a(unsigned long long h, const void *bytes,
                                size_t n)
{
    const unsigned char *b = bytes;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 1099511628211ULL;
    return h;
}

/* Where the index starts looking for source. */
static size_t first_slot(const mesh_source *source, int size)
{
    const mesh_source *c = source; /* + 0.0: -0.0 hashes as 0.0, its equal */
    double numbers[4] = {c->scale + 0.0, c->offset.x + 0.0,
                         c->offset.y + 0.0, c->offset.z + 0.0};
    unsigned long long h = fnv1a(14695981039346656037ULL, c->path,
                                 strlen(c->path));
    h = fnv1a(h, numbers, sizeof numbers);
    h = fnv1a(h, &c->smooth, sizeof c->smooth);
    return (size_t)(h & (unsigned long long)(size - 1));
}

static size_t next_slot(const scene *s, size_t slot)
{
    return (slot + 1) & (size_t)(s->mesh_index_size - 1);
}

static void index_mesh(scene *s, int k)
{
    size_t slot = first_slot(&s->meshes[k].source, s->mesh_index_size);
    while (s->mesh_index[slot] != 0)
        slot = next_slot(s, slot);
    s->mesh_index[slot] = k + 1;
}

/* Room in the index for one more mesh; false when out of memory. */
static bool grow_index(scene *s)
{
    if (2 * (s->mesh_count + 1) < s->mesh_index_size)
        return true;
    int size = s->mesh_index_size ? 2 * s->mesh_index_size : 64;
    int *index = calloc((size_t)size, sizeof *index);
    if (index == NULL)
        return false;
    free(s->mesh_index);
    s->mesh_index = index, s->mesh_index_size = size;
    for (int k = 0; k < s->mesh_count; k++)
        if (s->meshes[k].source.path != NULL)
            index_mesh(s, k);
    return true;
}

int scene_add_mesh(scene *s, mesh m)
{
    mesh *grown = array_grow(s->meshes, s->mesh_count, &s->mesh_capacity,
                             SCENE_MAX_MESHES, sizeof m);
    if (grown == NULL)
        return -1;
    s->meshes = grown;
    if (!grow_index(s))
        return -1;
    s->meshes[s->mesh_count] = m;
    if (m.source.path != NULL)
        index_mesh(s, s->mesh_count);
    s->triangle_total += m.triangle_count;
    s->geometry_total += mesh_bytes(&m);
    return s->mesh_count++;
}

int scene_find_mesh(const scene *s, const mesh_source *source)
{
    if (s->mesh_index_size == 0 || source->path == NULL)
        return -1;
    size_t slot = first_slot(source, s->mesh_index_size);
    for (; s->mesh_index[slot] != 0; slot = next_slot(s, slot)) {
        int k = s->mesh_index[slot] - 1;
        if (mesh_source_equal(&s->meshes[k].source, source))
            return k;
    }
    return -1;
}
/* <<scene contents>> += ch05 */

int scene_add_transform(scene *s, transform t)
{
    transform *grown =
        array_grow(s->transforms, s->transform_count, &s->transform_capacity,
                   SCENE_MAX_TRANSFORMS, sizeof t);
    if (grown == NULL)
        return -1;
    s->transforms = grown;
    s->transforms[s->transform_count++] = t;
    return s->transform_count;
}

const transform *scene_transform(const scene *s, int k)
{
    return &s->transforms[k - 1];
}

void scene_count_triangles(const scene *s, long long *stored,
                           long long *instanced)
{
    *stored = *instanced = 0;
    for (int k = 0; k < s->mesh_count; k++)
        *stored += s->meshes[k].triangle_count;
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind == SHAPE_MESH)
            *instanced += s->meshes[o->mesh].triangle_count;
        if (o->kind == SHAPE_TRIANGLE)
            ++*stored, ++*instanced;
    }
}
