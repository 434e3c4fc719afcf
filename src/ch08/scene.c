/* scene.c: the scene's defaults, its contents, and the queries over them
 * (chapter 1). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

/* <<scene helpers>> ch02 */
#include "array.h"
/* <<scene helpers>> += ch07 */

/* True where the checker of tile size s takes its second colour. */
static bool checker_is_odd(vec3 p, double s)
{
    /* cubes centred on multiples of s: floors at y = 0 fall mid-cube */
    double sum = floor(p.x / s + 0.5) + floor(p.y / s + 0.5) +
                 floor(p.z / s + 0.5);
    return fabs(fmod(sum, 2)) == 1;
}
/* <<scene helpers>> += ch08 */
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
    /* <<free scene members>> += ch08 */
    kdtree_free(&s->object_tree);
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
    /* <<search members>> += ch06 */
    bool any_hit; /* a shadow ray's search: the first hit settles it */
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
/* <<search helpers>> += ch06 */

/* The hit point moved back onto the sphere, with its error bound. */
static void sphere_refine_hit(const sphere *sp, hit *h)
{
    vec3 out = vec3_sub(h->point, sp->center);
    double length = vec3_length(out);
    if (!(length > 0)) { /* on the centre: no direction to push along */
        h->error = vec3_scale(vec3_abs(h->point), gamma_bound(8));
        return;
    }
    vec3 q = vec3_scale(out, sp->radius / length); /* 5 roundings */
    h->point = vec3_add(sp->center, q);            /* and 1 more */
    h->error = vec3_add(vec3_scale(vec3_abs(q), gamma_bound(5)),
                        vec3_scale(vec3_abs(h->point), gamma_bound(1)));
}

/* How wrong the watertight test's t can be for a ray that starts at p
 * near the triangle (a, b, c), as a distance from its plane. */
static double triangle_test_error(vec3 a, vec3 b, vec3 c, vec3 p)
{
    vec3 corners[3] = {a, b, c};
    double M = 0; /* the triangle's reach from p: largest coordinate */
    for (int k = 0; k < 3; k++) {
        vec3 r = vec3_abs(vec3_sub(corners[k], p));
        M = fmax(M, fmax(r.x, fmax(r.y, r.z)));
    }
    double twice_area = vec3_length(vec3_cross(vec3_sub(b, a),
                                               vec3_sub(c, a)));
    if (!(twice_area > 0))
        return INFINITY; /* never hit: the test rejects it */
    return sqrt(3) * (gamma_bound(3) * M +
                      48 * gamma_bound(4) * M * M * M / twice_area);
}

/* The hit point rebuilt from its barycentric coordinates w, with its
 * error bound, widened by the error of the test that could meet the
 * triangle again. */
static void triangle_refine_hit(vec3 a, vec3 b, vec3 c, const double w[3],
                                hit *h)
{
    vec3 pa = vec3_scale(a, w[0]), pb = vec3_scale(b, w[1]),
         pc = vec3_scale(c, w[2]);
    h->point = vec3_add(vec3_add(pa, pb), pc);
    vec3 sum = vec3_add(vec3_add(vec3_abs(pa), vec3_abs(pb)), vec3_abs(pc));
    double test = triangle_test_error(a, b, c, h->point);
    h->error = vec3_add(vec3_scale(sum, gamma_bound(7)),
                        (vec3){test, test, test});
}

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
    case SHAPE_MESH: {
        const mesh *m = &s->meshes[o->mesh];
        const int *v = m->triangles[best->primitive].v;
        triangle_refine_hit(m->vertices[v[0]], m->vertices[v[1]],
                            m->vertices[v[2]], best->b, h);
        break;
    }
    }
}

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
        bound[i] = (1 + gamma_bound(3)) * carried + gamma_bound(3) * product;
    }
    h->point = mat4_mul_point(t->m, p);
    h->error = (vec3){bound[0], bound[1], bound[2]};
}
/* <<search helpers>> += ch08 */

/* The world box around b's eight corners moved by t, widened by the
 * rounding of the move. */
static box box_to_world(const transform *t, box b)
{
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = vec3_scale(lo, -1);
    for (int k = 0; k < 8; k++) {
        vec3 p = mat4_mul_point(t->m, (vec3){k & 1 ? b.hi.x : b.lo.x,
                                             k & 2 ? b.hi.y : b.lo.y,
                                             k & 4 ? b.hi.z : b.lo.z});
        lo = vec3_min(lo, p), hi = vec3_max(hi, p);
    }
    vec3 reach = vec3_max(vec3_abs(lo), vec3_abs(hi));
    vec3 pad = vec3_scale(reach, gamma_bound(3));
    return (box){vec3_sub(lo, pad), vec3_add(hi, pad)};
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
    /* <<search an object in its own space>> += ch06 */
    if (q->any_hit && q->best.object != NULL)
        return; /* an occluder is found: no other object can change that */
    /* <<search an object in its own space>> += ch08 */
    if (q->any_hit && o->kind == SHAPE_MESH) {
        if (mesh_occluded(&s->meshes[o->mesh], prepared_ray(q), q->t_min,
                          q->best.t, q->stats))
            q->best.object = o; /* any hit settles a shadow ray */
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
    /* <<bound the rounding of the hit point>> ch06 */
    refine_hit_point(s, best, h);
    vec3 object_point = h->point, object_error = h->error;
    /* <<bring the hit back into the world>> ch05 */
    if (placed != NULL)
        hit_to_world(placed, r, h);
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
static void search_objects(const scene *s, scene_search *q)
{
    /* <<search the objects' tree>> ch08 */
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
/* <<scene contents>> += ch06 */

bool scene_occluded(const scene *s, ray r, double t_min, double t_max,
                    render_stats *stats)
{
    scene_search q = {.r = r, .t_min = t_min, .stats = stats,
                      .best = {.object = NULL, .t = t_max},
                      .any_hit = true};
    search_objects(s, &q);
    return q.best.object != NULL;
}

bool scene_can_shadow(const scene *s, const hit *h)
{
    if (s->object_count != 1)
        return s->object_count > 1; /* another object may be in the way */
    shape_kind kind = s->objects[0].kind;
    return kind == SHAPE_MESH || (kind == SHAPE_SPHERE && h->inside);
}
/* <<scene contents>> += ch08 */

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
    /* <<move the object's box into the world>> ch08 */
    if (o->transform != 0)
        b = box_to_world(scene_transform(s, o->transform), b);
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

/* A world point in the camera's frame: the placed camera's rotation R and
 * eye e give R^T (p - e); an unplaced camera's frame is the world's. */
static vec3 point_to_camera(const camera_view *v, vec3 p)
{
    if (!v->is_placed)
        return p;
    const double(*m)[4] = v->to_world.m;
    vec3 d = {p.x - m[0][3], p.y - m[1][3], p.z - m[2][3]};
    return (vec3){m[0][0] * d.x + m[1][0] * d.y + m[2][0] * d.z,
                  m[0][1] * d.x + m[1][1] * d.y + m[2][1] * d.z,
                  m[0][2] * d.x + m[1][2] * d.y + m[2][2] * d.z};
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
        vec3 p = point_to_camera(&view, (vec3){k & 1 ? b.hi.x : b.lo.x,
                                                k & 2 ? b.hi.y : b.lo.y,
                                                k & 4 ? b.hi.z : b.lo.z});
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
