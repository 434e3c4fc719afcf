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


/* <<a bvh>> ch09 */
typedef struct bvh {
    int width;         /* children a node: 2 */
    bvh_node *nodes;   /* node 0 is the root */
    int node_count;    /* 0: no tree */
    int node_capacity; /* allocated */
    int *items;        /* leaf after leaf */
    int item_count, leaf_count, depth;
} bvh;

/* <<bvh building>> ch09 */
/* Builds t over count items whose bounding boxes are bounds[0..count)
 * by p: no tree when count < p->min_items. False only when out of
 * memory (and then no tree). */
bool bvh_build(bvh *t, int count, const box *bounds, const bvh_params *p);

void bvh_free(bvh *t);

/* The bytes t holds: its nodes and its items. */
long long bvh_bytes(const bvh *t);

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
