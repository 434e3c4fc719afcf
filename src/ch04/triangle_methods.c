/* triangle_methods.c: the three ray-triangle methods in double (chapter 04). */
#include "triangle.h"

typedef double real;
typedef long double wider; /* the watertight test's fallback precision */
/* triangle_hit_NAME: the double versions are the plain names. */
#define TRIANGLE_METHOD(name) triangle_hit_##name

typedef struct {
    real x, y, z;
} rvec;

static inline rvec rvec_from(vec3 v) { return (rvec){(real)v.x, (real)v.y, (real)v.z}; }
static inline rvec rvec_sub(rvec a, rvec b) { return (rvec){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline rvec rvec_scale(rvec a, real s) { return (rvec){a.x * s, a.y * s, a.z * s}; }
static inline real rvec_dot(rvec a, rvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/* sqrt in double then rounded: correctly rounded in float as well. */
static inline real real_sqrt(real x) { return (real)sqrt((double)x); }
static inline rvec rvec_add(rvec a, rvec b) { return (rvec){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline rvec rvec_cross(rvec a, rvec b)
{
    return (rvec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* Zero area: the three points lie on a line (or coincide). */
static inline bool is_degenerate(rvec a, rvec b, rvec c)
{
    rvec n = rvec_cross(rvec_sub(b, a), rvec_sub(c, a));
    return n.x == 0 && n.y == 0 && n.z == 0;
}

bool TRIANGLE_METHOD(sheet)(vec3 a, vec3 b, vec3 c, ray r, double t_min, double t_max,
                           triangle_hit *out)
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
        rvec ni = rvec_cross(rvec_sub(p[(i + 1) % 3], x), rvec_sub(p[(i + 2) % 3], x));
        w[i] = real_sqrt(rvec_dot(ni, ni)) * (rvec_dot(ni, n) < 0 ? -1 : 1);
        if (w[i] < 0)
            return false; /* beyond the edge opposite p_i */
    }
    *out = (triangle_hit){t, {w[0] / twice_area, w[1] / twice_area, w[2] / twice_area}};
    return true;
}

bool TRIANGLE_METHOD(moller_trumbore)(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                                     double t_max, triangle_hit *out)
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

bool TRIANGLE_METHOD(watertight)(vec3 a, vec3 b, vec3 c, ray r, double t_min, double t_max,
                                triangle_hit *out)
{
    real d[3] = {(real)r.dir.x, (real)r.dir.y, (real)r.dir.z};
    int kz = fabs((double)d[0]) > fabs((double)d[1]) ? 0 : 1;
    kz = fabs((double)d[2]) > fabs((double)d[kz]) ? 2 : kz;
    int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    if (d[kz] < 0) {
        int swap = kx;
        kx = ky, ky = swap;
    }
    real sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1 / d[kz];
    rvec o = rvec_from(r.origin);
    rvec pa = rvec_sub(rvec_from(a), o);
    rvec pb = rvec_sub(rvec_from(b), o);
    rvec pc = rvec_sub(rvec_from(c), o);
    real A[3] = {pa.x, pa.y, pa.z}, B[3] = {pb.x, pb.y, pb.z}, C[3] = {pc.x, pc.y, pc.z};
    real ax = A[kx] - sx * A[kz], ay = A[ky] - sy * A[kz];
    real bx = B[kx] - sx * B[kz], by = B[ky] - sy * B[kz];
    real cx = C[kx] - sx * C[kz], cy = C[ky] - sy * C[kz];
    real u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    if (u == 0 || v == 0 || w == 0) { /* exactly on an edge: decide more precisely */
        u = (real)((wider)cx * by - (wider)cy * bx);
        v = (real)((wider)ax * cy - (wider)ay * cx);
        w = (real)((wider)bx * ay - (wider)by * ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0))
        return false; /* signs differ: the ray passes outside an edge */
    real det = u + v + w;
    if (det == 0)
        return false; /* parallel, or degenerate */
    real t = (u * sz * A[kz] + v * sz * B[kz] + w * sz * C[kz]) / det;
    if (!(t > t_min && t < t_max) || is_degenerate(pa, pb, pc))
        return false;
    *out = (triangle_hit){t, {u / det, v / det, w / det}};
    return true;
}
