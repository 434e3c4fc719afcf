/* ch03_half_vector.c: Blinn-Phong with the sheet's half vector (l + v) / 2.
 *
 *   build/rel/failures/ch03_half_vector figures/ch03-failure-half-vector.png
 *
 * One glossy sphere (highlight blinn, shininess k = 30 as in chapter 3's
 * highlights scene) under three white point lights, which make angles of
 * about 8, 20 and 90 degrees with the viewer as seen from their highlights.
 * The right half is what chapter 3's program renders (render, with the
 * normalised h = (l + v) / |l + v|). The left half is the same picture with
 * each light's highlight term swapped for the sheet's, h = (l + v) / 2,
 * whose length cos(theta / 2) is raised to the power 4k too: the highlight
 * near l = v survives, a little dimmer, the one at 20 degrees fades to a
 * ghost and the one at 90 degrees vanishes. Prints each light's brightest
 * highlight term in both halves, and exits 1 unless some light's highlight
 * shows (above 0.02) on the right only: the figure shows the failure.
 *
 * Built by `make failures` (rule $(B)/failures/ch03_%) against the objects
 * of chapter 3's program but main.o; `make test` checks the committed PNG. */
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "search.h"
#include "shade.h"
#include "failure_util.h"

static const char SCENE[] =
    "camera fov 30\n"
    "image 320 320\n"
    "background 0.05 0.05 0.08\n"
    "ambient 0.1 0.1 0.1\n"
    "material glossy diffuse 0.5 specular 0.8 shininess 30 highlight blinn\n"
    "sphere center 0 0 6 radius 1 color 0.2 0.35 0.8 material glossy\n"
    "light point position -0.5 -0.5 0 intensity 0.7 0.7 0.7\n"
    "light point position 1.3 1.3 -0.2 intensity 0.7 0.7 0.7\n"
    "light point position -5 1 4.7 intensity 0.7 0.7 0.7\n";

#define VISIBLE 0.02 /* a highlight term this bright shows on the sphere */

/* The sheet's <n, h>^(4k) with h = (l + v) / 2, not a unit vector. */
static double sheet_blinn(vec3 n, vec3 l, vec3 v, double k)
{
    double nh = vec3_dot(n, vec3_scale(vec3_add(l, v), 0.5));
    return pow(nh > 0 ? nh : 0, 4.0 * k);
}

/* Per light: the brightest highlight term rho_s <n, h>^(4k) of each half
 * (0: the sheet's h, 1: the normalised h), and the angle between l and v
 * in degrees where the program's is brightest. */
typedef struct {
    double peak[2], angle;
} light_peak;

#define MAX_LIGHTS 3

/* Swaps each light's highlight at the hit h, seen from v, into c: the
 * normalised h's out, the sheet's in, as shade adds them (normal towards
 * the viewer, a light behind the surface adds none). */
static vec3 swap_at_hit(const scene *s, const hit *h, vec3 v, vec3 c,
                        light_peak peaks[MAX_LIGHTS])
{
    const material *m = scene_material(s, h->material);
    vec3 n = vec3_dot(h->normal, v) < 0 ? vec3_scale(h->normal, -1)
                                        : h->normal;
    for (int j = 0; j < s->light_count; j++) {
        light_sample ls = light_toward(&s->lights[j], h->point);
        if (vec3_dot(n, ls.l) <= 0)
            continue;
        double k = m->shininess;
        double unit = m->specular * specular_blinn(n, ls.l, v, k);
        double sheet = m->specular * sheet_blinn(n, ls.l, v, k);
        c = vec3_add(c, vec3_scale(ls.intensity, sheet - unit));
        light_peak *p = &peaks[j];
        p->peak[0] = fmax(p->peak[0], sheet);
        if (unit > p->peak[1]) {
            p->peak[1] = unit;
            p->angle = acos(vec3_dot(ls.l, v)) * (180 / M_PI);
        }
    }
    return c;
}

/* Turns the program's picture into the sheet's, pixel by pixel. */
static void swap_highlights(const scene *s, const image *program,
                            image *sheet, light_peak peaks[MAX_LIGHTS])
{
    camera_view view = camera_view_of(&s->cam);
    for (int j = 0; j < s->cam.height; j++)
        for (int i = 0; i < s->cam.width; i++) {
            ray r = camera_view_ray(&view, i, j);
            vec3 c = program->pixels[(size_t)j * program->width + i];
            hit h;
            if (scene_intersect(s, r, 0, INFINITY, &h, &(render_stats){0}))
                c = swap_at_hit(s, &h, vec3_scale(r.dir, -1), c, peaks);
            image_set(sheet, i, j, c);
        }
}

/* Renders both halves of the figure; false, saying why, if it cannot. */
static bool render_halves(const char *path, image *sheet, image *program,
                          light_peak peaks[MAX_LIGHTS])
{
    scene s;
    scene_init(&s);
    scene_error err;
    bool ok = scene_parse(&s, SCENE, strlen(SCENE), "SCENE", &err) &&
              s.light_count <= MAX_LIGHTS &&
              image_init(sheet, s.cam.width, s.cam.height) &&
              image_init(program, s.cam.width, s.cam.height);
    if (ok) {
        render(&s, program, &(render_stats){0});
        swap_highlights(&s, program, sheet, peaks);
    } else
        fprintf(stderr, "%s: error: cannot make the scene\n", path);
    scene_free(&s);
    return ok;
}

/* Prints each light's peaks; true if some light's highlight shows with the
 * normalised h and not with the sheet's, as the figure means to show. */
static bool report(const char *path, const light_peak peaks[MAX_LIGHTS])
{
    bool vanished = false;
    for (int j = 0; j < MAX_LIGHTS; j++) {
        const light_peak *p = &peaks[j];
        printf("%s: light %d, l and v %.0f degrees apart: highlight peak "
               "%.3g with h = (l + v) / 2, %.3g with h normalised\n",
               path, j + 1, p->angle, p->peak[0], p->peak[1]);
        vanished |= p->peak[0] < VISIBLE && p->peak[1] > VISIBLE;
    }
    if (!vanished)
        fprintf(stderr, "%s: error: the sheet's h no longer fails\n", path);
    return vanished;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    image sheet = {0}, program = {0};
    light_peak peaks[MAX_LIGHTS] = {{{0, 0}, 0}};
    bool ok = render_halves(path, &sheet, &program, peaks) &&
              write_side_by_side(&sheet, &program, 1, path) &&
              report(path, peaks);
    image_free(&sheet);
    image_free(&program);
    return ok ? 0 : 1;
}
