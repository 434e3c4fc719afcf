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
