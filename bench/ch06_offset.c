/* ch06_offset.c: shadow rays that hit their own surface, and shadows lost
 * to the cure, for four ways of starting a ray on a surface, as the scene
 * is scaled and moved away from the origin.
 *
 *   build/rel/bench/ch06_offset > figures/ch06-offset.csv
 *
 * The scene, at scale 1: a floor (two triangles, 8 x 8), a sphere of
 * radius 1 and an icosphere mesh of radius 1 (320 triangles) resting on
 * it, and a card (two triangles) leaning on the floor with one edge: a
 * slope of 1 in 3. At scale S every coordinate x becomes S (x + (3, 2, 4)):
 * the scene is S wide and S away from the origin. A directional light
 * shines almost straight down.
 *
 * Self-hits. Points on surfaces that are lit (the tops of both spheres, the
 * floor in front of everything, the card's top), each reached by a ray
 * from 3 units above it at up to 60 degrees from its normal, so that the
 * hit point carries a renderer's rounding. A shadow ray from such a point
 * that reports a hit has hit its own surface (or its mesh's neighbour).
 *
 * Lost contact shadows. Points on the floor under the card, at distances x
 * from its edge spread evenly in log x from 1e-7 to 1e-1 (the card is then
 * x/3 above them): all are in the card's shadow. A shadow ray that reports
 * no hit has lost it.
 *
 * Methods: none (t > 0), epsilon (t > 1e-4), normal (origin moved 1e-4
 * along the geometric normal), skip (the sphere or triangle left is not
 * tested), bound (the program's ray_leaving). All in double, through the
 * program's scene_intersect for the hit; none, epsilon, normal and skip
 * also in float, as a renderer built on float vectors (the sheet's
 * glm::vec3) would compute them. Rows:
 *   METHOD-PRECISION,SCALE,ns_per_shadow_ray,fraction,self_hit_rate
 *   METHOD-PRECISION,SCALE,ns_per_shadow_ray,fraction,lost_contact_rate
 * Columns: method,param,ns_per_op,error,error_kind.
 *
 * As a side effect it renders figures/ch06-acne-naive.png: the scene file
 * scenes/ch06-acne.scene (the tangled copy) shaded as the program shades
 * it, but with every hit point and shadow ray in float and t > 1e-4. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/rng.h"
#include "scene_file.h"
#include "render.h"
#include "offset.h"
#include "search.h"
#include "shade.h"
#include "timing.h"

#define EPSILON 1e-4 /* the fixed t_min and normal offset, in scene units */

/* ---------------------------------------------------------------- the scene */

static double S; /* the scale of the scene being built */

static vec3 place(vec3 p) { return (vec3){S * (p.x + 3), S * (p.y + 2), S * (p.z + 4)}; }

static void add_triangle(scene *s, vec3 a, vec3 b, vec3 c)
{
    object o = {.kind = SHAPE_TRIANGLE, .corners = {place(a), place(b), place(c)}};
    if (!scene_add_object(s, o))
        abort();
}

