/* ch10_acne.c: the float path's shadow rays, offset by double's bound and
 * by float's.
 *
 *   build/rel/failures/ch10_acne figures/ch10-failure-acne.png
 *
 * The bunny, its BVH's leaves decided in float alone (accelerator
 * bvh-float), lit by one directional light. Each pixel's ray finds its
 * hit through the float path, and a shadow ray leaves the hit towards
 * the light through the float path too. On the left the hit's point is
 * bounded as chapter 6 bounds a hit of chapter 4's test in double
 * (triangle_refine_hit); on the right as the program bounds a hit of a
 * mesh decided in float (mesh_refine_hit). A lit point is drawn in the
 * mesh's colour by its Lambert term, a point in shadow by the ambient
 * light alone. Each half is magnified twice. Compares every pixel with
 * the exact path (the same tree, its leaves decided in double, its hits
 * bounded by chapter 6): prints the pixels that are in shadow in a half
 * and lit in the exact path (in their own shadow), and the others that
 * differ, and exits 1 unless the left has more than a third of the
 * bunny's pixels in their own shadow, and the right none, and at most
 * 0.1% of the pixels unlike the exact path's.
 *
 * Built by `make failures` (rule $(B)/failures/ch10_%) against the objects
 * of chapter 10's program but main.o; `make test` checks the committed
 * PNG. */
#include <string.h>

#include "failure_util.h"
#include "offset.h"
#include "scene_file.h"

#define W 200    /* pixels across each half */
#define H 150    /* pixels down */
#define SCALE 2  /* magnification of each half in the figure */

static const char SCENE[] =
    "camera fov 32 position 0 0.3 0 look_at 0.05 -0.3 5.6\n"
    "accelerator bvh-float\n"
    "mesh file meshes/bunny.obj scale 12 offset 0.45 -1.4 5.6 smooth\n";

static const vec3 BACKGROUND = {0.45, 0.55, 0.8};
static const vec3 COLOR = {0.85, 0.8, 0.7};
static const vec3 TO_LIGHT = {-0.6, 0.7, -0.4}; /* normalised at use */

/* How the point of a hit on triangle k at w is bounded. */
typedef enum { DOUBLES_BOUND, THE_PROGRAMS_BOUND } bound_kind;

/* Pixel (i, j) through m: -1 for a miss, 0 for a point in shadow, 1 for
 * a lit one; its colour in *color. */
static int trace_pixel(const mesh *m, const camera_view *view, int i, int j,
                       bound_kind bound, vec3 *color)
{
    render_stats st = {0};
    ray r = camera_view_ray(view, i, j);
    mesh_ray mr = mesh_ray_of(r);
    triangle_hit th;
    int k = mesh_nearest(m, &mr, 0, INFINITY, &th, &st);
    *color = BACKGROUND;
    if (k < 0)
        return -1;
    hit h;
    mesh_fill_hit(m, k, r, &th, &h);
    if (bound == DOUBLES_BOUND) {
        const int *v = m->triangles[k].v;
        triangle_refine_hit(m->vertices[v[0]], m->vertices[v[1]],
                            m->vertices[v[2]], th.b, &h);
    } else
        mesh_refine_hit(m, k, th.b, &h);
    vec3 l = vec3_normalize(TO_LIGHT);
    double facing = vec3_dot(h.normal, l);
    mesh_ray shadow = mesh_ray_of(ray_leaving(&h, l));
    bool lit = facing > 0 && !mesh_occluded(m, &shadow, 0, INFINITY, &st);
    *color = vec3_scale(COLOR, 0.25 + (lit ? 0.75 * facing : 0));
    return lit;
}

/* The pixels of a half that differ from the exact path: in shadow where
 * it is lit (their own shadow), or any other difference. */
typedef struct {
    long own_shadow, other;
} pixel_count;

/* Draws half through the float mesh with the bound, counting in *n its
 * differences from the exact mesh's pixels. */
static void draw_half(const mesh *in_float, const mesh *exact,
                      const camera_view *view, bound_kind bound, image *half,
                      pixel_count *n, long *hits)
{
    *hits = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            vec3 color, unused;
            int seen = trace_pixel(in_float, view, i, j, bound, &color);
            int truth = trace_pixel(exact, view, i, j, THE_PROGRAMS_BOUND,
                                    &unused);
            *hits += truth >= 0;
            n->own_shadow += seen == 0 && truth == 1;
            n->other += seen != truth && !(seen == 0 && truth == 1);
            image_set(half, i, j, color);
        }
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    scene_error err;
    scene_init(&s);
    if (!scene_parse(&s, SCENE, strlen(SCENE), "SCENE", &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col,
                err.message);
        scene_free(&s);
        return 2;
    }
    s.cam.width = W, s.cam.height = H;
    const mesh *in_float = &s.meshes[0];
    mesh exact = *in_float; /* the same arrays and tree, decided in double */
    exact.bvh_in_float = false;
    camera_view view = camera_view_of(&s.cam);
    image left = {0}, right = {0};
    pixel_count n[2] = {{0, 0}, {0, 0}};
    long hits = 0;
    bool ok = in_float->bvh_in_float && image_init(&left, W, H) &&
              image_init(&right, W, H);
    if (ok) {
        draw_half(in_float, &exact, &view, DOUBLES_BOUND, &left, &n[0], &hits);
        draw_half(in_float, &exact, &view, THE_PROGRAMS_BOUND, &right, &n[1],
                  &hits);
        ok = write_side_by_side(&left, &right, SCALE, path);
        printf("%s: of %ld pixels on the bunny, in their own shadow: %ld "
               "with double's bound (%ld other differences), %ld with the "
               "program's (%ld other differences)\n", path, hits,
               n[0].own_shadow, n[0].other, n[1].own_shadow, n[1].other);
    } else
        fprintf(stderr, "%s: error: no bunny in float\n", path);
    scene_free(&s);
    image_free(&left);
    image_free(&right);
    bool shows = 3 * n[0].own_shadow > hits && n[1].own_shadow == 0 &&
                 1000 * n[1].other <= W * H;
    if (ok && !shows)
        fprintf(stderr, "%s: error: the naive half no longer fails alone\n",
                path);
    return ok && shows ? 0 : 1;
}
