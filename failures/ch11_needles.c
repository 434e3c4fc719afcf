/* ch11_needles.c: the wide nodes a ray tests, through the bunny and
 * through needles.
 *
 *   build/rel/failures/ch11_needles figures/ch11-failure-needles.png
 *
 * Two meshes of as many triangles in the same box, the unit cube: the
 * bunny, scaled into it, and needles, each from a point on the cube's
 * surface to another, a thousandth of a unit wide, whose boxes are long
 * and overlap everywhere. The same SIZE x SIZE rays from an eye in front
 * of the cube are traced through each mesh's eight-wide BVH (the
 * program's, mesh_nearest, walked with the build's own instructions
 * on every machine), and each pixel shows the wide nodes whose
 * children its ray tested (--stats's count), black for none to white for
 * HOT or more, on a log scale. Left the needles, right the bunny; each half magnified
 * twice. Prints the mean count a ray over the rays that enter the cube,
 * and exits 1 unless the needles' is at least three times the bunny's.
 *
 * Built by `make failures` against the objects of chapter 11's program
 * but main.o; `make test` checks the committed PNG. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "failure_util.h"
#include "mesh.h"
#include "obj.h"

#define SIZE 160   /* pixels a side of each half */
#define SCALE 2    /* magnification of each half in the figure */
#define HOT 1000   /* nodes a ray drawn white (shades: a log scale) */
#define WIDTH 1e-3 /* of a needle */

/* x in [0, 1) from a 64-bit state (xorshift*): the needles' own numbers,
 * the same on every machine. */
static double uniform01(uint64_t *state)
{
    *state ^= *state >> 12, *state ^= *state << 25, *state ^= *state >> 27;
    return (double)((*state * 0x2545F4914F6CDD1Dull) >> 11) * 0x1p-53;
}

/* A point on the surface of the unit cube, at random. */
static vec3 point_on_cube(uint64_t *state)
{
    double p[3] = {uniform01(state), uniform01(state), uniform01(state)};
    int face = (int)(uniform01(state) * 3);
    p[face] = uniform01(state) < 0.5 ? 0 : 1;
    return (vec3){p[0], p[1], p[2]};
}

/* n needles across the unit cube into m; false when out of memory. */
static bool make_needles(mesh *m, int n)
{
    uint64_t state = 20261206;
    *m = (mesh){.vertex_capacity = 3 * n, .triangle_capacity = n};
    m->vertices = malloc(sizeof *m->vertices * 3 * (size_t)n);
    m->triangles = malloc(sizeof *m->triangles * (size_t)n);
    if (m->vertices == NULL || m->triangles == NULL)
        return false;
    for (int k = 0; k < n; k++) {
        vec3 a = point_on_cube(&state), b = point_on_cube(&state);
        vec3 side = {uniform01(&state) - 0.5, uniform01(&state) - 0.5,
                     uniform01(&state) - 0.5};
        side = vec3_scale(vec3_normalize(side), WIDTH);
        m->vertices[m->vertex_count++] = a;
        m->vertices[m->vertex_count++] = b;
        m->vertices[m->vertex_count++] = vec3_add(a, side);
        m->triangles[m->triangle_count++] = (mesh_triangle){{3 * k,
                                                             3 * k + 1,
                                                             3 * k + 2}};
    }
    mesh_compute_bounds(m);
    return true;
}

/* The bunny, scaled and moved into the unit cube; false if not read. */
static bool load_bunny(mesh *m)
{
    parse_error err;
    *m = (mesh){0};
    if (!mesh_load_obj(m, "meshes/bunny.obj", &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col,
                err.message);
        return false;
    }
    mesh_compute_bounds(m);
    vec3 lo = m->bounds.lo, size = vec3_sub(m->bounds.hi, lo);
    double s = 1 / fmax(size.x, fmax(size.y, size.z)); /* the longest: 1 */
    for (int k = 0; k < m->vertex_count; k++)
        m->vertices[k] = vec3_scale(vec3_sub(m->vertices[k], lo), s);
    mesh_compute_bounds(m);
    return true;
}

/* The ray of pixel (i, j): from an eye in front of the cube's centre,
 * looking along +z at it, 50 degrees across. */
static ray pixel_ray(int i, int j)
{
    double t = tan(25 * M_PI / 180);
    double dx = (2 * (i + 0.5) / SIZE - 1) * t;
    double dy = (1 - 2 * (j + 0.5) / SIZE) * t;
    return (ray){{0.5, 0.5, -1.2}, vec3_normalize((vec3){dx, dy, 1})};
}

/* Draws into img the nodes each ray through m tests; the mean over the
 * rays that enter m's box. */
static double draw_nodes(const mesh *m, image *img)
{
    long long nodes = 0, entering = 0;
    for (int j = 0; j < SIZE; j++)
        for (int i = 0; i < SIZE; i++) {
            mesh_ray mr = mesh_ray_of(pixel_ray(i, j));
            render_stats st = {0};
            triangle_hit th;
            mesh_nearest(m, &mr, 0, INFINITY, &th, &st);
            double near = 0, far = INFINITY;
            if (box_clip(&m->bounds, mr.r.origin, mr.inv_dir, &near, &far))
                entering++, nodes += st.bvh_nodes;
            double heat = fmin(1, log1p((double)st.bvh_nodes) / log1p(HOT));
            image_set(img, i, j, (vec3){heat, heat, heat});
        }
    return entering > 0 ? (double)nodes / (double)entering : 0;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    mesh bunny = {0}, needles = {0};
    image left = {0}, right = {0};
    bvh_params wide = {.width = 8};
    /* The walk of the build's own instructions: its node test gives the
     * same lanes on every machine (AVX2's fused test may open a box more
     * or less at the edge of float's rounding), and so the same figure. */
    bvh_allow_avx2(false);
    bool ok = load_bunny(&bunny) &&
              make_needles(&needles, bunny.triangle_count) &&
              mesh_build_bvh(&bunny, &wide) &&
              mesh_build_bvh(&needles, &wide) &&
              image_init(&left, SIZE, SIZE) && image_init(&right, SIZE, SIZE);
    double mean_needles = 0, mean_bunny = 0;
    if (ok) {
        mean_needles = draw_nodes(&needles, &left);
        mean_bunny = draw_nodes(&bunny, &right);
        ok = write_side_by_side(&left, &right, SCALE, path);
        printf("%s: wide nodes a ray tests, over the rays that enter the "
               "box: %.1f through %d needles, %.1f through the bunny\n",
               path, mean_needles, needles.triangle_count, mean_bunny);
    } else
        fprintf(stderr, "%s: error: cannot make the meshes\n", path);
    mesh_free(&bunny);
    mesh_free(&needles);
    image_free(&left);
    image_free(&right);
    bool shows = mean_needles >= 3 * mean_bunny && mean_bunny > 0;
    if (ok && !shows)
        fprintf(stderr, "%s: error: the needles no longer cost a ray more "
                "nodes than the bunny\n", path);
    return ok && shows ? 0 : 1;
}
