/* triangle_packet.c: triangles PACKET_W at a time, in float (chapter 10).
 */
#include <float.h>
#include <math.h>
#include <string.h>
#include "triangle_packet.h"

/* <<filling packets>> ch10 */
int triangle_packets_needed(int count)
{
    return (count + PACKET_W - 1) / PACKET_W;
}

/* Lane k of q: triangle item's corners in float, and their reach. */
static void fill_lane(triangle_packet *q, int k, const vec3 *vertices,
                      const mesh_triangle *t, int item)
{
    float reach = 0;
    for (int i = 0; i < 3; i++)
        for (int axis = 0; axis < 3; axis++) {
            float f = (float)vec3_axis(vertices[t->v[i]], axis);
            q->corner[i][axis][k] = f;
            reach = fabsf(f) > reach ? fabsf(f) : reach;
        }
    q->reach[k] = reach;
    q->triangle[k] = item;
}

int triangle_packets_fill(triangle_packet *packets, const vec3 *vertices,
                          const mesh_triangle *triangles, const int *items,
                          int count)
{
    int n = triangle_packets_needed(count);
    for (int p = 0; p < n; p++) {
        memset(&packets[p], 0, sizeof packets[p]);
        for (int k = 0; k < PACKET_W; k++) {
            int j = p * PACKET_W + k;
            packets[p].triangle[k] = -1; /* empty, unless filled */
            if (j < count) { /* items has count entries, no more */
                int item = items ? items[j] : j;
                fill_lane(&packets[p], k, vertices, &triangles[item], item);
            }
        }
    }
    return n;
}

/* <<a ray for packets, made>> ch10 */
packet_ray packet_ray_of(const watertight_ray *w)
{
    packet_ray r = {w->kx, w->ky, w->kz, (float)w->sx, (float)w->sy,
                    (float)w->sz, {0}, 0, w};
    const float o[3] = {(float)w->origin.x, (float)w->origin.y,
                        (float)w->origin.z}; /* indexed: no branch */
    for (int a = 0; a < 3; a++) {
        float m = fabsf(o[a]);
        r.origin_reach = m > r.origin_reach ? m : r.origin_reach;
    }
    r.origin[0] = o[w->kx], r.origin[1] = o[w->ky], r.origin[2] = o[w->kz];
    return r;
}

/* <<the float test's helpers>> ch10 */
/* pbrt's gamma(n): n float roundings stay within a factor 1 +- gamma(n). */
static inline float gamma_of(int n)
{
    const float u = FLT_EPSILON / 2;
    return n * u / (1 - n * u);
}

/* Covers the rounding of the bounds and double's own error. */
#define BOUND_MARGIN (1 + 0x1p-10f)
/* Covers the rounding of the comparison of t, and double's division. */
#define T_MARGIN (1 + 0x1p-20f)

/* x in every lane of a vector. */
static inline packet_float packet_splat(float x)
{
    packet_float v = {0};
    for (int k = 0; k < PACKET_W; k++)
        v[k] = x;
    return v;
}

/* |x| alike for a float and for a vector's lanes, so that the filter's
 * one text serves both: the sign bit cleared, NaN's included. */
static inline packet_float packet_abs(packet_float x)
{
    return (packet_float)((packet_int)x & 0x7fffffff);
}
#define lanes_abs(x) _Generic((x), float: fabsf, default: packet_abs)(x)

/* Is every lane of the mask m set? Alike for one lane and for vectors. */
static inline int lane_set(int m)
{
    return m != 0;
}

/* Lane k of a mask (-1 or 0 in each) in bit k: SSE's one instruction
 * where the lanes are its four. */
static inline unsigned packet_bits(packet_int m)
{
#if defined(__SSE__) && PACKET_W == 4 && !defined(RT_SCALAR)
    return (unsigned)__builtin_ia32_movmskps((packet_float)m);
#else
    unsigned bits = 0;
    for (int k = 0; k < PACKET_W; k++)
        bits |= (unsigned)(m[k] & 1) << k;
    return bits;
#endif
}

static inline int packet_all_set(packet_int m)
{
    return packet_bits(m) == (1u << PACKET_W) - 1;
}
#define lanes_all(m) _Generic((m), int: lane_set, default: packet_all_set)(m)

