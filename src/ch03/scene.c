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
}

void scene_free(scene *s)
{
    /* <<free scene members>> ch02 */
    free(s->objects);
    /* <<free scene members>> += ch03 */
    free(s->materials);
    free(s->lights);
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
} scene_search;


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
    }
}

static void object_fill_hit(const scene *s, const nearest_hit *best, ray r,
                            hit *h)
{
    const object *o = best->object;
    ray local = r; /* the ray in o's own space: the same until chapter 5 */
    shape_fill_hit(s, best, local, h);
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
