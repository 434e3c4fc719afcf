/* bvh.h: bounding volume hierarchies over items with boxes, built by the
 * binned surface area heuristic, and the walk of a ray through them
 * (chapter 9).
 *
 * A bvh sorts count items (triangles of a mesh), each with a bounding
 * box, into a tree of boxes: every node's box holds its items' boxes, in
 * float, rounded outward. bvh_build makes one (false only when out of
 * memory); the tree knows nothing else of its items. Zero means default
 * in bvh_params. A tree with no nodes is "no tree". A bvh_walk hands out
 * the leaves whose boxes a ray meets, nearest box first, and the caller
 * tests their items. */
#ifndef BVH_H
#define BVH_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#include "box.h"

/* <<bvh parameters>> ch09 */
/* How to build a bvh; zero means default, in every member. */
typedef struct {
    int width;                /* children a node: 2; 0: the default */
    int bins;                 /* candidate planes + 1, 2 to BVH_MAX_BINS;
                                 0: 32 */
    int max_leaf_items;       /* 1 to 15; 0: 8 */
    double traversal_cost;    /* K_T: one node's box test; 0: 1 */
    double intersection_cost; /* K_I: one item's test; 0: 1 */
    int min_items;            /* fewer items get no tree; 0: 1 */
    int item_group;           /* items a leaf tests at once: the costs
                                 count groups; 0: 1 */
} bvh_params;

#define BVH_MAX_BINS 64
/* The build cuts in the middle below this depth: the walk's stack has
 * room for BVH_MAX_DEPTH levels. */
#define BVH_MEDIAN_DEPTH 32
#define BVH_MAX_DEPTH 64
/* Every box is this much larger, relative to the largest coordinate of
 * all items: as chapter 8's planes are thick (KDTREE_THICKNESS), for the
 * rounding of the triangle tests. */
#define BVH_THICKNESS 0x1p-32

/* The defaults, every member filled. */
bvh_params bvh_default_params(void);
/* <<bvh parameters>> += ch11 */

/* Does the walk test nodes with AVX2's eight lanes? Where the processor
 * has AVX2 and FMA and bvh_allow_avx2 has not forbidden it; the build's
 * flags need not name them (the answer is known when the program
 * runs). */
bool bvh_walks_with_avx2(void);

/* false: trees built from now on are walked with the build's own
 * instructions (for the tests, which compare the two). */
void bvh_allow_avx2(bool allowed);

/* Does the walk take AVX-512VL as well: the same eight lanes, with
 * thirty-two vector registers and a compress? Where the walk has AVX2,
 * the processor has AVX-512F, AVX-512VL and POPCNT, and
 * bvh_allow_avx512 has not forbidden it. */
bool bvh_walks_with_avx512(void);

/* false: trees built from now on are walked with AVX2 at most. */
void bvh_allow_avx512(bool allowed);

/* <<bvh nodes>> ch09 */
/* A node of the binary tree, and its box: lo x, y, z, then hi x, y, z,
 * in float, rounded outward. Interior node k (count 0) was split on
 * axis; its children are nodes k + 1 and index. A leaf lists count items
 * from items[index]. 32 bytes, two to a cache line. */
typedef struct {
    float box[6];
    uint32_t index;
    uint16_t count, axis;
} bvh_node;

_Static_assert(sizeof(bvh_node) == 32, "a node is 32 bytes");

/* <<more kinds of bvh node>> ch11 */
/* A node of up to eight children, laid out for the walk: face[2 a] the
 * lower and face[2 a + 1] the upper faces of axis a of the eight
 * children, a lane each; an unused lane has an empty box (lo +inf, hi
 * -inf) and an empty leaf. child[c] is a node's index, or (BVH_LEAF set)
 * a leaf: its item count in bits 27-30, its first item (or packet)
 * below. The children that are nodes take the first lanes, numbered one
 * after another: lane c's is child[0] + c. order[k] holds,
 * in bits 3 o to 3 o + 2, the lane at place k of octant o's order
 * (bit a of o: the ray goes down axis a), farthest first; the top byte
 * of order[0], which the orders leave free, counts the children that
 * are nodes. */
typedef struct {
    float face[6][8];
    uint32_t child[8], order[8];
} bvh_node8;

_Static_assert(sizeof(bvh_node8) == 256, "four cache lines");

#define BVH_LEAF 0x80000000u
#define BVH_COUNT_SHIFT 27
#define BVH_FIRST_MASK ((1u << BVH_COUNT_SHIFT) - 1)
#define BVH_NODES_SHIFT 24 /* in order[0]: how many children are nodes */

/* How many of n's children are nodes: lanes 0 to this less one. */
static inline int bvh_child_nodes(const bvh_node8 *n)
{
    return (int)(n->order[0] >> BVH_NODES_SHIFT);
}

/* A leaf's word: count items (1 to 15; 0: an unused lane) from first. */
static inline uint32_t bvh_leaf_word(uint32_t first, uint32_t count)
{
    return BVH_LEAF | count << BVH_COUNT_SHIFT | first;
}

