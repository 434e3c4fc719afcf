/* ch04_leaks.c: rays through the shared edges of a closed mesh.
 *
 *   build/rel/failures/ch04_leaks figures/ch04-failure-leaks.png
 *
 * The camera sits inside a closed mesh, a crumpled dome of triangles in
 * front of the eye closed by a fan to a point behind it, so every ray from
 * the eye must hit a triangle and the background should never show. The
 * dome's vertices lie on the rays of every CELL-th pixel, so that the
 * pixels along the grid lines and the cells' diagonals are aimed exactly
 * (to the last bit of rounding) at edges that two triangles share, and the
 * grid's crossings at vertices. The left half finds the nearest triangle by
 * Moller-Trumbore in double, at the origin; the right half is what chapter
 * 4's program renders (render: the watertight test). Both are shaded by
 * the program's shade, flat, with no highlight, so that a leak, a pixel of
 * the bright background, cannot pass for one. Each half is magnified twice.
 * Prints the leaking pixels of each half and exits 1 unless Moller-Trumbore
 * leaks some and the watertight test none.
 *
 * Built by `make failures` (rule $(B)/failures/ch04_%) against the objects
 * of chapter 4's program but main.o; `make test` checks the committed PNG. */
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "search.h"
#include "shade.h"
#include "failure_util.h"

#define CELL 8           /* pixels between neighbouring vertices of the dome */
#define COLS 13          /* cells across */
#define ROWS 10          /* cells down */
#define WIDTH (COLS * CELL + 1) /* the outer pixels lie on the rim's edges */
#define HEIGHT (ROWS * CELL + 1)
#define SCALE 3          /* magnification of each half in the figure */

static const char SCENE[] =
    "camera fov 60\n"
    "background 1 0.85 0.3\n"
    "ambient 0.25 0.25 0.3\n"
    "material default ambient 0.3 diffuse 0.8 specular 0\n"
    "light point position 0 0 0 intensity 0.5 0.5 0.55\n"
    "light point position -2 2 1 intensity 0.45 0.4 0.35\n";

static const vec3 COLOR = {0.12, 0.2, 0.35};

/* Distance of grid vertex (x, y) from the eye: 4.625 to 5 in steps
 * of 1/8, from a hash, exact in binary so that no libm enters the mesh. */
static double dome_radius(int x, int y)
{
    unsigned h = (unsigned)x * 73856093u ^ (unsigned)y * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return 4.625 + (h % 4) * 0.125;
}

static int vertex_index(int x, int y) { return y * (COLS + 1) + x; }

/* The two triangles of cell (x, y); the diagonal alternates. */
static void add_cell(mesh *m, int x, int y)
{
    int a = vertex_index(x, y), b = vertex_index(x + 1, y);
    int c = vertex_index(x, y + 1), d = vertex_index(x + 1, y + 1);
    mesh_triangle *t = &m->triangles[m->triangle_count];
    if ((x + y) % 2 == 0) /* diagonal a-d */
        t[0] = (mesh_triangle){{a, b, d}}, t[1] = (mesh_triangle){{a, d, c}};
    else                  /* diagonal b-c */
        t[0] = (mesh_triangle){{a, b, c}}, t[1] = (mesh_triangle){{b, d, c}};
    m->triangle_count += 2;
}

#define RIM (2 * (COLS + ROWS))                 /* grid vertices on the rim */
#define APEX ((COLS + 1) * (ROWS + 1))          /* the vertex behind the eye */
#define TRIANGLES (2 * COLS * ROWS + RIM)

/* The grid vertices around the rim in order, into rim[RIM]. */
static void rim_vertices(int rim[RIM])
{
    int n = 0;
    for (int x = 0; x < COLS; x++)
        rim[n++] = vertex_index(x, 0);
    for (int y = 0; y < ROWS; y++)
        rim[n++] = vertex_index(COLS, y);
    for (int x = COLS; x > 0; x--)
        rim[n++] = vertex_index(x, ROWS);
    for (int y = ROWS; y > 0; y--)
        rim[n++] = vertex_index(0, y);
}

/* An empty mesh with room for the dome; false when out of memory. */
static bool alloc_dome(mesh *m)
{
    *m = (mesh){.vertex_capacity = APEX + 1, .triangle_capacity = TRIANGLES};
    m->vertices = malloc(sizeof *m->vertices * (APEX + 1));
    m->triangles = malloc(sizeof *m->triangles * TRIANGLES);
    if (m->vertices != NULL && m->triangles != NULL)
        return true;
    mesh_free(m);
    return false;
}

/* The closed mesh around the eye: the dome, its vertices on the rays of
 * every CELL-th pixel, and the fan from its rim to the apex behind the
 * eye. False when out of memory. */
