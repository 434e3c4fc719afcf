/* ch05_normals.c: the sheet's normal transform M n beside the inverse
 * transpose, as a picture (chapter 05).
 *
 *   build/rel/pictures/ch05_normals figures/ch05-normals.png
 *
 * Renders one scene twice, side by side: on the left every placed sphere
 * is shaded with the sheet's normal M n (its object-space normal moved like
 * a vector), on the right with the program's (M^-1)^T n. Everything else,
 * the hits, the lights, the shading, is the program's own: only the normal
 * differs. Writes the PNG given, or figures/ch05-normals.png. */
#include <stdio.h>
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "shade.h"

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

/* The placed sphere whose colour the hit has, or NULL. */
static const object *placed_sphere_of(const scene *s, const hit *h)
{
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind == SHAPE_SPHERE && o->transform != 0 && o->color.x == h->color.x &&
            o->color.y == h->color.y && o->color.z == h->color.z)
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

static void render_half(const scene *s, image *img, int x0, bool sheet)
{
    camera_view view = camera_view_of(&s->cam);
    render_stats stats = {0};
    for (int j = 0; j < s->cam.height; j++)
        for (int i = 0; i < s->cam.width; i++) {
            ray r = camera_view_ray(&view, i, j);
            hit h;
            vec3 c;
            if (!scene_intersect(s, r, 0, INFINITY, &h, &stats)) {
                c = background_color(&s->bg, r.dir);
            } else {
                const object *o = placed_sphere_of(s, &h);
                if (sheet && o != NULL)
                    h.normal = h.geometric_normal = sheet_normal(s, o, &h);
                c = shade(s, &h, vec3_scale(r.dir, -1), &stats);
            }
            image_set(img, x0 + i, j, c);
        }
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "figures/ch05-normals.png";
    scene s;
    scene_error err;
    scene_init(&s);
    if (!scene_parse(&s, SCENE, sizeof SCENE - 1, "(ch05_normals)", &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col, err.message);
        return 1;
    }
    enum { GAP = 4 }; /* white pixels between the two pictures */
    image img = {0};
    char why[256];
    bool ok = image_init(&img, 2 * s.cam.width + GAP, s.cam.height);
    if (ok) {
        for (int j = 0; j < img.height; j++)
            for (int i = 0; i < GAP; i++)
                image_set(&img, s.cam.width + i, j, (vec3){1, 1, 1});
        render_half(&s, &img, 0, true);
        render_half(&s, &img, s.cam.width + GAP, false);
        ok = image_write_png(&img, out, why, sizeof why);
        if (!ok)
            fprintf(stderr, "%s: error: %s\n", out, why);
    }
    image_free(&img);
    scene_free(&s);
    return ok ? 0 : 1;
}