/* <<a bvh>> ch09 */
typedef struct bvh {
    int width;         /* children a node: 2 */
    bvh_node *nodes;   /* node 0 is the root */
    int node_count;    /* 0: no tree */
    int node_capacity; /* allocated */
    int *items;        /* leaf after leaf */
    int item_count, leaf_count, depth;
    /* <<more of a bvh>> ch11 */
    bvh_node8 *nodes8; /* width 4 or 8; node 0 is the root */
    bool avx2; /* walked with AVX2 (bvh_walks_with_avx2 when collapsed) */
    bool avx512; /* and with AVX-512VL (bvh_walks_with_avx512) */
} bvh;

/* <<bvh building>> ch09 */
/* Builds t over count items whose bounding boxes are bounds[0..count)
 * by p: no tree when count < p->min_items. False only when out of
 * memory (and then no tree). */
bool bvh_build(bvh *t, int count, const box *bounds, const bvh_params *p);

void bvh_free(bvh *t);

/* The bytes t holds: its nodes and its items. */
long long bvh_bytes(const bvh *t);
/* <<bvh building>> += ch11 */

/* The instructions of t's walk: "scalar", the build's own ("SSE2", ...),
 * or AVX2 chosen when the program runs. */
const char *bvh_vector_width_name(const bvh *t);

/* <<bvh ray tests>> ch09 */
/* <<the ray's float constants>> ch09 */
/* What a ray's box tests need, in float: for each axis the face it meets
 * first (near, 0..5 into a box) and last (far), the origin rounded
 * towards the side that makes each face's t smaller (o_near) and larger
 * (o_far), and 1 / d; and its interval. */
typedef struct {
    float o_near[3], o_far[3], inv[3];
    int near[3], far[3];
    float t_min, t_max;
} bvh_ray;

/* Where a far face's t may lie above the float t computed (the rounding
 * of o_far - face, of the product and of 1 / d: 2 gamma_3, and more). */
#define BVH_FAR_WIDENING (1 + 0x1p-21f)
/* How far beyond the nearest hit a box may start and still be opened:
 * relative, far above the rounding of its float t_near. */
#define BVH_SLACK 0x1p-20

/* The constants of the ray origin + t d over [t_min, t_max], with
 * inv = 1 / d; false for a ray beyond float's reach (a coordinate of
 * the origin past 2^100, or of 1 / d below 2^-100, 0 included), which is
 * then searched without the tree. t_min >= 0. */
bool bvh_ray_of(vec3 origin, vec3 inv, double t_min, double t_max,
                bvh_ray *out);