/* An icosahedron subdivided twice onto the sphere (center, 1): 320 triangles. */
static void add_icosphere(scene *s, vec3 center)
{
    double g = (1 + sqrt(5.0)) / 2;
    const double c[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    static vec3 v[200];
    static int faces[400][3], next[400][3], cache[200][200];
    int nv = 12, nf = 20;
    for (int k = 0; k < 12; k++)
        v[k] = vec3_normalize((vec3){c[k][0], c[k][1], c[k][2]});
    memcpy(faces, f, sizeof f);
    for (int round = 0; round < 2; round++) {
        memset(cache, -1, sizeof cache);
        int n = 0;
        for (int k = 0; k < nf; k++) {
            int m[3];
            for (int e = 0; e < 3; e++) {
                int a = faces[k][e], b = faces[k][(e + 1) % 3];
                if (cache[a][b] < 0) {
                    v[nv] = vec3_normalize(vec3_add(v[a], v[b]));
                    cache[a][b] = cache[b][a] = nv++;
                }
                m[e] = cache[a][b];
            }
            int quads[4][3] = {{faces[k][0], m[0], m[2]}, {faces[k][1], m[1], m[0]},
                               {faces[k][2], m[2], m[1]}, {m[0], m[1], m[2]}};
            memcpy(next[n], quads, sizeof quads);
            n += 4;
        }
        memcpy(faces, next, (size_t)n * sizeof faces[0]);
        nf = n;
    }
    mesh mh = {0};
    mh.vertices = malloc((size_t)nv * sizeof *mh.vertices);
    mh.triangles = malloc((size_t)nf * sizeof *mh.triangles);
    if (!mh.vertices || !mh.triangles)
        abort();
    for (int k = 0; k < nv; k++)
        mh.vertices[k] = place(vec3_add(center, v[k]));
    for (int k = 0; k < nf; k++)
        mh.triangles[k] = (mesh_triangle){{faces[k][0], faces[k][1], faces[k][2]}};
    mh.vertex_count = mh.vertex_capacity = nv;
    mh.triangle_count = mh.triangle_capacity = nf;
    mesh_compute_bounds(&mh);
    object o = {.kind = SHAPE_MESH, .mesh = scene_add_mesh(s, mh)};
    if (o.mesh < 0 || !scene_add_object(s, o))
        abort();
}

enum { FLOOR_A, FLOOR_B, SPHERE, ICOSPHERE, CARD_A, CARD_B };
static const vec3 SPHERE_CENTER = {-1.5, 1, 0}, ICO_CENTER = {1.5, 1, 0};
static const vec3 CARD[4] = {{-1, 0, 2}, {1, 0, 2}, {1, 0.5, 3.5}, {-1, 0.5, 3.5}};

static void build_scene(scene *s, double scale)
{
    S = scale;
    scene_init(s);
    add_triangle(s, (vec3){-4, 0, -4}, (vec3){4, 0, -4}, (vec3){4, 0, 4});
    add_triangle(s, (vec3){-4, 0, -4}, (vec3){4, 0, 4}, (vec3){-4, 0, 4});
    object sp = {.kind = SHAPE_SPHERE, .sphere = {place(SPHERE_CENTER), S}};
    if (!scene_add_object(s, sp))
        abort();
    add_icosphere(s, ICO_CENTER);
    add_triangle(s, CARD[0], CARD[1], CARD[2]);
    add_triangle(s, CARD[0], CARD[2], CARD[3]);
}

/* ---------------------------------------------------------------- the samples */

static rng_state rng;
static double uniform01(void) { return rng_uniform01(&rng); }

typedef struct {
    vec3 origin, target; /* at scale 1 */
    int object;          /* the object the target is on */
    bool contact;        /* true: in the card's shadow; false: lit */
} sample;

#define N_EACH 1500
#define N_SAMPLES (5 * N_EACH)
static sample samples[N_SAMPLES];
static int n_samples;
static vec3 light_dir; /* towards the light, unit */

static void add_lit(vec3 target, vec3 normal, int object)
{
    vec3 out = rng_near_direction(&rng, normal);
    samples[n_samples++] = (sample){vec3_add(target, vec3_scale(out, 3)), target, object, false};
}

static void make_samples(void)
{
    rng = (rng_state){0x853C49E6748FEA9BULL}; /* fixed seed: the same samples every run */
    light_dir = vec3_normalize((vec3){-0.1, 1, -0.05});
    n_samples = 0;
    for (int k = 0; k < N_EACH; k++) { /* the sphere's top: <n, l> > 0.3 */
        vec3 n;
        do
            n = rng_near_direction(&rng, light_dir);
        while (vec3_dot(n, light_dir) < 0.3);
        add_lit(vec3_add(SPHERE_CENTER, n), n, SPHERE);
        add_lit(vec3_add(ICO_CENTER, n), n, ICOSPHERE); /* near the mesh */
    }
    for (int k = 0; k < N_EACH; k++) { /* the floor in front of everything */
        vec3 p = {-3.8 + 7.6 * uniform01(), 0, -3.8 + 2.2 * uniform01()};
        add_lit(p, (vec3){0, 1, 0}, -1);
    }
    vec3 card_n = vec3_normalize((vec3){0, 1.5, -0.5});
    for (int k = 0; k < N_EACH; k++) { /* the card's top */
        double u = 0.05 + 0.9 * uniform01(), v = 0.05 + 0.9 * uniform01();
        vec3 p = {-1 + 2 * u, 0.5 * v, 2 + 1.5 * v};
        add_lit(p, card_n, -1);
    }
    for (int k = 0; k < N_EACH; k++) { /* under the card */
        double x = pow(10, -7 + 6 * (k + 0.5) / N_EACH);
        vec3 p = {-0.9 + 1.8 * uniform01(), 0, 2 + x};
        samples[n_samples++] = (sample){{p.x, 0.2, 3.8}, p, -1, true};
    }
}

/* ---------------------------------------------------------------- any hit, skipping */

/* Any hit along r in (t_min, t_max), not counting object skip_object or
 * triangle skip_triangle of a mesh. real_float: every test in float. */
static bool occluded(const scene *s, ray r, double t_min, double t_max, int skip_object,
                     int skip_triangle, bool in_float)
{
    triangle_method tri = in_float ? triangle_hit_watertight_float : triangle_hit_watertight;
    triangle_hit th;
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (k == skip_object && o->kind != SHAPE_MESH)
            continue;
        if (o->kind == SHAPE_SPHERE) {
            double t[2];
            int n = (in_float ? sphere_roots_robust_float : sphere_roots_robust)(
                o->sphere.center, o->sphere.radius, r, t);
            for (int j = 0; j < n; j++)
                if (t[j] > t_min && t[j] < t_max)
                    return true;
        } else if (o->kind == SHAPE_TRIANGLE) {
            if (tri(o->corners[0], o->corners[1], o->corners[2], r, t_min, t_max, &th))
                return true;
        } else {
            const mesh *m = &s->meshes[o->mesh];
            for (int j = 0; j < m->triangle_count; j++) {
                const int *v = m->triangles[j].v;
                if (k == skip_object && j == skip_triangle)
                    continue;
                if (tri(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]], r, t_min, t_max,
                        &th))
                    return true;
            }
        }
    }
    return false;
}