/* <<the edge functions' error bound>> ch10 */
/* e_E in each lane: how far U, V or W computed in float can be from the
 * exact value of the same formula on the double corners and origin.
 * reach: the lane's largest |corner coordinate| plus the origin's (T);
 * xm, ym: the sums of its sheared corners' |x| and |y| (X and Y). */
static inline packet_float edge_error_bound(packet_float reach,
                                            packet_float xm, packet_float ym)
{
    packet_float e_s = gamma_of(11) * reach; /* a sheared x or y */
    return (2 * e_s * (xm + ym) + 2 * e_s * e_s + 2 * gamma_of(2) * xm * ym) *
               BOUND_MARGIN + FLT_MIN;
}

/* <<the float filter, lane by lane and in vectors>> ch10 */
/* edge_error_bound of one lane: its numbers in every lane of a vector,
 * and the first lane read back. */
static inline float edge_error_bound_alone(float reach, float xm, float ym)
{
    return edge_error_bound(packet_splat(reach), packet_splat(xm),
                            packet_splat(ym))[0];
}
#define lanes_edge_bound(reach, xm, ym)                                        \
    _Generic((reach), float: edge_error_bound_alone,                           \
             default: edge_error_bound)(reach, xm, ym)

/* The lanes of p that chapter 4's test could hit: -1 in each. */
static inline packet_int kept_in_vectors(const triangle_packet *p,
                                         const packet_ray *r, float t_max,
                                         int t_filter)
{
    typedef packet_float lanes;
    typedef packet_int lane_mask;
    const lanes *a = p->corner[0], *b = p->corner[1], *c = p->corner[2];
    lanes p_reach = p->reach;
    lane_mask empty = p->triangle < 0; /* -1 where no triangle is */
    /* <<the float filter>> ch10 */
    /* <<the float filter's edge functions>> ch10 */
    /* <<the edge functions in float>> ch10 */
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float ox = r->origin[0], oy = r->origin[1], oz = r->origin[2];
    lanes az = a[kz] - oz, bz = b[kz] - oz, cz = c[kz] - oz;
    lanes ax = (a[kx] - ox) - r->sx * az, ay = (a[ky] - oy) - r->sy * az;
    lanes bx = (b[kx] - ox) - r->sx * bz, by = (b[ky] - oy) - r->sy * bz;
    lanes cx = (c[kx] - ox) - r->sx * cz, cy = (c[ky] - oy) - r->sy * cz;
    lanes u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    lanes reach = p_reach + r->origin_reach; /* >= |corner| + |origin| */
    lanes xm = lanes_abs(ax) + lanes_abs(bx) + lanes_abs(cx); /* >= max |x| */
    lanes ym = lanes_abs(ay) + lanes_abs(by) + lanes_abs(cy);
    lanes e_e = lanes_edge_bound(reach, xm, ym); /* U, V or W */
    lane_mask outside = (((u < -e_e) | (v < -e_e) | (w < -e_e)) &
                         ((u > e_e) | (v > e_e) | (w > e_e))) |
                        empty;
    if (lanes_all(outside)) /* an edge between, or nothing, in every lane */
        return (lane_mask){0};
    lanes det = u + v + w;
    lanes za = r->sz * az, zb = r->sz * bz, zc = r->sz * cz;
    lanes n = u * za + v * zb + w * zc; /* t times det */
    /* <<the float test's error bounds>> ch10 */
    lanes zm = lanes_abs(za) + lanes_abs(zb) + lanes_abs(zc);
    lanes sum = lanes_abs(u) + lanes_abs(v) + lanes_abs(w);
    lanes e_d = (3 * e_e + gamma_of(2) * sum) * BOUND_MARGIN + FLT_MIN;
    lanes e_z = gamma_of(6) * fabsf(r->sz) * reach; /* a scaled z */
    lanes e_n = (e_z * sum + 3 * e_e * (zm + e_z) + gamma_of(3) * sum * zm) *
                    BOUND_MARGIN + FLT_MIN; /* t times det */
    lane_mask sure = (lanes_abs(det) > e_d) & t_filter; /* det's sign */
    lane_mask far = ((det > 0) & (n - e_n >= t_max * (det + e_d) * T_MARGIN)) |
                    ((det < 0) & (-n - e_n >= t_max * (e_d - det) * T_MARGIN));
    lane_mask behind = ((det > 0) & (n + e_n < 0)) | ((det < 0) & (n - e_n > 0));
    lane_mask kept = (outside | (sure & (far | behind))) == 0;
    return kept;
}

