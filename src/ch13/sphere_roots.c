/* sphere_roots.c: the three ray-sphere forms in double (chapter 2). */
#include "sphere.h"

typedef double real;
/* sphere_roots_NAME: the double versions are the plain names. */
#define SPHERE_FORM(name) sphere_roots_##name

/* <<ray-sphere forms in any precision>> ch02 */
/* <<vectors in the working precision>> ch02 */
typedef struct {
    real x, y, z;
} rvec;

static inline rvec rvec_from(vec3 v)
{
    return (rvec){(real)v.x, (real)v.y, (real)v.z};
}
static inline rvec rvec_sub(rvec a, rvec b)
{
    return (rvec){a.x - b.x, a.y - b.y, a.z - b.z};
}
static inline rvec rvec_scale(rvec a, real s)
{
    return (rvec){a.x * s, a.y * s, a.z * s};
}
static inline real rvec_dot(rvec a, rvec b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
/* sqrt in double then rounded: correctly rounded in float as well. */
static inline real real_sqrt(real x) { return (real)sqrt((double)x); }

/* <<geometric form>> ch02 */
/* Sheet 1.4 for any origin: m = <c - o, d>, D^2 = |c - o|^2 - m^2,
 * t = m -+ sqrt(r^2 - D^2). Needs |d| = 1. */
int SPHERE_FORM(geometric)(vec3 center, double radius, ray r, double t[2])
{
    rvec oc = rvec_sub(rvec_from(center), rvec_from(r.origin));
    rvec d = rvec_from(r.dir);
    real rr = (real)radius * (real)radius;
    real m = rvec_dot(oc, d); /* along the ray to the point nearest c */
    real D2 = rvec_dot(oc, oc) - m * m; /* may round below 0: still a hit */
    if (D2 > rr)
        return 0;
    real half_chord = real_sqrt(rr - D2);
    t[0] = (double)(m - half_chord);
    t[1] = (double)(m + half_chord);
    return 2;
}

/* <<textbook quadratic form>> ch02 */
/* a t^2 + b t + c0 = 0: a = <d,d>, b = 2<f,d>, c0 = <f,f> - r^2, f = o - c */
int SPHERE_FORM(quadratic)(vec3 center, double radius, ray r, double t[2])
{
    rvec f = rvec_sub(rvec_from(r.origin), rvec_from(center));
    rvec d = rvec_from(r.dir);
    real a = rvec_dot(d, d);
    real b = 2 * rvec_dot(f, d);
    real c0 = rvec_dot(f, f) - (real)radius * (real)radius;
    real disc = b * b - 4 * a * c0;
    if (disc < 0)
        return 0;
    real s = real_sqrt(disc);
    t[0] = (double)((-b - s) / (2 * a));
    t[1] = (double)((-b + s) / (2 * a));
    return 2;
}

/* <<robust form>> ch02 */
/* Haines, Guenther, Akenine-Moeller (Ray Tracing Gems, ch. 7): the
 * discriminant from the centre-to-line vector, the roots without cancelling. */
int SPHERE_FORM(robust)(vec3 center, double radius, ray r, double t[2])
{
    rvec f = rvec_sub(rvec_from(r.origin), rvec_from(center));
    rvec d = rvec_from(r.dir);
    real rr = (real)radius * (real)radius;
    real a = rvec_dot(d, d);
    real beta = rvec_dot(f, d);
    rvec to_line = rvec_sub(
        f, rvec_scale(d, beta / a)); /* c to the line's nearest point */
    real delta = rr - rvec_dot(to_line, to_line); /* (beta^2 - a c0) / a */
    if (delta < 0)
        return 0;
    real c0 = rvec_dot(f, f) - rr;
    /* -beta - sign(beta) sqrt(a delta): one sign, nothing cancels */
    real q = -beta - (real)copysign(sqrt((double)(a * delta)), (double)beta);
    real near = q / a,
         far = q != 0 ? c0 / q : near; /* q = 0: both roots are 0 */
    t[0] = (double)(near < far ? near : far);
    t[1] = (double)(near < far ? far : near);
    return 2;
}
