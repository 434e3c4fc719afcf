/* ch05_normals.c: the sheet's normal transform M n beside the inverse
 * transpose (chapter 05).
 *
 *   build/rel/failures/ch05_normals figures/ch05-failure-normals.png
 *
 * A flattened, tilted ellipsoid and a sheared sphere, each the unit sphere
 * placed by a transform. The right half is what chapter 5's program renders
 * (render: normals moved by (M^-1)^T n). The left half is the same picture
 * with each placed sphere's normal moved like a vector, the sheet's M n:
 * the hits, the lights and the Phong sum are the program's own, only the
 * normal differs. Prints the largest angle between the two normals and the
 * share of the spheres' pixels whose colour changes by more than 0.05, and
 * exits 1 unless that share is at least a tenth: the figure shows the
 * failure.
 *
 * Built by `make failures` (rule $(B)/failures/ch05_%) against the objects
 * of chapter 5's program but main.o; `make test` checks the committed PNG. */
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "search.h"
#include "shade.h"
#include "failure_util.h"

static const char SCENE[] =
    "camera position 0 0.6 -0.2 look_at 0 0.05 5 up 0 1 0 fov 44\n"
    "image 240 200\n"
    "background gradient 0.85 0.85 0.9  0.3 0.45 0.8\n"
    "ambient 0.25 0.25 0.3\n"
    "material glaze ambient 0.15 diffuse 0.6 specular 0.7 shininess 60\n"
    "material floor diffuse 0.8 specular 0\n"
    "sphere center 0 -1000.6 5 radius 1000 color 0.75 0.75 0.7 material floor\n"
    "sphere center 0 0 0 color 0.85 0.3 0.25 material glaze "
    "transform scale 1.5 0.3 0.9 rotate z 15 translate -0.3 0.1 5.2\n"
    "sphere center 0 0 0 color 0.3 0.45 0.9 material glaze "
    "transform scale 0.45 0.45 0.45 shear xy 1.2 0 translate 0.9 -0.1 3.8\n"
    "light directional direction 0.6 -1 0.8 intensity 0.6 0.6 0.6\n"
    "light point position -3 4 1 intensity 0.8 0.8 0.75\n";

#define CHANGED 0.05 /* a colour channel that moves this much shows */

/* The placed sphere whose colour the hit has, or NULL. */
static const object *placed_sphere_of(const scene *s, const hit *h)
{
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind == SHAPE_SPHERE && o->transform != 0 &&
            o->color.x == h->color.x && o->color.y == h->color.y &&
            o->color.z == h->color.z)
            return o;
    }
    return NULL;
}

/* The sheet's normal at h: the object's normal moved by M like a vector. */
static vec3 sheet_normal(const scene *s, const object *o, const hit *h)
{
    const transform *t = scene_transform(s, o->transform);
    vec3 local = mat4_mul_point(t->inv, h->point);
    vec3 n = vec3_normalize(vec3_sub(local, o->sphere.center));
    return vec3_normalize(mat4_mul_dir(t->m, n));
}

int main(int argc, char **argv)
{
    const char *out = output_path(argc, argv);
    scene s;
    scene_error err;
    scene_init(&s);
    if (out == NULL ||
        !scene_parse(&s, SCENE, sizeof SCENE - 1, "(ch05_normals)", &err)) {
        if (out != NULL)
            fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line,
                    err.col, err.message);
        return 1;
    }
    image sheet = {0}, right = {0};
    render_stats stats = {0};
    bool ok = image_init(&sheet, s.cam.width, s.cam.height) &&
              image_init(&right, s.cam.width, s.cam.height);
    if (ok)
        render(&s, &right, &stats);
    camera_view view = camera_view_of(&s.cam);
    long placed = 0, changed = 0;
    double worst = 0;
    for (int j = 0; ok && j < sheet.height; j++)
        for (int i = 0; i < sheet.width; i++) {
            size_t k = (size_t)j * sheet.width + i;
            ray r = camera_view_ray(&view, i, j);
            hit h;
            sheet.pixels[k] = right.pixels[k];
            const object *o = NULL;
            if (scene_intersect(&s, r, 0, INFINITY, &h, &stats))
                o = placed_sphere_of(&s, &h);
            if (o == NULL)
                continue;
            vec3 n = sheet_normal(&s, o, &h);
            worst = fmax(worst, acos(fmin(1, vec3_dot(n, h.normal))));
            h.normal = h.geometric_normal = n;
            vec3 c = shade(&s, &h, vec3_scale(r.dir, -1), &stats);
            sheet.pixels[k] = c;
            vec3 d = vec3_sub(c, right.pixels[k]);
            placed++;
            changed += fmax(fabs(d.x), fmax(fabs(d.y), fabs(d.z))) > CHANGED;
        }
    double share = placed > 0 ? (double)changed / placed : 0;
    printf("ch05_normals: M n is up to %.1f degrees off; %.0f%% of the "
           "placed spheres' pixels change by more than %.2f\n",
           worst * 180 / M_PI, 100 * share, CHANGED);
    ok = ok && write_side_by_side(&sheet, &right, 1, out);
    image_free(&sheet);
    image_free(&right);
    scene_free(&s);
    return ok && share >= 0.1 ? 0 : 1;
}
