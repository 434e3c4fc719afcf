/* camera.h: the pinhole camera and its primary rays (chapter 1).
 *
 * The eye is at the origin looking down +z, x to the right, y up; the image
 * plane is z = 1. Pixel (i, j) is column i from the left, row j from the
 * top. A camera_view holds what every ray of one image shares; make it once
 * per image with camera_view_of. */
#ifndef CAMERA_H
#define CAMERA_H

#include "vec.h"

typedef struct {
    double fov_deg;    /* horizontal field of view in degrees, in (0, 180) */
    int width, height; /* image size in pixels, both >= 1 */
    /* <<camera members>> ch05 */
    bool is_placed; /* false: at the origin, looking down +z (chapter 5) */
    vec3 position;  /* the eye */
    vec3 look_at;   /* a point in the middle of the picture */
    vec3 up;        /* up in the picture; not along the view */
} camera;

/* What every primary ray of one image shares, computed once per image. */
typedef struct {
    double pixel_size; /* s */
    double left, top;  /* x of the image's left edge, y of its top edge */
    /* <<camera view members>> ch05 */
    bool is_placed;
    mat4 to_world; /* camera to world, when placed */
} camera_view;

/* Width (and height) of one pixel on the image plane: 2 tan(fov/2) / width. */
double camera_pixel_size(const camera *cam);

/* The point of the image plane at pixel coordinates (u, v): u runs from 0 at
 * the left edge to width at the right edge, v from 0 at the top to height. */
vec3 camera_image_point(const camera *cam, double u, double v);

camera_view camera_view_of(const camera *cam);

/* The primary ray through the point (u, v) of the image, in pixel units as
 * above, with a unit direction. */
ray camera_view_ray_at(const camera_view *view, double u, double v);

/* The primary ray through the centre of pixel (i, j): (i + 1/2, j + 1/2). */
ray camera_view_ray(const camera_view *view, int i, int j);

/* The same for a single ray: makes the view, then the ray. */
ray camera_ray(const camera *cam, int i, int j);
/* <<projection declarations>> ch08 */

/* How many pixels of the image the box [lo, hi] covers at most: the
 * rectangle around its corners' images, cut to the image; 0 when a corner
 * is at or behind the eye (no estimate then). */
double camera_box_pixels(const camera *cam, vec3 lo, vec3 hi);

#endif
