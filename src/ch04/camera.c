/* camera.c: primary rays (chapter 01). See camera.h. */
#include "camera.h"

double camera_pixel_size(const camera *cam)
{
    double half_width = tan(cam->fov_deg * (M_PI / 180.0) / 2.0);
    return 2.0 * half_width / cam->width;
}

vec3 camera_image_point(const camera *cam, double u, double v)
{
    double s = camera_pixel_size(cam);
    double left = -0.5 * cam->width * s; /* = -tan(fov/2) */
    double top = 0.5 * cam->height * s;
    return (vec3){left + u * s, top - v * s, 1.0};
}

ray camera_ray(const camera *cam, int i, int j)
{
    vec3 on_plane = camera_image_point(cam, i + 0.5, j + 0.5);
    ray r = {{0.0, 0.0, 0.0}, vec3_normalize(on_plane)};
    return r;
}