/* <<the scalar node test>> ch09 */
/* x rounded to the float just below it (or equal), and just above. */
static inline float bvh_float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static inline float bvh_float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Which of lanes boxes, their faces stride apart (box[face * stride +
 * lane]), the ray meets in [r->t_min, t_max]: a bit each in the mask,
 * and in t_near[lane] where it enters. A NaN (0 * inf: the ray in a
 * face's plane) never narrows the interval. */
static inline unsigned bvh_lanes_test_scalar(const float *box, int stride,
                                             int lanes, const bvh_ray *r,
                                             float t_max, float *t_near)
{
    unsigned mask = 0;
    for (int c = 0; c < lanes; c++) {
        float t0 = r->t_min, t1 = t_max;
        for (int a = 0; a < 3; a++) {
            float enter = box[r->near[a] * stride + c] - r->o_near[a];
            float leave = box[r->far[a] * stride + c] - r->o_far[a];
            enter *= r->inv[a];
            leave = leave * r->inv[a] * BVH_FAR_WIDENING;
            t0 = enter > t0 ? enter : t0; /* a NaN keeps t0 */
            t1 = leave < t1 ? leave : t1;
        }
        t_near[c] = t0;
        mask |= (unsigned)(t0 <= t1) << c;
    }
    return mask;
}

/* <<more node tests>> ch11 */
/* <<the vector node tests>> ch11 */
/* GCC warns that a vector of eight floats is passed otherwise with AVX
 * than without: these functions are always inlined, never called. */
#pragma GCC diagnostic ignored "-Wpsabi"

typedef float bvh_f8 __attribute__((vector_size(32)));
typedef int32_t bvh_i8 __attribute__((vector_size(32)));
typedef float bvh_f4 __attribute__((vector_size(16)));

#define BVH_INLINE static inline __attribute__((always_inline))

/* x in every lane: the eight-lane initializer, which GCC and Clang make
 * one broadcast. A macro, not a function, so that it is compiled with
 * the instructions of the function that uses it: Clang will not let a
 * function with AVX call one without it that returns eight floats (the
 * two would pass them differently), inlined or not. */
#define bvh_splat8(x)                                                        \
    __extension__({                                                          \
        float bvh_x_ = (x); /* x read once */                                \
        (bvh_f8){bvh_x_, bvh_x_, bvh_x_, bvh_x_,                             \
                 bvh_x_, bvh_x_, bvh_x_, bvh_x_};                            \
    })

#ifdef __SSE__ /* two halves of four */
BVH_INLINE bvh_f4 bvh_low(bvh_f8 a)
{
    return __builtin_shufflevector(a, a, 0, 1, 2, 3);
}

BVH_INLINE bvh_f4 bvh_high(bvh_f8 a)
{
    return __builtin_shufflevector(a, a, 4, 5, 6, 7);
}

BVH_INLINE bvh_f8 bvh_join(bvh_f4 lo, bvh_f4 hi)
{
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
}

/* a > b ? a : b lane by lane, b where either is a NaN (maxps) */
BVH_INLINE bvh_f8 bvh_max8(bvh_f8 a, bvh_f8 b)
{
    return bvh_join(__builtin_ia32_maxps(bvh_low(a), bvh_low(b)),
                    __builtin_ia32_maxps(bvh_high(a), bvh_high(b)));
}

BVH_INLINE bvh_f8 bvh_min8(bvh_f8 a, bvh_f8 b)
{
    return bvh_join(__builtin_ia32_minps(bvh_low(a), bvh_low(b)),
                    __builtin_ia32_minps(bvh_high(a), bvh_high(b)));
}

/* lane c's comparison (-1 or 0) in bit c */
BVH_INLINE unsigned bvh_mask8(bvh_i8 m)
{
    return (unsigned)__builtin_ia32_movmskps(bvh_low((bvh_f8)m)) |
           (unsigned)__builtin_ia32_movmskps(bvh_high((bvh_f8)m)) << 4;
}
#else
BVH_INLINE bvh_f8 bvh_max8(bvh_f8 a, bvh_f8 b)
{
    bvh_i8 take = a > b; /* false for a NaN */
    return (bvh_f8)(((bvh_i8)a & take) | ((bvh_i8)b & ~take));
}

BVH_INLINE bvh_f8 bvh_min8(bvh_f8 a, bvh_f8 b)
{
    bvh_i8 take = a < b;
    return (bvh_f8)(((bvh_i8)a & take) | ((bvh_i8)b & ~take));
}

BVH_INLINE unsigned bvh_mask8(bvh_i8 m)
{
    unsigned mask = 0;
    for (int c = 0; c < 8; c++)
        mask |= (unsigned)(m[c] & 1) << c;
    return mask;
}
#endif

/* The walk's ray: bvh_ray's numbers in every lane, made once a ray, so
 * that a node's test takes each as an operand, not broadcast at every
 * node; near and far as rows of a node8. */
typedef struct {
    bvh_f8 o_near[3], o_far[3], inv[3];
    bvh_f8 zero_near[3], zero_far[3]; /* AVX2's: -o / d, down and up */
    bvh_f8 inv_far[3]; /* AVX2's: 1 / d widened, for the exits */
    int near[3], far[3];
    int32_t rows[6]; /* AVX2's: near[a], far[a] as byte offsets */
    float t_min;
} bvh_ray8;

/* r (its rows a node8's: bvh_walk_rows) in every lane. */
BVH_INLINE bvh_ray8 bvh_ray8_of(const bvh_ray *r)
{
    bvh_ray8 v;
#pragma GCC unroll 3 /* a constant each axis: no index kept */
    for (int a = 0; a < 3; a++) {
        v.o_near[a] = bvh_splat8(r->o_near[a]);
        v.o_far[a] = bvh_splat8(r->o_far[a]);
        v.inv[a] = bvh_splat8(r->inv[a]);
        v.near[a] = r->near[a], v.far[a] = r->far[a];
    }
    v.t_min = r->t_min;
    return v;
}

/* A row of eight faces read as a vector wherever it lies, as memcpy
 * would read it. */
typedef float bvh_f8_row
    __attribute__((vector_size(32), aligned(4), may_alias));

/* Where the ray enters (row r->near[a]) and leaves (r->far[a]) the eight
 * slabs of axis a: rows of n->face, as the walk's ray names them. Macros,
 * for the reason bvh_splat8 is one. */
#define bvh_enter8(n, r, a)                                                  \
    ((*(const bvh_f8_row *)(n)->face[(r)->near[a]] - (r)->o_near[a]) *       \
     (r)->inv[a])
#define bvh_leave8(n, r, a)                                                  \
    ((*(const bvh_f8_row *)(n)->face[(r)->far[a]] - (r)->o_far[a]) *         \
     (r)->inv[a])

/* The text of the node test (below) names its operations max8, min8 and
 * mask8: here those of the build's own instructions. */
#define max8 bvh_max8
#define min8 bvh_min8
#define mask8 bvh_mask8

/* <<the slab test of a node>> ch11 */
/* Which of n's children the ray r meets in [r->t_min, bound]: a bit
 * each, and in t_near where it enters. */
static inline unsigned bvh_node8_lanes(const bvh_node8 *n, const bvh_ray8 *r,
                                       float bound, float t_near[8])
{
    bvh_f8 t0 = max8(bvh_enter8(n, r, 0), bvh_splat8(r->t_min));
    t0 = max8(bvh_enter8(n, r, 1), t0); /* a NaN keeps t0 */
    t0 = max8(bvh_enter8(n, r, 2), t0);
    bvh_f8 t1 = min8(bvh_leave8(n, r, 0), bvh_splat8(INFINITY));
    t1 = min8(bvh_leave8(n, r, 1), t1);
    t1 = min8(bvh_leave8(n, r, 2), t1);
    /* widened once, not axis by axis */
    t1 = min8(t1 * BVH_FAR_WIDENING, bvh_splat8(bound));
    memcpy(t_near, &t0, sizeof t0);
    return mask8(t0 <= t1);
}

/* The same for r as bvh_ray_of makes it (its rows the walk's:
 * bvh_walk_rows); lane by lane with -DRT_SCALAR, chapter 9's test. */
static inline unsigned bvh_node8_test(const bvh_node8 *n, const bvh_ray *r,
                                      float bound, float t_near[8])
{
#ifdef RT_SCALAR
    return bvh_lanes_test_scalar(&n->face[0][0], 8, 8, r, bound, t_near);
#else
    bvh_ray8 v = bvh_ray8_of(r);
    return bvh_node8_lanes(n, &v, bound, t_near);
#endif
}

#undef max8
#undef min8
#undef mask8

#if defined(__x86_64__) && !defined(RT_SCALAR)
#define BVH_AVX2_TARGET __attribute__((target("avx2,fma")))
#define BVH_HAS_AVX2_PATH 1
#else /* no AVX2 to choose: the walk never asks for it */
#define BVH_AVX2_TARGET
#define BVH_HAS_AVX2_PATH 0
#endif

#if BVH_HAS_AVX2_PATH
#define max8 __builtin_ia32_maxps256
#define min8 __builtin_ia32_minps256
#define mask8(m) (unsigned)__builtin_ia32_movmskps256((bvh_f8)(m))
#endif

/* Where the ray enters and leaves the eight slabs of axis a, each face
 * by one fused multiply-add: face / d plus -o / d, rounded once. */
#define bvh_row8(n, offset)                                                  \
    (*(const bvh_f8_row *)((const char *)(n) + (offset)))
#define bvh_enter_fused(n, r, a)                                             \
    __builtin_ia32_vfmaddps256(bvh_row8(n, (r)->rows[2 * (a)]), (r)->inv[a], \
                               (r)->zero_near[a])
#define bvh_leave_fused(n, r, a)                                             \
    __builtin_ia32_vfmaddps256(bvh_row8(n, (r)->rows[2 * (a) + 1]),          \
                               (r)->inv_far[a], (r)->zero_far[a])

/* Which of n's children the ray r meets, as bvh_node8_lanes, in AVX2's
 * eight lanes with FMA, whatever the build's flags; the same again in
 * met, -1 in a lane met and 0 in the others, for a push to permute. To
 * be called only where bvh_walks_with_avx2() says yes. r's zero_near and
 * zero_far must be made (bvh_ray8_fused). */
BVH_AVX2_TARGET static inline unsigned
bvh_node8_lanes_avx2(const bvh_node8 *n, const bvh_ray8 *r, float bound,
                     float t_near[8], int32_t met[8])
{
#if BVH_HAS_AVX2_PATH
    /* <<the fused slab test of a node>> ch11 */
    bvh_f8 t0 = max8(bvh_enter_fused(n, r, 0), bvh_splat8(r->t_min));
    t0 = max8(bvh_enter_fused(n, r, 1), t0); /* a NaN keeps t0 */
    t0 = max8(bvh_enter_fused(n, r, 2), t0);
    bvh_f8 t1 = min8(bvh_leave_fused(n, r, 0), bvh_splat8(bound));
    t1 = min8(bvh_leave_fused(n, r, 1), t1);
    t1 = min8(bvh_leave_fused(n, r, 2), t1); /* widened by inv_far */
    bvh_i8 hit = t0 <= t1;
    memcpy(t_near, &t0, sizeof t0);
    memcpy(met, &hit, sizeof hit);
    return mask8(hit);
#else
    unsigned mask = bvh_node8_lanes(n, r, bound, t_near);
    for (int c = 0; c < 8; c++)
        met[c] = -(int32_t)(mask >> c & 1);
    return mask;
#endif
}

/* How far -o / d, rounded to the nearest float p, is moved outward so
 * that it lies on the safe side of the exact value after the rounding
 * of the move itself: 4 u |p|, and the smallest float (an underflow). */
static inline float bvh_zero_margin(float p)
{
    return fabsf(p) * 0x1p-22f + 0x1p-149f;
}

/* For each octant, the byte offsets in a node8 of its near and far
 * faces, axis by axis (bvh.c fills it). */
extern int32_t bvh_octant_rows[8][6];

/* The fused test's numbers of r (its rows a node8's: bvh_walk_rows): the
 * exits' 1 / d, widened; its crossings of the planes through zero,
 * -o / d, from its float origins and the 1 / d of the entries (rounded
 * down: zero_near) or of the exits (rounded up: zero_far); its rows. */
BVH_INLINE void bvh_ray8_fused(bvh_ray8 *v, const bvh_ray *r)
{
    unsigned octant = 0;
    for (int a = 0; a < 3; a++)
        octant |= (unsigned)(r->near[a] != 2 * a) << a;
    memcpy(v->rows, bvh_octant_rows[octant], sizeof v->rows);
    for (int a = 0; a < 3; a++) {
        float inv_far = r->inv[a] * BVH_FAR_WIDENING;
        float p_near = -r->o_near[a] * r->inv[a];
        float p_far = -r->o_far[a] * inv_far;
        v->inv_far[a] = bvh_splat8(inv_far);
        v->zero_near[a] = bvh_splat8(p_near - bvh_zero_margin(p_near));
        v->zero_far[a] = bvh_splat8(p_far + bvh_zero_margin(p_far));
    }
}

/* bvh_node8_lanes_avx2 for r as bvh_ray_of makes it (for the tests). */
BVH_AVX2_TARGET static inline unsigned
bvh_node8_test_avx2(const bvh_node8 *n, const bvh_ray *r, float bound,
                    float t_near[8])
{
    bvh_ray8 v = bvh_ray8_of(r);
    bvh_ray8_fused(&v, r);
    int32_t met[8];
    return bvh_node8_lanes_avx2(n, &v, bound, t_near, met);
}

#undef max8
#undef min8
#undef mask8

/* Each level pushes at most seven children more than it takes; a push
 * writes eight lanes above the top before it knows how many it keeps. */
#define BVH_STACK8 (7 * BVH_MAX_DEPTH + 9)

/* The bound of the boxes after a hit at t, a float (the float path's):
 * t (1 + BVH_SLACK) rounded to the nearest float, then the next float
 * up, which lies above the exact product (bvh_float_up's bound, or one
 * float more), in float alone; a NaN, which bounds nothing, where that
 * step would leave the floats (infinity) or cross zero (-0). t is a
 * hit's distance, never a NaN. */
static inline float bvh_bound_after(float t)
{
    float p = t * (float)(1 + BVH_SLACK);
    uint32_t bits; /* read as an integer, a float's bits count its size */
    memcpy(&bits, &p, sizeof bits);
    /* below zero (the sign bit set), up is towards zero: one less */
    bits += bits >> 31 ? UINT32_MAX : 1;
    memcpy(&p, &bits, sizeof p);
    return p;
}

/* r's faces as rows of a node8 (face 2 a or 2 a + 1 of axis a), in
 * place; the shift of its octant's orders (3 o). */
static inline unsigned bvh_walk_rows(bvh_ray *r)
{
    unsigned octant = 0;
    for (int a = 0; a < 3; a++) {
        int down = r->near[a] != a; /* enters by the upper face */
        octant |= (unsigned)down << a;
        r->near[a] = 2 * a + down, r->far[a] = 2 * a + 1 - down;
    }
    return 3 * octant;
}

/* <<pushing the children hit>> ch11 */
/* The children of n in mask (more than one), onto the stack at top in
 * the order of the ray's octant (shift), farthest first: the new top. */
static inline int bvh_push8(uint32_t *stack, float *entry, int top,
                            const bvh_node8 *n, unsigned mask,
                            const float t_near[8], unsigned shift)
{
    for (int k = 0; k < 8; k++) {
        unsigned c = n->order[k] >> shift & 7;
        stack[top] = n->child[c], entry[top] = t_near[c];
        top += (int)(mask >> c & 1); /* kept only if hit */
    }
    return top;
}

/* The origin of r rounded outward, axis by axis (bvh_ray_of's rule). */
static inline void bvh_round_origin(const double o[3], bvh_ray *r)
{
    for (int a = 0; a < 3; a++) {
        float up = bvh_float_up(o[a]), down = bvh_float_down(o[a]);
        bool ahead = r->near[a] == 2 * a;
        r->o_near[a] = ahead ? up : down, r->o_far[a] = ahead ? down : up;
    }
}

/* bvh_ray_of's ray, its rows those of a node8 (bvh_walk_rows), made
 * inline; the shift of its octant's orders in *shift. false where
 * bvh_ray_of says false. */
BVH_INLINE bool bvh_wide_ray_of(vec3 origin, vec3 inv, double t_min,
                                double t_max, bvh_ray *r, unsigned *shift)
{
    const double o[3] = {origin.x, origin.y, origin.z};
    const double q[3] = {inv.x, inv.y, inv.z};
    unsigned octant = 0;
    bool near = true, in_float = true; /* no branch until the end */
#pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        near &= (fabs(o[a]) <= 0x1p100) & (fabs(q[a]) >= 0x1p-100);
        float f = (float)o[a];
        in_float &= (double)f == o[a];
        int down = signbit(q[a]) != 0; /* enters by the upper face */
        r->o_near[a] = r->o_far[a] = f, r->inv[a] = (float)q[a];
        r->near[a] = 2 * a + down, r->far[a] = 2 * a + 1 - down;
        octant |= (unsigned)down << a;
    }
    if (!in_float) /* a float origin needs no rounding */
        bvh_round_origin(o, r);
    r->t_min = bvh_float_down(t_min);
    r->t_max = bvh_float_up(t_max * (1 + BVH_SLACK));
    *shift = 3 * octant;
    return near;
}