/* The nearest hit, by the same tests: object, triangle of a mesh, t. */
static bool nearest(const scene *s, ray r, bool in_float, int *hit_object, int *triangle, double *t)
{
    triangle_method tri = in_float ? triangle_hit_watertight_float : triangle_hit_watertight;
    triangle_hit th;
    *t = INFINITY, *hit_object = -1;
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind == SHAPE_SPHERE) {
            double ts[2];
            int n = (in_float ? sphere_roots_robust_float : sphere_roots_robust)(
                o->sphere.center, o->sphere.radius, r, ts);
            for (int j = n - 1; j >= 0; j--)
                if (ts[j] > 0 && ts[j] < *t)
                    *t = ts[j], *hit_object = k, *triangle = 0;
        } else if (o->kind == SHAPE_TRIANGLE) {
            if (tri(o->corners[0], o->corners[1], o->corners[2], r, 0, *t, &th))
                *t = th.t, *hit_object = k, *triangle = 0;
        } else {
            const mesh *m = &s->meshes[o->mesh];
            for (int j = 0; j < m->triangle_count; j++) {
                const int *v = m->triangles[j].v;
                if (tri(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]], r, 0, *t, &th))
                    *t = th.t, *hit_object = k, *triangle = j;
            }
        }
    }
    return *hit_object >= 0;
}

/* ---------------------------------------------------------------- the methods */

#ifdef YOURS_OFFSET
/* make chart-ch06 WORKBOOK=1: the reader's offset (exercise 6.1), renamed
 * in a copy of the workbook's offset.o, as a sixth method "yours" (double
 * only, like bound) timed in the same rounds. */
vec3 yours_offset_origin(vec3 point, vec3 error, vec3 n_g, vec3 dir);
enum method { NONE, EPS, NORMAL, SKIP, BOUND, YOURS, N_METHODS };
static const char *const METHOD_NAMES[N_METHODS] = {"none",  "epsilon", "normal",
                                                    "skip",  "bound",   "yours"};
#define DRAWS_FIGURES 0 /* the reader's chart leaves figures/ alone */
#else
#define DRAWS_FIGURES 1
enum method { NONE, EPS, NORMAL, SKIP, BOUND, N_METHODS };
static const char *const METHOD_NAMES[N_METHODS] = {"none", "epsilon", "normal", "skip", "bound"};
#endif

/* A shadow ray's start, made once per sample and precision. */
typedef struct {
    vec3 point, error, n_g; /* the hit as the renderer has it */
    int object, triangle;
    bool valid, contact;
} start;

static start starts[2][N_SAMPLES]; /* [in_float][sample] */

static vec3 float_point(ray r, double t)
{
    float x = (float)r.origin.x + (float)t * (float)r.dir.x;
    float y = (float)r.origin.y + (float)t * (float)r.dir.y;
    float z = (float)r.origin.z + (float)t * (float)r.dir.z;
    return (vec3){x, y, z};
}