static bool make_dome(const camera *cam, mesh *m)
{
    if (!alloc_dome(m))
        return false;
    camera_view view = camera_view_of(cam);
    for (int y = 0; y <= ROWS; y++)
        for (int x = 0; x <= COLS; x++) {
            vec3 dir = camera_view_ray(&view, x * CELL, y * CELL).dir;
            m->vertices[vertex_index(x, y)] =
                vec3_scale(dir, dome_radius(x, y));
        }
    m->vertices[APEX] = (vec3){0, 0, -5};
    m->vertex_count = APEX + 1;
    for (int y = 0; y < ROWS; y++)
        for (int x = 0; x < COLS; x++)
            add_cell(m, x, y);
    int rim[RIM];
    rim_vertices(rim);
    for (int k = 0; k < RIM; k++)
        m->triangles[m->triangle_count++] =
            (mesh_triangle){{rim[(k + 1) % RIM], rim[k], APEX}};
    mesh_compute_bounds(m);
    return true;
}

/* The scene, with the dome as its one object; false if it cannot be made. */
static bool make_scene(scene *s)
{
    scene_init(s);
    scene_error err;
    if (!scene_parse(s, SCENE, strlen(SCENE), "SCENE", &err))
        return false;
    s->cam.width = WIDTH, s->cam.height = HEIGHT;
    mesh m;
    if (!make_dome(&s->cam, &m))
        return false;
    int index = scene_add_mesh(s, m);
    if (index < 0) {
        mesh_free(&m);
        return false;
    }
    object o = {.kind = SHAPE_MESH, .mesh = index, .color = COLOR};
    return scene_add_object(s, o);
}

/* What Moller-Trumbore sees along r: the nearest of all the mesh's
 * triangles, shaded as the program shades; *leak when it hits none. */
static vec3 moller_trumbore_pixel(const scene *s, ray r, bool *leak)
{
    const mesh *m = &s->meshes[0];
    double nearest = INFINITY;
    int k_nearest = -1;
    for (int k = 0; k < m->triangle_count; k++) {
        const int *v = m->triangles[k].v;
        triangle_hit th;
        if (triangle_hit_moller_trumbore(m->vertices[v[0]], m->vertices[v[1]],
                                         m->vertices[v[2]], r, 0, nearest,
                                         &th))
            nearest = th.t, k_nearest = k;
    }
    *leak = k_nearest < 0;
    if (*leak)
        return background_color(&s->bg, r.dir);
    const int *v = m->triangles[k_nearest].v;
    hit h = {.color = COLOR}; /* material 0, as the object's */
    triangle_fill_hit(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]],
                      r, nearest, &h);
    return shade(s, &h, vec3_scale(r.dir, -1), &(render_stats){0});
}

/* Is pixel (i, j) aimed at an edge or a vertex: on a grid line, or on
 * the diagonal that add_cell draws in its cell? */
static bool aimed(int i, int j)
{
    int a = i % CELL, b = j % CELL;
    if (a == 0 || b == 0)
        return true;
    return (i / CELL + j / CELL) % 2 == 0 ? a == b : a + b == CELL;
}

/* What each half counts: leaks[0] by Moller-Trumbore, leaks[1] by the
 * program, aimed pixels, and leaks where no pixel is aimed (a hole: a bug
 * of the mesh, not of the test). */
typedef struct {
    long leaks[2], aimed, stray;
} leak_count;

/* Renders both halves, counting the pixels through which each leaks. */
static void render_halves(const scene *s, image *mt, image *program,
                          leak_count *n)
{
    render(s, program, &(render_stats){0});
    camera_view view = camera_view_of(&s->cam);
    for (int j = 0; j < HEIGHT; j++)
        for (int i = 0; i < WIDTH; i++) {
            ray r = camera_view_ray(&view, i, j);
            bool leak[2];
            hit h;
            image_set(mt, i, j, moller_trumbore_pixel(s, r, &leak[0]));
            leak[1] = !scene_intersect(s, r, 0, INFINITY, &h,
                                       &(render_stats){0});
            n->leaks[0] += leak[0], n->leaks[1] += leak[1];
            n->aimed += aimed(i, j);
            n->stray += (leak[0] || leak[1]) && !aimed(i, j);
        }
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    image mt = {0}, program = {0};
    leak_count n = {{0, 0}, 0, 0};
    bool ok = make_scene(&s) && image_init(&mt, WIDTH, HEIGHT) &&
              image_init(&program, WIDTH, HEIGHT);
    if (ok) {
        render_halves(&s, &mt, &program, &n);
        ok = write_side_by_side(&mt, &program, SCALE, path);
        printf("%s: of %ld pixels aimed at shared edges and vertices, "
               "%ld leak to the background by Moller-Trumbore, %ld by the "
               "watertight test (%ld leaks elsewhere)\n",
               path, n.aimed, n.leaks[0], n.leaks[1], n.stray);
    } else
        fprintf(stderr, "%s: error: cannot make the scene\n", path);
    scene_free(&s);
    image_free(&mt);
    image_free(&program);
    bool shows = n.leaks[0] > 0 && n.leaks[1] == 0 && n.stray == 0;
    if (ok && !shows)
        fprintf(stderr, "%s: error: no longer leaks left only, and only "
                        "at edges\n", path);
    return ok && shows ? 0 : 1;
}