/* The walk's ray in vectors and the bound of its boxes (bvh_ray_of's
 * t_max), by bvh_wide_ray_of and bvh_ray8_of: false where they say so. */
BVH_INLINE bool bvh_ray8_setup(vec3 origin, vec3 inv, double t_min,
                               double t_max, bvh_ray8 *v, float *ray_bound,
                               unsigned *shift)
{
    bvh_ray r;
    if (!bvh_wide_ray_of(origin, inv, t_min, t_max, &r, shift))
        return false;
    *v = bvh_ray8_of(&r), *ray_bound = r.t_max;
    bvh_ray8_fused(v, &r);
    return true;
}

typedef double bvh_d4 __attribute__((vector_size(32)));
typedef int64_t bvh_l4 __attribute__((vector_size(32)));

/* Lane a (a constant) of a vector of four in all eight lanes. */
#define bvh_lane8(v, a) __builtin_shufflevector(v, v, a, a, a, a, a, a, a, a)

typedef int32_t bvh_i4 __attribute__((vector_size(16)));

/* bvh_zero_margin lane by lane. */
BVH_AVX2_TARGET static inline bvh_f4 bvh_zero_margins4(bvh_f4 p)
{
    bvh_f4 size = (bvh_f4)((bvh_i4)p & 0x7fffffff); /* |p| */
    return size * 0x1p-22f + 0x1p-149f;
}

