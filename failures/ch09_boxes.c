/* ch09_boxes.c: a BVH whose float boxes are rounded to nearest, far from
 * the origin.
 *
 *   build/rel/failures/ch09_boxes figures/ch09-failure-boxes.png
 *
 * A rolling grid of COLS x COLS cells, each two triangles, lies a million
 * units from the origin, where neighbouring floats are 1/16 apart, and a
 * camera looks at it from a few units away. Its vertices are doubles that
 * no float holds. The left half finds each pixel's nearest triangle
 * through the naive BVH of ch09_naive_bvh.h: the program's tree, with its
 * boxes rounded to the nearest float and no pad, and the ray's origin
 * rounded to the nearest float; the right half through the program's own
 * BVH (mesh_nearest), its boxes rounded outward and padded. Both halves
 * are shaded alike, a check of two colours by |<n, d>|, and a pixel whose
 * ray finds nothing shows the dark background. Each half is magnified
 * twice. Prints the pixels whose answer (triangle or t) differs from
 * brute force's in each half, and exits 1 unless the naive half has some
 * and the program's none.
 *
 * Built by `make failures` (rule $(B)/failures/ch09_%) against the objects
 * of chapter 9's program but main.o; `make test` checks the committed PNG. */
#include <string.h>

#include "scene_file.h"
#include "failure_util.h"
#include "ch09_naive_bvh.h"

#define SIZE 160  /* pixels a side of each half */
#define SCALE 2   /* magnification of each half in the figure */
#define COLS 12   /* cells a side of the grid */
#define CELL 0.25 /* units: four float steps at a million */

/* The grid's corner: a million, and a little that no float there holds. */
static const vec3 CORNER = {1e6 + 0.0123, 1e6 + 0.0271, 1e6 + 0.0417};

static const char SCENE[] =
    "camera fov 60 position 1000001.5123 999999.9771 999998.5417 "
    "look_at 1000001.5123 1000001.5271 1000000.0417\n";

static const vec3 BACKGROUND = {0.08, 0.09, 0.14};
static const vec3 CHECKS[2] = {{0.9, 0.65, 0.3}, {0.35, 0.6, 0.85}};

/* The height of grid vertex (i, j) above the grid's plane: gentle hills. */
static double height(int i, int j)
{
    return 0.12 * sin(0.9 * i + 0.4) * cos(0.7 * j - 0.3);
}

/* The grid: (COLS + 1)^2 vertices and 2 COLS^2 triangles, its BVH built
 * by the program; false when out of memory. */
static bool make_grid(mesh *m)
{
    int n = COLS + 1;
    *m = (mesh){.vertex_capacity = n * n, .triangle_capacity = 2 * COLS * COLS};
    m->vertices = malloc(sizeof *m->vertices * (size_t)(n * n));
    m->triangles = malloc(sizeof *m->triangles * 2 * COLS * COLS);
    if (m->vertices == NULL || m->triangles == NULL)
        return false;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            m->vertices[m->vertex_count++] = vec3_add(
                CORNER, (vec3){i * CELL, j * CELL, height(i, j)});
    for (int j = 0; j < COLS; j++)
        for (int i = 0; i < COLS; i++) {
            int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            m->triangles[m->triangle_count++] = (mesh_triangle){{a, b, d}};
            m->triangles[m->triangle_count++] = (mesh_triangle){{a, d, c}};
        }
    mesh_compute_bounds(m);
    return mesh_build_bvh(m, &(bvh_params){0});
}

/* m sharing its arrays, with no tree. */
static mesh bare(const mesh *m)
{
    mesh b = *m;
    b.tree = (kdtree){0}, b.leaf_corners = NULL, b.bvh = (bvh){0};
    return b;
}

/* The colour of triangle k's hit along r (k < 0: the background): its
 * cell's check, darker as the surface turns away. */