/* Lane k of kept_in_vectors, computed alone: 1 or 0. */
static inline int kept_alone(const triangle_packet *p, int k,
                             const packet_ray *r, float t_max, int t_filter)
{
    typedef float lanes;
    typedef int lane_mask;
    float a[3], b[3], c[3], p_reach = p->reach[k];
    for (int axis = 0; axis < 3; axis++)
        a[axis] = p->corner[0][axis][k], b[axis] = p->corner[1][axis][k],
        c[axis] = p->corner[2][axis][k];
    int empty = p->triangle[k] < 0;
    /* <<the float filter>> ch10 */
    /* <<the float filter's edge functions>> ch10 */
    /* <<the edge functions in float>> ch10 */
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float ox = r->origin[0], oy = r->origin[1], oz = r->origin[2];
    lanes az = a[kz] - oz, bz = b[kz] - oz, cz = c[kz] - oz;
    lanes ax = (a[kx] - ox) - r->sx * az, ay = (a[ky] - oy) - r->sy * az;
    lanes bx = (b[kx] - ox) - r->sx * bz, by = (b[ky] - oy) - r->sy * bz;
    lanes cx = (c[kx] - ox) - r->sx * cz, cy = (c[ky] - oy) - r->sy * cz;
    lanes u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    lanes reach = p_reach + r->origin_reach; /* >= |corner| + |origin| */
    lanes xm = lanes_abs(ax) + lanes_abs(bx) + lanes_abs(cx); /* >= max |x| */
    lanes ym = lanes_abs(ay) + lanes_abs(by) + lanes_abs(cy);
    lanes e_e = lanes_edge_bound(reach, xm, ym); /* U, V or W */
    lane_mask outside = (((u < -e_e) | (v < -e_e) | (w < -e_e)) &
                         ((u > e_e) | (v > e_e) | (w > e_e))) |
                        empty;
    if (lanes_all(outside)) /* an edge between, or nothing, in every lane */
        return (lane_mask){0};
    lanes det = u + v + w;
    lanes za = r->sz * az, zb = r->sz * bz, zc = r->sz * cz;
    lanes n = u * za + v * zb + w * zc; /* t times det */
    /* <<the float test's error bounds>> ch10 */
    lanes zm = lanes_abs(za) + lanes_abs(zb) + lanes_abs(zc);
    lanes sum = lanes_abs(u) + lanes_abs(v) + lanes_abs(w);
    lanes e_d = (3 * e_e + gamma_of(2) * sum) * BOUND_MARGIN + FLT_MIN;
    lanes e_z = gamma_of(6) * fabsf(r->sz) * reach; /* a scaled z */
    lanes e_n = (e_z * sum + 3 * e_e * (zm + e_z) + gamma_of(3) * sum * zm) *
                    BOUND_MARGIN + FLT_MIN; /* t times det */
    lane_mask sure = (lanes_abs(det) > e_d) & t_filter; /* det's sign */
    lane_mask far = ((det > 0) & (n - e_n >= t_max * (det + e_d) * T_MARGIN)) |
                    ((det < 0) & (-n - e_n >= t_max * (e_d - det) * T_MARGIN));
    lane_mask behind = ((det > 0) & (n + e_n < 0)) | ((det < 0) & (n - e_n > 0));
    lane_mask kept = (outside | (sure & (far | behind))) == 0;
    return kept;
}

