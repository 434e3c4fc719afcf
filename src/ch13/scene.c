/* scene.c: the scene as a container: its defaults, what it owns, and the
 * arrays that hold its contents (chapter 1). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>
/* <<scene.c includes>> ch02 */
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
    /* <<scene member defaults>> += ch06 */
    s->max_depth = 64; /* a guarantee; the cutoff usually ends first */
    s->cutoff = 0.01;
    /* <<scene member defaults>> += ch08 */
    s->tree_params = kdtree_default_params();
    /* <<scene member defaults>> += ch13 */
    s->pixels = PIXEL_DEFAULTS;
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
    mesh_index_free(&s->mesh_index);
    /* <<free scene members>> += ch05 */
    free(s->transforms);
    /* <<free scene members>> += ch08 */
    kdtree_free(&s->object_tree);
    memset(s, 0, sizeof *s); /* a second scene_free finds nothing to free */
}

void scene_phase(const scene *s, const char *what)
{
    if (s->on_phase != NULL)
        s->on_phase(s->phase_context, what);
}

/* <<scene arrays>> ch02 */
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
/* <<scene arrays>> += ch03 */

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
/* <<scene arrays>> += ch04 */

int scene_add_mesh(scene *s, mesh m)
{
    mesh *grown = array_grow(s->meshes, s->mesh_count, &s->mesh_capacity,
                             SCENE_MAX_MESHES, sizeof m);
    if (grown == NULL)
        return -1;
    s->meshes = grown;
    if (!mesh_index_reserve(&s->mesh_index, s->meshes, s->mesh_count))
        return -1;
    s->meshes[s->mesh_count] = m;
    mesh_index_add(&s->mesh_index, s->meshes, s->mesh_count);
    s->triangle_total += m.triangle_count;
    s->geometry_total += mesh_bytes(&m);
    return s->mesh_count++;
}

int scene_find_mesh(const scene *s, const mesh_source *source)
{
    return mesh_index_find(&s->mesh_index, s->meshes, source);
}
/* <<scene arrays>> += ch05 */

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

/* <<whole-scene questions>> ch05 */

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
/* <<whole-scene questions>> += ch06 */

bool scene_can_shadow(const scene *s, const hit *h)
{
    if (s->object_count != 1)
        return s->object_count > 1; /* another object may be in the way */
    shape_kind kind = s->objects[0].kind;
    return kind == SHAPE_MESH || (kind == SHAPE_SPHERE && h->inside);
}

long scene_shadow_rays(const scene *s)
{
    long rays = 0;
    for (int k = 0; k < s->light_count; k++)
        rays += s->lights[k].kind == LIGHT_AREA ? s->lights[k].samples : 1;
    return rays;
}