static vec3 shade_hit(const mesh *m, int k, ray r)
{
    if (k < 0)
        return BACKGROUND;
    const int *v = m->triangles[k].v;
    vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
    vec3 n = vec3_normalize(vec3_cross(vec3_sub(b, a), vec3_sub(c, a)));
    int cell = k / 2, check = (cell % COLS + cell / COLS) % 2;
    double facing = fabs(vec3_dot(n, vec3_normalize(r.dir)));
    return vec3_scale(CHECKS[check], 0.3 + 0.7 * facing);
}

/* What each half found unlike brute force: wrong[0] the naive BVH's
 * pixels, wrong[1] the program's; missed: the naive pixels that found
 * nothing where brute force found a triangle. */
typedef struct {
    long wrong[2], missed;
} pixel_count;

static bool same(int k1, const triangle_hit *h1, int k2,
                 const triangle_hit *h2)
{
    return k1 == k2 && (k1 < 0 || memcmp(&h1->t, &h2->t, sizeof h1->t) == 0);
}

/* Renders both halves: naive through the naive tree, program through
 * the program's, each pixel checked against brute force. */
static void render_halves(const camera *cam, const mesh *program,
                          const mesh *naive, const mesh *brute, image *left,
                          image *right, pixel_count *n)
{
    camera_view view = camera_view_of(cam);
    render_stats st = {0};
    for (int j = 0; j < SIZE; j++)
        for (int i = 0; i < SIZE; i++) {
            ray r = camera_view_ray(&view, i, j);
            mesh_ray mr = mesh_ray_of(r);
            triangle_hit h[3];
            int k[3] = {naive_bvh_nearest(naive, &mr, &h[0], &st),
                        mesh_nearest(program, &mr, 0, INFINITY, &h[1], &st),
                        mesh_nearest(brute, &mr, 0, INFINITY, &h[2], &st)};
            n->wrong[0] += !same(k[0], &h[0], k[2], &h[2]);
            n->wrong[1] += !same(k[1], &h[1], k[2], &h[2]);
            n->missed += k[0] < 0 && k[2] >= 0;
            image_set(left, i, j, shade_hit(brute, k[0], r));
            image_set(right, i, j, shade_hit(brute, k[1], r));
        }
}

/* The camera of SCENE, SIZE x SIZE; false if it does not parse. */
static bool make_camera(scene *s)
{
    scene_init(s);
    scene_error err;
    if (!scene_parse(s, SCENE, strlen(SCENE), "SCENE", &err))
        return false;
    s->cam.width = s->cam.height = SIZE;
    return true;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    mesh program = {0}, naive = {0}, brute = {0};
    image left = {0}, right = {0};
    pixel_count n = {{0, 0}, 0};
    bool ok = make_camera(&s) && make_grid(&program);
    if (ok) {
        brute = bare(&program), naive = bare(&program);
        ok = mesh_build_bvh(&naive, &(bvh_params){0}) &&
             image_init(&left, SIZE, SIZE) && image_init(&right, SIZE, SIZE);
    }
    if (ok) {
        naive_bvh_boxes(&naive, 0);
        render_halves(&s.cam, &program, &naive, &brute, &left, &right, &n);
        ok = write_side_by_side(&left, &right, SCALE, path);
        printf("%s: of %d pixels, %ld differ from brute force through the "
               "BVH rounded to nearest (%ld of them find nothing), %ld "
               "through the program's\n",
               path, SIZE * SIZE, n.wrong[0], n.missed, n.wrong[1]);
    } else
        fprintf(stderr, "%s: error: cannot make the grid\n", path);
    mesh_free_tree(&naive);
    mesh_free(&program);
    scene_free(&s);
    image_free(&left);
    image_free(&right);
    bool shows = n.wrong[0] > 0 && n.wrong[1] == 0;
    if (ok && !shows)
        fprintf(stderr, "%s: error: the naive half no longer fails alone\n",
                path);
    return ok && shows ? 0 : 1;
}