static vec3 geometric_normal(const scene *s, int index, int triangle, vec3 p)
{
    const object *o = &s->objects[index];
    if (o->kind == SHAPE_SPHERE)
        return vec3_normalize(vec3_sub(p, o->sphere.center));
    const vec3 *c = o->corners;
    vec3 m[3];
    if (o->kind == SHAPE_MESH) {
        const mesh *mh = &s->meshes[o->mesh];
        for (int k = 0; k < 3; k++)
            m[k] = mh->vertices[mh->triangles[triangle].v[k]];
        c = m;
    }
    return vec3_normalize(vec3_cross(vec3_sub(c[1], c[0]), vec3_sub(c[2], c[0])));
}

/* The hits of every sample at the current scale, in both precisions. */
static void make_starts(const scene *s)
{
    render_stats stats = {0};
    for (int k = 0; k < n_samples; k++) {
        const sample *sm = &samples[k];
        vec3 o = place(sm->origin);
        ray r = {o, vec3_normalize(vec3_sub(place(sm->target), o))};
        for (int f = 0; f < 2; f++) {
            start *st = &starts[f][k];
            double t;
            st->valid = nearest(s, r, f, &st->object, &st->triangle, &t);
            bool on_floor = st->object == FLOOR_A || st->object == FLOOR_B;
            bool on_card = st->object == CARD_A || st->object == CARD_B;
            if (sm->contact)
                st->valid &= on_floor;
            else if (sm->object >= 0)
                st->valid &= st->object == sm->object;
            else
                st->valid &= sm->target.y == 0 ? on_floor : on_card;
            st->contact = sm->contact;
            if (!st->valid)
                continue;
            if (f) {
                st->point = float_point(r, t);
                st->n_g = geometric_normal(s, st->object, st->triangle, st->point);
            } else {
                hit h;
                if (!scene_intersect(s, r, 0, INFINITY, &h, &stats))
                    abort();
                st->point = h.point, st->error = h.error, st->n_g = h.geometric_normal;
            }
        }
    }
}

/* The shadow ray of method m from st, and its t_min, in *t_min. */
static ray shadow_ray(enum method m, const start *st, bool in_float, double *t_min)
{
    *t_min = m == EPS ? EPSILON : 0;
    vec3 n = vec3_dot(st->n_g, light_dir) < 0 ? vec3_scale(st->n_g, -1) : st->n_g;
    vec3 o = st->point;
    if (m == NORMAL)
        o = vec3_add(o, vec3_scale(n, EPSILON));
    else if (m == BOUND)
        o = offset_origin(st->point, st->error, st->n_g, light_dir);
#ifdef YOURS_OFFSET
    else if (m == YOURS)
        o = yours_offset_origin(st->point, st->error, st->n_g, light_dir);
#endif
    if (in_float)
        o = (vec3){(float)o.x, (float)o.y, (float)o.z};
    return (ray){o, light_dir};
}

typedef struct {
    double self_hit_rate, lost_rate, ns;
} result;

/* Every shadow ray of method m once: how many say "blocked". */
static int run_method(const scene *s, enum method m, bool in_float, int *counted)
{
    int blocked = 0;
    for (int k = 0; k < n_samples; k++) {
        const start *st = &starts[in_float][k];
        if (!st->valid)
            continue;
        double t_min;
        ray r = shadow_ray(m, st, in_float, &t_min);
        bool skip = m == SKIP;
        blocked += occluded(s, r, t_min, INFINITY, skip ? st->object : -1,
                            skip ? st->triangle : -1, in_float);
        counted[0]++;
    }
    return blocked;
}

/* One timed case: a method, in a precision, on one scene's shadow rays. */
typedef struct {
    const scene *s;
    enum method m;
    bool in_float;
} offset_case;

/* reps shadow rays: whole passes over the scene's starting points. */
static void run_offset_case(void *ctx, long reps)
{
    const offset_case *c = ctx;
    for (long done = 0; done < reps;) {
        int counted = 0;
        bench_sink += run_method(c->s, c->m, c->in_float, &counted);
        done += counted > 0 ? counted : 1;
    }
}

/* The number of shadow rays in one pass of run_method. */
static long rays_per_pass(const scene *s, enum method m, bool in_float)
{
    int counted = 0;
    bench_sink += run_method(s, m, in_float, &counted);
    return counted > 0 ? counted : 1;
}