bool triangle_packet_stops_at_edges(const triangle_packet *p,
                                    const packet_ray *r)
{
    typedef packet_float lanes;
    typedef packet_int lane_mask;
    const lanes *a = p->corner[0], *b = p->corner[1], *c = p->corner[2];
    lanes p_reach = p->reach;
    lane_mask empty = p->triangle < 0;
    /* <<the float filter's edge functions>> ch10 */
    /* <<the edge functions in float>> ch10 */
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float ox = r->origin[0], oy = r->origin[1], oz = r->origin[2];
    lanes az = a[kz] - oz, bz = b[kz] - oz, cz = c[kz] - oz;
    lanes ax = (a[kx] - ox) - r->sx * az, ay = (a[ky] - oy) - r->sy * az;
    lanes bx = (b[kx] - ox) - r->sx * bz, by = (b[ky] - oy) - r->sy * bz;
    lanes cx = (c[kx] - ox) - r->sx * cz, cy = (c[ky] - oy) - r->sy * cz;
    lanes u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    lanes reach = p_reach + r->origin_reach; /* >= |corner| + |origin| */
    lanes xm = lanes_abs(ax) + lanes_abs(bx) + lanes_abs(cx); /* >= max |x| */
    lanes ym = lanes_abs(ay) + lanes_abs(by) + lanes_abs(cy);
    lanes e_e = lanes_edge_bound(reach, xm, ym); /* U, V or W */
    lane_mask outside = (((u < -e_e) | (v < -e_e) | (w < -e_e)) &
                         ((u > e_e) | (v > e_e) | (w > e_e))) |
                        empty;
    return lanes_all(outside);
}

/* <<the tests of packets, made>> ch10 */
/* What the filter reads of (t_min, t_max): t_max rounded up to float, and
 * whether t may be tested (t_min >= 0). */
typedef struct {
    float t_max;
    int t_filter;
} float_interval;

/* nextafter(x, INFINITY) as a step of the bits, without a call: read as
 * an integer, a double's bits count its magnitude, so that one more is
 * the next double away from zero, one less the next towards it. */
static inline double double_after(double x)
{
    if (!(x < INFINITY) || x == 0) /* inf, NaN; either zero */
        return x == 0 ? 0x1p-1074 : x;
    int64_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits += x > 0 ? 1 : -1;
    memcpy(&x, &bits, sizeof x);
    return x;
}

static float_interval float_interval_of(double t_min, double t_max)
{
    return (float_interval){float_up_by_bits(t_max), t_min >= 0 ? -1 : 0};
}

/* The program's filter and decision: in vectors, unless built with
 * -DRT_SCALAR. */
#ifdef RT_SCALAR
#define LANE_BY_LANE true
#else
#define LANE_BY_LANE false
#endif

/* The lanes of p that the filter keeps, lane k in bit k. */
static unsigned candidates(const triangle_packet *p, const packet_ray *r,
                           float_interval in, bool alone)
{
    unsigned bits = 0;
    if (alone) {
        for (int k = 0; k < PACKET_W; k++)
            bits |= (unsigned)kept_alone(p, k, r, in.t_max, in.t_filter) << k;
        return bits;
    }
    return packet_bits(kept_in_vectors(p, r, in.t_max, in.t_filter));
}

unsigned triangle_packet_candidates(const triangle_packet *p,
                                    const packet_ray *r, double t_min,
                                    double t_max, bool alone)
{
    return candidates(p, r, float_interval_of(t_min, t_max), alone);
}

/* Chapter 4's test, tightened, of lane k of packet q: its triangle's
 * corners read from the mesh (vertices, triangles), or from the lane
 * itself when vertices is NULL (every corner a float, held exactly). */
static bool hit_in_lane(const packet_ray *r, const triangle_packet *q,
                        int k, const vec3 *vertices,
                        const mesh_triangle *triangles, double t_min,
                        double t_max, triangle_hit *out)
{
    vec3 c[3];
    for (int i = 0; i < 3; i++) /* NULL: the lane's own, at hand */
        c[i] = vertices == NULL
                   ? (vec3){q->corner[i][0][k], q->corner[i][1][k],
                            q->corner[i][2][k]}
                   : vertices[triangles[q->triangle[k]].v[i]];
    return triangle_hit_tightened(r->exact, &c[0], &c[1], &c[2], t_min,
                                  t_max, out);
}