/* -o / d lane by lane, o and 1 / d floats, rounded down (*down, from
 * inv) and up (*up, from inv_far): each product to nearest, moved outward
 * by bvh_zero_margin. */
BVH_AVX2_TARGET static inline void bvh_zeros4(bvh_f4 o, bvh_f4 inv,
                                              bvh_f4 inv_far, bvh_f4 *down,
                                              bvh_f4 *up)
{
    bvh_f4 p = -o * inv, q = -o * inv_far;
    *down = p - bvh_zero_margins4(p), *up = q + bvh_zero_margins4(q);
}

/* bvh_ray8_setup in AVX's lanes, the three axes at once (the fourth lane
 * a harmless 1): to be called only where bvh_walks_with_avx2() says yes.
 * An origin that is not a float takes the axis-by-axis way. */
BVH_AVX2_TARGET static inline bool
bvh_ray8_setup_avx2(vec3 origin, vec3 inv, double t_min, double t_max,
                    bvh_ray8 *v, float *ray_bound, unsigned *shift)
{
#if BVH_HAS_AVX2_PATH
    const bvh_d4 o = {origin.x, origin.y, origin.z, 1};
    const bvh_d4 q = {inv.x, inv.y, inv.z, 1};
    const bvh_l4 size = {INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX};
    bvh_l4 near = ((bvh_d4)((bvh_l4)o & size) <= 0x1p100) &
                  ((bvh_d4)((bvh_l4)q & size) >= 0x1p-100);
    bvh_f4 o_f = __builtin_convertvector(o, bvh_f4);
    bvh_l4 in_float = __builtin_convertvector(o_f, bvh_d4) == o;
    if (__builtin_ia32_movmskpd256((bvh_d4)(near & in_float)) != 15)
        return bvh_ray8_setup(origin, inv, t_min, t_max, v, ray_bound, shift);
    bvh_f4 q_f = __builtin_convertvector(q, bvh_f4);
    unsigned octant = (unsigned)__builtin_ia32_movmskpd256(q); /* signs */
    bvh_f4 q_far = q_f * BVH_FAR_WIDENING; /* the exits' 1 / d */
    bvh_f4 zero_near, zero_far;
    bvh_zeros4(o_f, q_f, q_far, &zero_near, &zero_far);
    v->zero_near[0] = bvh_lane8(zero_near, 0);
    v->zero_near[1] = bvh_lane8(zero_near, 1);
    v->zero_near[2] = bvh_lane8(zero_near, 2);
    v->zero_far[0] = bvh_lane8(zero_far, 0);
    v->zero_far[1] = bvh_lane8(zero_far, 1);
    v->zero_far[2] = bvh_lane8(zero_far, 2);
    v->inv[0] = bvh_lane8(q_f, 0);
    v->inv[1] = bvh_lane8(q_f, 1);
    v->inv[2] = bvh_lane8(q_f, 2);
    v->inv_far[0] = bvh_lane8(q_far, 0);
    v->inv_far[1] = bvh_lane8(q_far, 1);
    v->inv_far[2] = bvh_lane8(q_far, 2);
    memcpy(v->rows, bvh_octant_rows[octant & 7], sizeof v->rows);
    v->t_min = bvh_float_down(t_min);
    *ray_bound = bvh_float_up(t_max * (1 + BVH_SLACK));
    *shift = 3 * (octant & 7);
    return true;
#else
    return bvh_ray8_setup(origin, inv, t_min, t_max, v, ray_bound, shift);
#endif
}