static result measure(const scene *s, enum method m, bool in_float)
{
    int self = 0, lit = 0, lost = 0, contact = 0;
    for (int k = 0; k < n_samples; k++) {
        const start *st = &starts[in_float][k];
        if (!st->valid)
            continue;
        double t_min;
        ray r = shadow_ray(m, st, in_float, &t_min);
        bool skip = m == SKIP;
        bool blocked = occluded(s, r, t_min, INFINITY, skip ? st->object : -1,
                                skip ? st->triangle : -1, in_float);
        if (st->contact)
            contact++, lost += !blocked;
        else
            lit++, self += blocked;
    }
    return (result){(double)self / lit, (double)lost / contact, 0};
}

/* ---------------------------------------------------------------- the naive picture */

/* The nearest hit in float: object, and the point as float arithmetic gives it. */
static vec3 naive_color(const scene *s, ray r)
{
    int index, triangle;
    double t;
    if (!nearest(s, r, true, &index, &triangle, &t))
        return background_color(&s->bg, r.dir);
    vec3 p = float_point(r, t);
    vec3 n = geometric_normal(s, index, triangle, p);
    if (vec3_dot(n, r.dir) > 0)
        n = vec3_scale(n, -1);
    const object *o = &s->objects[index];
    const material *m = scene_material(s, o->material);
    vec3 color = vec3_add(m->emission, vec3_scale(vec3_mul(o->color, s->ambient), m->ambient));
    for (int j = 0; j < s->light_count; j++) {
        light_sample ls = light_toward(&s->lights[j], p);
        double nl = vec3_dot(n, ls.l);
        if (nl <= 0 || occluded(s, (ray){p, ls.l}, EPSILON, ls.distance, -1, -1, true))
            continue; /* the sheet's shadow ray: from p itself, t > 1e-4 */
        color = vec3_add(color, vec3_mul(vec3_scale(o->color, m->diffuse * nl), ls.intensity));
    }
    return color;
}

static void render_naive(const char *scene_path, const char *out)
{
    scene s;
    scene_error err;
    scene_init(&s);
    if (!scene_load(&s, scene_path, &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col, err.message);
        exit(1);
    }
    image img;
    if (!image_init(&img, s.cam.width, s.cam.height))
        abort();
    camera_view view = camera_view_of(&s.cam);
    for (int j = 0; j < img.height; j++)
        for (int i = 0; i < img.width; i++)
            image_set(&img, i, j, naive_color(&s, camera_view_ray(&view, i, j)));
    char why[256];
    if (!image_write_png(&img, out, why, sizeof why)) {
        fprintf(stderr, "%s: %s\n", out, why);
        exit(1);
    }
    image_free(&img);
    scene_free(&s);
}

int main(int argc, char **argv)
{
    const char *acne_scene = argc > 1 ? argv[1] : "build/tangle/ch06/scenes/ch06-acne.scene";
    make_samples();
    bench_print_machine();
    bench_csv_header();
    const double scales[] = {1, 1e2, 1e4, 1e6};
    for (int k = 0; k < 4; k++) {
        scene s;
        build_scene(&s, scales[k]);
        make_starts(&s);
        offset_case ctx[2 * N_METHODS];
        bench_case cases[2 * N_METHODS];
        char names[2 * N_METHODS][48], param[32];
        snprintf(param, sizeof param, "%g", scales[k]);
        int n = 0;
        for (int f = 0; f < 2; f++)
            for (int m = 0; m < N_METHODS; m++) {
                if (f && m >= BOUND)
                    continue; /* the program's method (and yours) is double only */
                ctx[n] = (offset_case){&s, m, f};
                snprintf(names[n], sizeof names[n], "%s-%s", METHOD_NAMES[m],
                         f ? "float" : "double");
                cases[n] = (bench_case){names[n], param, run_offset_case, &ctx[n],
                                        rays_per_pass(&s, m, f)};
                n++;
            }
        bench_timing timing[2 * N_METHODS];
        bench_time_cases(cases, n, timing); /* the methods take turns */
        for (int c = 0; c < n; c++) {
            result r = measure(&s, ctx[c].m, ctx[c].in_float);
            bench_row(names[c], param, &timing[c], "%.6f", r.self_hit_rate, "self_hit_rate");
            bench_row(names[c], param, &timing[c], "%.6f", r.lost_rate, "lost_contact_rate");
        }
        fflush(stdout);
        scene_free(&s);
    }
    if (DRAWS_FIGURES)
        render_naive(acne_scene, "figures/ch06-acne-naive.png");
    return 0;
}
