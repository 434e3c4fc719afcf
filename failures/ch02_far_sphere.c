/* ch02_far_sphere.c: chapter 2's far sphere, drawn by the sheet's roots.
 *
 *   build/rel/failures/ch02_far_sphere figures/ch02-failure-far-sphere.png
 *
 * The scene is scenes/ch02-far.scene brought to 1,000 radii, the distance
 * of a football at the far end of a pitch (the lens widened to 0.2 degrees
 * so that it frames the sphere alike). The left half solves for the roots
 * with the sheet's geometric form in float, the right half with the robust
 * form in double, as the program does; both are shaded as chapter 2 shades,
 * |<n, d>| times the colour. Prints how many pixels the float form calls a
 * hit where the program sees a miss, or the other way round, and exits 1
 * when there are none: then the figure no longer shows the failure.
 *
 * Built by `make failures` (rule $(B)/failures/ch02_%) against the objects
 * of chapter 2's program but main.o; `make test` checks the committed PNG. */
#include "camera.h"
#include "sphere.h"
#include "failure_util.h"

#define SIZE 320         /* pixels per side of each half */
#define DISTANCE 1000.0  /* radii: the naive forms fail in float past 178 */

static const vec3 COLOR = {0.9, 0.6, 0.2}, BACKGROUND = {0.1, 0.1, 0.15};

/* The visible root of the form roots along r, or 0 for a miss. */
static double visible_root(const sphere *sp, sphere_roots_fn roots, ray r)
{
    double t[2];
    if (roots(sp->center, sp->radius, r, t) == 0)
        return 0;
    double visible = t[0] > 0 ? t[0] : t[1]; /* the rule of sphere_hit_t */
    return visible > 0 ? visible : 0;
}

/* Chapter 2's shading: the colour times |<n, d>|; the background on a miss. */
static vec3 shade_root(const sphere *sp, ray r, double t)
{
    if (t == 0)
        return BACKGROUND;
    hit h;
    sphere_fill_hit(sp, r, t, &h);
    return vec3_scale(COLOR, fabs(vec3_dot(h.normal, r.dir)));
}

/* Renders both halves; returns the pixels whose hit or miss they differ on. */
static long render_halves(const camera *cam, const sphere *sp, image *naive,
                          image *robust)
{
    camera_view view = camera_view_of(cam);
    long wrong = 0;
    for (int j = 0; j < cam->height; j++)
        for (int i = 0; i < cam->width; i++) {
            ray r = camera_view_ray(&view, i, j);
            double tn = visible_root(sp, sphere_roots_geometric_float, r);
            double tr = visible_root(sp, sphere_roots_robust, r);
            wrong += (tn == 0) != (tr == 0);
            image_set(naive, i, j, shade_root(sp, r, tn));
            image_set(robust, i, j, shade_root(sp, r, tr));
        }
    return wrong;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    /* ch02-far.scene: fov 0.0002 at 1e6 radii, the same framing here */
    camera cam = {0.0002 * 1e6 / DISTANCE, SIZE, SIZE};
    sphere sp = {{0.3, 0.2, DISTANCE}, 1};
    image naive, robust;
    if (!image_init(&naive, SIZE, SIZE) || !image_init(&robust, SIZE, SIZE))
        return 2;
    long wrong = render_halves(&cam, &sp, &naive, &robust);
    printf("%s: geometric float misclassifies %ld of %d pixels "
           "(hit for miss or miss for hit) at %.0f radii\n",
           path, wrong, SIZE * SIZE, DISTANCE);
    bool ok = write_side_by_side(&naive, &robust, 1, path);
    image_free(&naive);
    image_free(&robust);
    if (ok && wrong == 0)
        fprintf(stderr, "%s: error: the float form no longer fails\n", path);
    return ok && wrong > 0 ? 0 : 1;
}