/* <<deciding the kept lanes>> ch10 */
int triangle_packets_nearest_in_mesh(const packet_ray *r,
                                     const triangle_packet *packets,
                                     int count, const vec3 *vertices,
                                     const mesh_triangle *triangles,
                                     double t_min, double t_max, int best,
                                     triangle_hit *out, long long *decided)
{
    int nearest = -1;
    double t_upto = double_after(t_max); /* t_max itself, for a tie */
    float_interval in = float_interval_of(t_min, t_upto);
    for (int p = 0; p < count; p++)
        for (unsigned bits = candidates(&packets[p], r, in, LANE_BY_LANE);
             bits != 0;
             bits &= bits - 1) {
            int k = __builtin_ctz(bits), i = packets[p].triangle[k];
            triangle_hit th;
            ++*decided;
            if (hit_in_lane(r, &packets[p], k, vertices, triangles, t_min,
                            t_upto, &th) &&
                (th.t < t_max || i < best)) { /* a tie: the lower index */
                *out = th, t_max = th.t, best = i, nearest = i;
                t_upto = double_after(t_max);
                in = float_interval_of(t_min, t_upto);
            }
        }
    return nearest;
}

bool triangle_packets_any_in_mesh(const packet_ray *r,
                                  const triangle_packet *packets, int count,
                                  const vec3 *vertices,
                                  const mesh_triangle *triangles,
                                  double t_min, double t_max,
                                  long long *decided)
{
    float_interval in = float_interval_of(t_min, t_max);
    triangle_hit unused;
    for (int p = 0; p < count; p++)
        for (unsigned bits = candidates(&packets[p], r, in, LANE_BY_LANE);
             bits != 0;
             bits &= bits - 1) {
            ++*decided;
            if (hit_in_lane(r, &packets[p], __builtin_ctz(bits), vertices,
                            triangles, t_min, t_max, &unused))
                return true;
        }
    return false;
}

/* <<the float decision, made>> ch10 */
/* What the lanes hit in float need for their answers: t = n / det, and
 * u / det, v / det, w / det. */
typedef struct {
    packet_float u, v, w, n, det;
} float_hits;

/* The lanes of p hit in float alone: -1 in each; their numbers in *h. */
static inline packet_int float_hits_in_vectors(const triangle_packet *p,
                                               const packet_ray *r,
                                               float t_min, float t_max,
                                               float_hits *h)
{
    typedef packet_float lanes;
    typedef packet_int lane_mask;
    const lanes *a = p->corner[0], *b = p->corner[1], *c = p->corner[2];
    lane_mask empty = p->triangle < 0;
    /* <<the float decision>> ch10 */
    /* <<the edge functions in float>> ch10 */
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float ox = r->origin[0], oy = r->origin[1], oz = r->origin[2];
    lanes az = a[kz] - oz, bz = b[kz] - oz, cz = c[kz] - oz;
    lanes ax = (a[kx] - ox) - r->sx * az, ay = (a[ky] - oy) - r->sy * az;
    lanes bx = (b[kx] - ox) - r->sx * bz, by = (b[ky] - oy) - r->sy * bz;
    lanes cx = (c[kx] - ox) - r->sx * cz, cy = (c[ky] - oy) - r->sy * cz;
    lanes u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    lane_mask inside = ((u >= 0) & (v >= 0) & (w >= 0)) |
                       ((u <= 0) & (v <= 0) & (w <= 0));
    if (lanes_all(inside == 0)) /* an edge between, in every lane */
        return (lane_mask){0};
    lanes det = u + v + w;
    lanes n = u * (r->sz * az) + v * (r->sz * bz) + w * (r->sz * cz);
    /* n / det in (t_min, t_max], without dividing: det's sign decides */
    lane_mask ahead = ((det > 0) & (n > t_min * det) & (n <= t_max * det)) |
                      ((det < 0) & (n < t_min * det) & (n >= t_max * det));
    lane_mask hit = inside & ahead & (empty == 0);
    *h = (float_hits){u, v, w, n, det};
    return hit;
}