/* For each mask of eight lanes, its set lanes from the lowest, three bits
 * each from bit 0, and their count in bits 24-27 (bvh.c fills it). */
extern uint32_t bvh_set_lanes[256];

#if BVH_HAS_AVX2_PATH
/* The lane at each place of n's order for the octant (shift), farthest
 * first, in *order; the places whose lanes are met (-1 in met), place k
 * in bit k. To be called only where bvh_walks_with_avx2() says yes. */
BVH_AVX2_TARGET static inline unsigned
bvh_places_hit(const bvh_node8 *n, const int32_t met[8], unsigned shift,
               bvh_i8 *order)
{
    bvh_i8 lanes;
    memcpy(&lanes, met, sizeof lanes);
    memcpy(order, n->order, sizeof *order);
    *order = *order >> (int)shift & 7;
    bvh_i8 kept = __builtin_ia32_permvarsi256(lanes, *order); /* sign: hit */
    return (unsigned)__builtin_ia32_movmskps256((bvh_f8)kept);
}

/* Lane k of v, moved to lane 0 by a permutation: never through memory. */
BVH_AVX2_TARGET static inline int32_t bvh_lane_of(bvh_i8 v, int k)
{
    return __builtin_ia32_permvarsi256(v, (bvh_i8){0} + k)[0];
}
#endif

