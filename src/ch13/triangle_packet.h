/* triangle_packet.h: triangles PACKET_W at a time, in float (chapter 10).
 *
 * A triangle_packet holds PACKET_W triangles of a mesh, lane by lane:
 * their corners rounded to float, and their indices in the mesh (-1: an
 * empty lane, never hit). A filter in float keeps every lane that chapter
 * 4's test in double could hit, and that test decides the lanes kept, on
 * the mesh's own corners: every answer is chapter 4's, ties included
 * (triangle_packets_nearest_in_mesh, _any_in_mesh). The same test decided
 * in float alone is faster, and gives float's answers
 * (triangle_packets_nearest_float, _any_float). Both are compiled in
 * vectors and lane by lane (-DRT_SCALAR), which agree bit for bit. */
#ifndef TRIANGLE_PACKET_H
#define TRIANGLE_PACKET_H

#include <stdint.h>
#include <string.h>
#include "triangle.h"

/* <<a packet of triangles>> ch10 */
#ifndef TRIANGLE_PACKET_WIDTH
#define TRIANGLE_PACKET_WIDTH 4 /* lanes of a packet: 4, or 8 with AVX */
#endif
#define PACKET_W TRIANGLE_PACKET_WIDTH

/* Aligned to their size even where no register is that wide (no AVX). */
typedef float packet_float
    __attribute__((vector_size(4 * PACKET_W), aligned(4 * PACKET_W)));
typedef int32_t packet_int
    __attribute__((vector_size(4 * PACKET_W), aligned(4 * PACKET_W)));

typedef struct {
    packet_float corner[3][3]; /* [corner][axis], a lane each */
    packet_float reach;        /* each lane's largest |coordinate| */
    packet_int triangle;       /* index in the mesh; -1: an empty lane */
} triangle_packet;

_Static_assert(sizeof(triangle_packet) == 11 * 4 * PACKET_W,
               "a packet is eleven vectors, with no padding");
_Static_assert(_Alignof(triangle_packet) == 4 * PACKET_W,
               "a packet starts where a vector may");

/* The packets that count triangles fill: ceil(count / PACKET_W). */
int triangle_packets_needed(int count);

/* The bytes a packet spends on each of its lanes' triangles. */
#define TRIANGLE_PACKET_BYTES_PER_TRIANGLE (sizeof(triangle_packet) / PACKET_W)

/* Packs the count triangles items[0..count) of a mesh (vertices,
 * triangles; items NULL: 0..count-1) into packets, PACKET_W to a packet,
 * in order; the last packet's spare lanes empty. packets must have room
 * for triangle_packets_needed(count) packets, aligned as triangle_packet
 * is (memory_alloc_aligned). Returns the number of packets filled. */
int triangle_packets_fill(triangle_packet *packets, const vec3 *vertices,
                          const mesh_triangle *triangles, const int *items,
                          int count);

/* <<a ray for packets>> ch10 */
typedef struct {
    int kx, ky, kz;
    float sx, sy, sz;     /* chapter 4's shear, rounded to float */
    float origin[3];      /* along kx, ky, kz, rounded to float */
    float origin_reach;   /* the origin's largest |coordinate| */
    const watertight_ray *exact; /* for the double test */
} packet_ray;

/* w's constants for the float test, and w itself (which must outlive
 * them). */
packet_ray packet_ray_of(const watertight_ray *w);

/* <<the tests of packets>> ch10 */
/* x rounded to the float at or above it, as chapter 9's bvh_float_up,
 * with no call: read as an integer, a float's bits count its magnitude,
 * so that one more (one less below zero) is nextafterf's step up. No
 * branch either: whether a hit's t rounds down is a coin's toss, which
 * a branch would guess wrong half the time. */
static inline float float_up_by_bits(double x)
{
    float f = (float)x;
    int32_t bits, below = (double)f < x; /* 0: exact, rounded up, a NaN */
    memcpy(&bits, &f, sizeof bits);
    bits += f >= 0 ? below : -below; /* below zero, up is towards it */
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The lanes of p that chapter 4's test could hit in (t_min, t_max), lane
 * k in bit k: computed in vectors, or (alone) lane by lane, which gives
 * the same bits. */
unsigned triangle_packet_candidates(const triangle_packet *p,
                                    const packet_ray *r, double t_min,
                                    double t_max, bool alone);

/* Does the filter stop at the edge functions: does an edge, or the lack
 * of a triangle, rule out every lane of p for r? */
bool triangle_packet_stops_at_edges(const triangle_packet *p,
                                    const packet_ray *r);

/* The nearest triangle of count packets, filled from the mesh (vertices,
 * triangles), that r hits in (t_min, t_max], chapter 4's test deciding
 * on the mesh's corners, by the tie rule of triangle_nearest_of_leaf: a
 * hit at t_max itself wins when its index is below best (-1: nothing
 * found yet, t_max excluded). Returns its index in the mesh and fills
 * *out; or -1. Adds the double tests to *decided (not NULL). vertices
 * NULL: every corner of the mesh is a float, which the packets hold
 * exactly, and the test reads them there. */
int triangle_packets_nearest_in_mesh(const packet_ray *r,
                                     const triangle_packet *packets,
                                     int count, const vec3 *vertices,
                                     const mesh_triangle *triangles,
                                     double t_min, double t_max, int best,
                                     triangle_hit *out, long long *decided);

/* Does r hit any triangle of count packets in (t_min, t_max)? As
 * triangle_packets_nearest_in_mesh. */
bool triangle_packets_any_in_mesh(const packet_ray *r,
                                  const triangle_packet *packets, int count,
                                  const vec3 *vertices,
                                  const mesh_triangle *triangles,
                                  double t_min, double t_max,
                                  long long *decided);

/* Chapter 4's test in float alone, with no bound and no second test:
 * the lanes of p that r hits in (t_min, t_max], lane k in bit k, in
 * vectors or (alone) lane by lane, as triangle_packet_candidates. */
unsigned triangle_packet_float_hits(const triangle_packet *p,
                                    const packet_ray *r, double t_min,
                                    double t_max, bool alone);

/* The nearest triangle of count packets hit in float alone in (t_min,
 * t_max], a hit at t_max itself only when its index is below best (the
 * tie rule of triangle_packets_nearest_in_mesh): its index, its hit in *out; or
 * -1. The hit is float's, t and barycentric coordinates. */
int triangle_packets_nearest_float(const packet_ray *r,
                                   const triangle_packet *packets, int count,
                                   double t_min, double t_max, int best,
                                   triangle_hit *out);

/* Does r hit any triangle of count packets in (t_min, t_max), in float
 * alone? */
bool triangle_packets_any_float(const packet_ray *r,
                                const triangle_packet *packets, int count,
                                double t_min, double t_max);

#endif
