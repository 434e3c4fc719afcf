/* camera.c: primary rays (chapter 1). See camera.h. */
#include "camera.h"

double camera_pixel_size(const camera *cam)
{
    double half_width = tan(cam->fov_deg * (M_PI / 180.0) / 2.0);
    return 2.0 * half_width / cam->width;
}

camera_view camera_view_of(const camera *cam)
{
    double s = camera_pixel_size(cam);
    camera_view view = {.pixel_size = s,
                        .left = -0.5 * cam->width * s, /* = -tan(fov/2) */
                        .top = 0.5 * cam->height * s};
    /* <<prepare the camera view>> ch05 */
    view.is_placed = cam->is_placed && mat4_look_at(cam->position, cam->look_at,
                                                    cam->up, &view.to_world);
    return view;
}

vec3 camera_image_point(const camera *cam, double u, double v)
{
    camera_view view = camera_view_of(cam);
    double s = view.pixel_size;
    return (vec3){view.left + u * s, view.top - v * s, 1.0};
}

ray camera_view_ray_at(const camera_view *view, double u, double v)
{
    double s = view->pixel_size;
    vec3 on_plane = {view->left + u * s, view->top - v * s, 1.0};
    ray r = {{0.0, 0.0, 0.0}, vec3_normalize(on_plane)};
    /* <<place the primary ray>> ch05 */
    if (view->is_placed) /* a rotation: renormalised against rounding only */
        r = (ray){mat4_mul_point(view->to_world, r.origin),
                  vec3_normalize(mat4_mul_dir(view->to_world, r.dir))};
    return r;
}

ray camera_view_ray(const camera_view *view, int i, int j)
{
    return camera_view_ray_at(view, i + 0.5, j + 0.5);
}

ray camera_ray(const camera *cam, int i, int j)
{
    camera_view view = camera_view_of(cam);
    return camera_view_ray(&view, i, j);
}
/* <<projection>> ch08 */

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

double camera_box_pixels(const camera *cam, vec3 lo, vec3 hi)
{
    camera_view view = camera_view_of(cam);
    double u0 = INFINITY, u1 = -INFINITY, w0 = INFINITY, w1 = -INFINITY;
    for (int k = 0; k < 8; k++) {
        vec3 p = point_to_camera(&view, (vec3){k & 1 ? hi.x : lo.x,
                                                k & 2 ? hi.y : lo.y,
                                                k & 4 ? hi.z : lo.z});
        double u, w;
        if (!(p.z > 0))
            return 0;
        pixel_of(&view, p, &u, &w);
        u0 = fmin(u0, u), u1 = fmax(u1, u), w0 = fmin(w0, w), w1 = fmax(w1, w);
    }
    u0 = fmax(u0, 0), u1 = fmin(u1, cam->width);
    w0 = fmax(w0, 0), w1 = fmin(w1, cam->height);
    return u1 > u0 && w1 > w0 ? (u1 - u0) * (w1 - w0) : 0;
}