/* bvh_push8 of the lanes met (-1 in met) in AVX2's lanes, with no loop,
 * and the child on top (the nearest) in *nearest, from a register: to be
 * called only where bvh_walks_with_avx2() says yes. */
BVH_AVX2_TARGET static inline int
bvh_push8_avx2(uint32_t *stack, float *entry, int top, const bvh_node8 *n,
               const int32_t met[8], const float t_near[8], unsigned shift,
               uint32_t *nearest)
{
#if BVH_HAS_AVX2_PATH
    const bvh_i8 thirds = {0, 3, 6, 9, 12, 15, 18, 21};
    bvh_i8 order, child;
    bvh_f8 t;
    memcpy(&child, n->child, sizeof child);
    memcpy(&t, t_near, sizeof t);
    unsigned hit = bvh_places_hit(n, met, shift, &order);
    bvh_i8 in_order = __builtin_ia32_permvarsi256(child, order);
    /* the highest place kept (place 0 if none: no clz of 0) */
    int last = 31 - __builtin_clz(hit | 1);
    *nearest = (uint32_t)bvh_lane_of(in_order, last);
    uint32_t set = bvh_set_lanes[hit];
    bvh_i8 places = ((bvh_i8){0} + (int)set) >> thirds & 7;
    bvh_i8 lanes = __builtin_ia32_permvarsi256(order, places);
    bvh_i8 kids = __builtin_ia32_permvarsi256(child, lanes);
    bvh_f8 entries = __builtin_ia32_permvarsf256(t, lanes);
    memcpy(stack + top, &kids, sizeof kids);
    memcpy(entry + top, &entries, sizeof entries);
    return top + (int)(set >> 24);
#else
    bvh_i8 lanes;
    memcpy(&lanes, met, sizeof lanes);
    top = bvh_push8(stack, entry, top, n, bvh_mask8(lanes), t_near, shift);
    *nearest = stack[top - 1];
    return top;
#endif
}

#if BVH_HAS_AVX2_PATH
#define BVH_AVX512_TARGET                                                    \
    __attribute__((target("avx2,fma,avx512f,avx512vl,popcnt")))
#else
#define BVH_AVX512_TARGET
#endif

/* bvh_push8_avx2 with AVX-512VL's compress: to be called only where
 * bvh_walks_with_avx512() says yes. */
BVH_AVX512_TARGET static inline int
bvh_push8_avx512(uint32_t *stack, float *entry, int top, const bvh_node8 *n,
                 const int32_t met[8], const float t_near[8], unsigned shift,
                 uint32_t *nearest)
{
#if BVH_HAS_AVX2_PATH
    bvh_i8 order, child;
    bvh_f8 t;
    memcpy(&child, n->child, sizeof child);
    memcpy(&t, t_near, sizeof t);
    unsigned char places =
        (unsigned char)bvh_places_hit(n, met, shift, &order);
    bvh_i8 kids = __builtin_ia32_permvarsi256(child, order);
    bvh_f8 entries = __builtin_ia32_permvarsf256(t, order);
    int last = 31 - __builtin_clz(places | 1u); /* as bvh_push8_avx2's */
    *nearest = (uint32_t)bvh_lane_of(kids, last);
    kids = __builtin_ia32_compresssi256_mask(kids, (bvh_i8){0}, places);
    entries = __builtin_ia32_compresssf256_mask(entries, (bvh_f8){0}, places);
    memcpy(stack + top, &kids, sizeof kids);
    memcpy(entry + top, &entries, sizeof entries);
    return top + __builtin_popcount(places);
#else
    return bvh_push8_avx2(stack, entry, top, n, met, t_near, shift,
                          nearest);
#endif
}

/* <<the bvh walk>> ch09 */
/* A child still to visit: a node (count 0) or a leaf of count items from
 * child, and where the ray enters its box. */