/* Lane k of float_hits_in_vectors, computed alone: 1 or 0. */
static inline int float_hit_alone(const triangle_packet *p, int k,
                                  const packet_ray *r, float t_min,
                                  float t_max, float_hits *h)
{
    typedef float lanes;
    typedef int lane_mask;
    float a[3], b[3], c[3];
    for (int axis = 0; axis < 3; axis++)
        a[axis] = p->corner[0][axis][k], b[axis] = p->corner[1][axis][k],
        c[axis] = p->corner[2][axis][k];
    int empty = p->triangle[k] < 0;
    /* <<the float decision>> ch10 */
    /* <<the edge functions in float>> ch10 */
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float ox = r->origin[0], oy = r->origin[1], oz = r->origin[2];
    lanes az = a[kz] - oz, bz = b[kz] - oz, cz = c[kz] - oz;
    lanes ax = (a[kx] - ox) - r->sx * az, ay = (a[ky] - oy) - r->sy * az;
    lanes bx = (b[kx] - ox) - r->sx * bz, by = (b[ky] - oy) - r->sy * bz;
    lanes cx = (c[kx] - ox) - r->sx * cz, cy = (c[ky] - oy) - r->sy * cz;
    lanes u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    lane_mask inside = ((u >= 0) & (v >= 0) & (w >= 0)) |
                       ((u <= 0) & (v <= 0) & (w <= 0));
    if (lanes_all(inside == 0)) /* an edge between, in every lane */
        return (lane_mask){0};
    lanes det = u + v + w;
    lanes n = u * (r->sz * az) + v * (r->sz * bz) + w * (r->sz * cz);
    /* n / det in (t_min, t_max], without dividing: det's sign decides */
    lane_mask ahead = ((det > 0) & (n > t_min * det) & (n <= t_max * det)) |
                      ((det < 0) & (n < t_min * det) & (n >= t_max * det));
    lane_mask hit = inside & ahead & (empty == 0);
    h->u[k] = u, h->v[k] = v, h->w[k] = w, h->n[k] = n, h->det[k] = det;
    return hit;
}

/* The lanes of p hit in float alone, lane k in bit k; their numbers in
 * *h. */
static unsigned float_hit_bits(const triangle_packet *p, const packet_ray *r,
                               float t_min, float t_max, float_hits *h,
                               bool alone)
{
    unsigned bits = 0;
    if (alone) {
        memset(h, 0, sizeof *h); /* a lane that stops early writes none */
        for (int k = 0; k < PACKET_W; k++)
            bits |= (unsigned)float_hit_alone(p, k, r, t_min, t_max, h) << k;
        return bits;
    }
    return packet_bits(float_hits_in_vectors(p, r, t_min, t_max, h));
}

unsigned triangle_packet_float_hits(const triangle_packet *p,
                                    const packet_ray *r, double t_min,
                                    double t_max, bool alone)
{
    float_hits h;
    return float_hit_bits(p, r, (float)t_min, (float)t_max, &h, alone);
}

int triangle_packets_nearest_float(const packet_ray *r,
                                   const triangle_packet *packets, int count,
                                   double t_min, double t_max, int best,
                                   triangle_hit *out)
{
    float lo = (float)t_min, nearest_t = (float)t_max;
    float_hits won; /* the nearest hit's packet, and its lane */
    int nearest = -1, lane = 0;
    for (const triangle_packet *q = packets; q < packets + count; q++) {
        float_hits h;
        unsigned bits = float_hit_bits(q, r, lo, nearest_t, &h, LANE_BY_LANE);
        if (bits == 0)
            continue;
        packet_float t = h.n / h.det; /* every lane's t at once */
        for (; bits != 0; bits &= bits - 1) {
            int k = __builtin_ctz(bits), i = q->triangle[k];
            if (!(t[k] > lo) || t[k] > nearest_t ||
                (t[k] == nearest_t && i > best))
                continue; /* a tie: the lower index */
            nearest_t = t[k], best = i, nearest = i, won = h, lane = k;
        }
    }
    if (nearest >= 0) { /* the barycentric coordinates of the winner */
        float inv = 1 / won.det[lane];
        out->t = nearest_t;
        out->b[0] = won.u[lane] * inv, out->b[1] = won.v[lane] * inv;
        out->b[2] = won.w[lane] * inv;
    }
    return nearest;
}

bool triangle_packets_any_float(const packet_ray *r,
                                const triangle_packet *packets, int count,
                                double t_min, double t_max)
{
    float lo = (float)t_min, hi = (float)t_max;
    for (const triangle_packet *q = packets; q < packets + count; q++) {
        float_hits h;
        unsigned bits = float_hit_bits(q, r, lo, hi, &h, LANE_BY_LANE);
        if (bits == 0)
            continue;
        packet_float t = h.n / h.det;
        for (; bits != 0; bits &= bits - 1) {
            int k = __builtin_ctz(bits);
            if (t[k] > lo && t[k] < hi)
                return true;
        }
    }
    return false;
}
