/* triangle_methods_float.c: the same three methods in float (chapter 4). */
#include "triangle.h"

typedef float real;
typedef double wider;
/* triangle_hit_NAME_float: the float versions, for tests and benchmarks. */
#define TRIANGLE_METHOD(name) triangle_hit_##name##_float

/* <<ray-triangle methods in any precision>> ch04 */
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
/* <<triangle vectors in the working precision>> ch04 */
static inline rvec rvec_add(rvec a, rvec b)
{
    return (rvec){a.x + b.x, a.y + b.y, a.z + b.z};
}
static inline rvec rvec_cross(rvec a, rvec b)
{
    return (rvec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
}

/* Zero area: the three points lie on a line (or coincide). */
static inline bool is_degenerate(rvec a, rvec b, rvec c)
{
    rvec n = rvec_cross(rvec_sub(b, a), rvec_sub(c, a));
    return n.x == 0 && n.y == 0 && n.z == 0;
}

/* <<the sheet's method>> ch04 */
bool TRIANGLE_METHOD(sheet)(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                            double t_max, triangle_hit *out)
{
    rvec p[3] = {rvec_from(a), rvec_from(b), rvec_from(c)};
    rvec o = rvec_from(r.origin), d = rvec_from(r.dir);
    rvec n = rvec_cross(rvec_sub(p[1], p[0]), rvec_sub(p[2], p[0]));
    real nd = rvec_dot(n, d);
    if (nd == 0)
        return false; /* parallel to the plane, or no plane at all */
    real t = rvec_dot(n, rvec_sub(p[0], o)) / nd;
    if (!(t > t_min && t < t_max))
        return false;
    rvec x = rvec_add(o, rvec_scale(d, t)); /* the hit point on the plane */
    real twice_area = real_sqrt(rvec_dot(n, n));
    real w[3];
    for (int i = 0; i < 3; i++) {
        rvec ni = rvec_cross(rvec_sub(p[(i + 1) % 3], x),
                             rvec_sub(p[(i + 2) % 3], x));
        w[i] = real_sqrt(rvec_dot(ni, ni)) * (rvec_dot(ni, n) < 0 ? -1 : 1);
        if (w[i] < 0)
            return false; /* beyond the edge opposite p_i */
    }
    *out = (triangle_hit){
        t, {w[0] / twice_area, w[1] / twice_area, w[2] / twice_area}};
    return true;
}

/* <<Moller-Trumbore>> ch04 */
bool TRIANGLE_METHOD(moller_trumbore)(vec3 a, vec3 b, vec3 c, ray r,
                                      double t_min, double t_max,
                                      triangle_hit *out)
{
    rvec p0 = rvec_from(a), d = rvec_from(r.dir);
    rvec e1 = rvec_sub(rvec_from(b), p0), e2 = rvec_sub(rvec_from(c), p0);
    rvec pv = rvec_cross(d, e2);
    real det = rvec_dot(e1, pv);
    if (det == 0)
        return false; /* parallel, or degenerate */
    real inv = 1 / det;
    rvec tv = rvec_sub(rvec_from(r.origin), p0);
    real u = rvec_dot(tv, pv) * inv;
    if (u < 0 || u > 1)
        return false;
    rvec qv = rvec_cross(tv, e1);
    real v = rvec_dot(d, qv) * inv;
    if (v < 0 || u + v > 1)
        return false;
    real t = rvec_dot(e2, qv) * inv;
    if (!(t > t_min && t < t_max))
        return false;
    *out = (triangle_hit){t, {1 - u - v, u, v}};
    return true;
}

/* <<watertight>> ch04 */
/* <<shear the ray onto the z axis>> ch04 */
/* The ray's origin, its axes permuted so that it runs along z, and the
 * shear that turns it into the z axis: all the edge functions need of it. */
typedef struct {
    int kx, ky, kz;
    real sx, sy, sz;
    rvec origin;
} sheared_ray;

static inline sheared_ray shear_ray(ray r)
{
    sheared_ray s = {.origin = rvec_from(r.origin)};
    real d[3] = {(real)r.dir.x, (real)r.dir.y, (real)r.dir.z};
    s.kz = fabs((double)d[0]) > fabs((double)d[1]) ? 0 : 1;
    s.kz = fabs((double)d[2]) > fabs((double)d[s.kz]) ? 2 : s.kz;
    s.kx = (s.kz + 1) % 3, s.ky = (s.kz + 2) % 3;
    if (d[s.kz] < 0) {
        int swap = s.kx;
        s.kx = s.ky, s.ky = swap;
    }
    s.sx = d[s.kx] / d[s.kz], s.sy = d[s.ky] / d[s.kz], s.sz = 1 / d[s.kz];
    return s;
}

static inline bool hit_sheared(const sheared_ray *s, vec3 a, vec3 b, vec3 c,
                               double t_min, double t_max, triangle_hit *out)
{
    /* <<shear the triangle>> ch04 */
    rvec pa = rvec_sub(rvec_from(a), s->origin);
    rvec pb = rvec_sub(rvec_from(b), s->origin);
    rvec pc = rvec_sub(rvec_from(c), s->origin);
    real A[3] = {pa.x, pa.y, pa.z}, B[3] = {pb.x, pb.y, pb.z},
         C[3] = {pc.x, pc.y, pc.z};
    real ax = A[s->kx] - s->sx * A[s->kz], ay = A[s->ky] - s->sy * A[s->kz];
    real bx = B[s->kx] - s->sx * B[s->kz], by = B[s->ky] - s->sy * B[s->kz];
    real cx = C[s->kx] - s->sx * C[s->kz], cy = C[s->ky] - s->sy * C[s->kz];
    /* <<the three edge functions>> ch04 */
    real u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    /* exactly on an edge: decide more precisely */
    if (u == 0 || v == 0 || w == 0) {
        u = (real)((wider)cx * by - (wider)cy * bx);
        v = (real)((wider)ax * cy - (wider)ay * cx);
        w = (real)((wider)bx * ay - (wider)by * ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0))
        return false; /* signs differ: the ray passes outside an edge */
    real det = u + v + w;
    if (det == 0)
        return false; /* parallel, or degenerate */
    real t =
        (u * s->sz * A[s->kz] + v * s->sz * B[s->kz] + w * s->sz * C[s->kz]) /
        det;
    if (!(t > t_min && t < t_max) || is_degenerate(pa, pb, pc))
        return false;
    *out = (triangle_hit){t, {u / det, v / det, w / det}};
    return true;
}

bool TRIANGLE_METHOD(watertight)(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                                 double t_max, triangle_hit *out)
{
    sheared_ray s = shear_ray(r);
    return hit_sheared(&s, a, b, c, t_min, t_max, out);
}