typedef struct {
    uint32_t child, count;
    float t_near;
} bvh_todo;

/* <<the walk's stack>> ch09 */
/* Each level pushes at most one child more than it takes. */
#define BVH_STACK (BVH_MAX_DEPTH + 1)

typedef struct {
    const bvh *t;
    const bvh_ray *r; /* the caller's: read, not copied */
    bvh_todo stack[BVH_STACK];
    int pending;
    long long visited; /* nodes whose children were tested, for --stats */
    double best;       /* the last nearest hit given to bvh_walk_next */
    float t_max;       /* and its bound in float */
    bool sorted;       /* nearest child first; false: any order (any hit) */
} bvh_walk;

/* A leaf: its items are items[first .. first + count). */
typedef struct {
    int first, count;
} bvh_leaf;

/* Starts a walk of the ray r, which must outlive the walk, through the
 * non-empty tree t. */
static inline void bvh_walk_start(bvh_walk *w, const bvh *t,
                                  const bvh_ray *r)
{
    /* a binary tree's root may be a leaf, of a tree of few items */
    const bvh_node *root = t->width == 2 ? &t->nodes[0] : NULL;
    bool leaf = root != NULL && root->count > 0;
    w->t = t, w->r = r, w->pending = 1, w->visited = 0, w->sorted = true;
    w->best = NAN, w->t_max = r->t_max; /* no bound yet: made at first */
    w->stack[0] = (bvh_todo){leaf ? root->index : 0, leaf ? root->count : 0,
                             r->t_min};
}

/* <<taking the children a node's test found>> ch09 */
/* The children in mask: the nearest into *next, the others pushed onto
 * w's stack, farthest on the bottom (unsorted: in the order of their
 * lanes); false when mask is empty. */
static inline bool bvh_take(bvh_walk *w, unsigned mask, const uint32_t *child,
                            const uint32_t *count, const float *t_near,
                            bvh_todo *next)
{
    if (mask == 0)
        return false;
    int c = __builtin_ctz(mask), first = w->pending;
    bvh_todo near = {child[c], count[c], t_near[c]};
    for (mask &= mask - 1; mask != 0; mask &= mask - 1) { /* lowest bit */
        c = __builtin_ctz(mask);
        bvh_todo todo = {child[c], count[c], t_near[c]}, swap = near;
        if (w->sorted && todo.t_near < near.t_near)
            near = todo, todo = swap; /* the nearest stays in hand */
        int k = w->pending++;
        for (; w->sorted && k > first && w->stack[k - 1].t_near < todo.t_near;
             k--)
            w->stack[k] = w->stack[k - 1];
        w->stack[k] = todo;
    }
    *next = near;
    return true;
}

/* The two children of binary node k, tested; taken. */
static inline bool bvh_visit2(bvh_walk *w, uint32_t k, float t_max,
                              bvh_todo *next)
{
    const bvh_node *n = w->t->nodes;
    uint32_t id[2] = {k + 1, n[k].index}, child[2], count[2];
    float t_near[2];
    unsigned mask = 0;
    for (int side = 0; side < 2; side++) {
        const bvh_node *kid = &n[id[side]];
        child[side] = kid->count ? kid->index : id[side];
        count[side] = kid->count;
        mask |= bvh_lanes_test_scalar(kid->box, 1, 1, w->r, t_max,
                                      &t_near[side]) << side;
    }
    return bvh_take(w, mask, child, count, t_near, next);
}

/* The children of node now that the ray meets before t_max, taken: the
 * nearest into *next, the others pushed; false when it meets none. */
static inline bool bvh_visit(bvh_walk *w, bvh_todo now, float t_max,
                             bvh_todo *next)
{
    w->visited++;
    return bvh_visit2(w, now.child, t_max, next);
}

/* best widened by BVH_SLACK, in float, within the ray's own bound; made
 * again only when best changes (rounding up may call the library). */
static inline float bvh_walk_bound(bvh_walk *w, double best)
{
    if (!(best == w->best)) {
        float t_max = bvh_float_up(best * (1 + BVH_SLACK));
        w->t_max = t_max < w->r->t_max ? t_max : w->r->t_max;
        w->best = best;
    }
    return w->t_max;
}

/* The next leaf whose box the ray meets before best (the nearest hit so
 * far, widened by BVH_SLACK: a hit at best itself may still win a tie);
 * false when none is left. A child just found is in range: the nearest
 * is taken at once. */
static inline bool bvh_walk_next(bvh_walk *w, double best, bvh_leaf *leaf)
{
    float t_max = bvh_walk_bound(w, best);
    while (w->pending > 0) {
        bvh_todo now = w->stack[--w->pending];
        if (now.t_near > t_max)
            continue; /* the box starts beyond the nearest hit */
        while (now.count == 0 && bvh_visit(w, now, t_max, &now))
            ; /* down to the nearest child, the others on the stack */
        if (now.count > 0) {
            *leaf = (bvh_leaf){(int)now.child, (int)now.count};
            return true;
        }
    }
    return false;
}

#endif
