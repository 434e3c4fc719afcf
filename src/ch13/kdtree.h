/* kdtree.h: kd-trees over items with boxes, built by the surface area
 * heuristic, and walked by rays (chapter 8).
 *
 * A kdtree cuts a box, its root cell, by axis-aligned planes into cells;
 * each leaf lists the items (triangles of a mesh, objects of a scene) that
 * meet its cell. kdtree_build makes one from the items' bounding boxes and
 * a function that clips an item to a cell; a kdtree_walk hands out the
 * leaves a ray passes through, nearest first. The tree knows nothing else
 * of what its items are. A tree with no nodes is "no tree": search its
 * items one by one. */
#ifndef KDTREE_H
#define KDTREE_H

#include <assert.h>
#include <stdbool.h>
#include <stdint.h>
#include "box.h"

/* <<kd-tree parameters>> ch08 */
typedef enum {
    KDTREE_SAH,         /* surface area heuristic, events sorted once */
    KDTREE_SAH_SORTING, /* the same tree, events sorted again per node */
    KDTREE_MEDIAN,      /* the longest axis cut in the middle */
    KDTREE_NONE         /* no tree: every item is tested */
} kdtree_method;

typedef struct {
    kdtree_method method;
    double traversal_cost;    /* K_T: one step down the tree */
    double intersection_cost; /* K_I: one item tested */
    double empty_bonus;       /* in [0, 1): discount of an empty side */
    int max_depth;            /* 0: 8 + 1.3 log2 N */
    int min_items;            /* fewer items than this get no tree;
                                 0: the default of the caller */
} kdtree_params;

/* The defaults the chapter's measurements chose. */
kdtree_params kdtree_default_params(void);

#define KDTREE_MAX_DEPTH 64 /* the walk's stack has room for this many */
/* Memory stays bounded whatever the input: a build stops splitting before
 * its leaves hold more than this many references per item. */
#define KDTREE_REFERENCES_PER_ITEM 8
/* The walk treats every plane as this thick, relative to the largest
 * coordinate of the root cell: far more than the rounding of a clipped
 * box or of a triangle test moves a point. */
#define KDTREE_THICKNESS 0x1p-32

/* <<kd-tree nodes>> ch08 */
/* Interior node k cuts its cell at `split` on axis bits & 3 (0, 1, 2);
 * its children are node k + 1 (below the plane) and node bits >> 2
 * (above). A leaf (bits & 3 == 3) lists bits >> 2 items from
 * items[first]. Sixteen bytes, four to a cache line. */
typedef struct {
    union {
        double split;
        uint32_t first;
    };
    uint32_t bits;
} kdtree_node;

_Static_assert(sizeof(kdtree_node) == 16, "a node is sixteen bytes");

typedef struct kdtree {
    kdtree_node *nodes; /* node 0 is the root */
    int node_count, node_capacity;
    int *items; /* leaf after leaf */
    int item_count, item_capacity;
    box bounds;       /* the root cell */
    double thickness; /* of the planes, for the walk: see KDTREE_THICKNESS */
    int depth;        /* of the deepest leaf */
    int leaf_count;
} kdtree;

void kdtree_free(kdtree *t);

/* <<kd-tree building>> ch08 */
/* The part of item that lies in the closed box cell: its bounding box in
 * *out and true; false if there is none. */
typedef bool (*kdtree_clip)(const void *context, int item, const box *cell,
                            box *out);

/* Builds t over count items whose bounding boxes are bounds[0..count),
 * by p->method; clip (with context) cuts an item to a cell. Leaves no
 * tree when count < p->min_items or p->method is KDTREE_NONE. False only
 * when out of memory. */
bool kdtree_build(kdtree *t, int count, const box *bounds, kdtree_clip clip,
                  const void *context, const kdtree_params *p);

/* The bytes t holds: its nodes and its items, as allocated. */
long long kdtree_bytes(const kdtree *t);

/* <<kd-tree walking>> ch08 */
/* How far the walk's comparisons of t lean towards going on: relative,
 * and far above the rounding of any t it compares. */
#define KDTREE_SLACK 0x1p-20

/* A node still to visit, and the ray's interval inside its cell. */
typedef struct {
    int node; /* -1: none */
    double t_min, t_max;
} kdtree_todo;

/* <<the children a ray passes through>> ch08 */
/* The children of interior node k, whose record is *n, that a ray over
 * [t_min, t_max] passes through, in the order it meets them: next[0],
 * then next[1] (node -1: none). The plane is thick: the ray is below it
 * until it crosses its top face and above it from its bottom face on.
 * low and high are the ray's origin minus and plus the thickness on the
 * node's axis, inv is 1 / d there. */
static inline void kdtree_children(const kdtree_node *n, int k, double low,
                                   double high, double inv, double t_min,
                                   double t_max, kdtree_todo next[2])
{
    double t_top = (n->split - low) * inv, t_bottom = (n->split - high) * inv;
    int below = k + 1, above = (int)(n->bits >> 2);
    /* a comparison with NaN (0 * inf: on a face) keeps the whole interval */
    kdtree_todo under = {below, t_min, t_max}, over = {above, t_min, t_max};
    if (inv < 0) { /* going down: above, then below */
        over.t_max = t_bottom < t_max ? t_bottom : t_max;
        under.t_min = t_top > t_min ? t_top : t_min;
        next[0] = over, next[1] = under;
    } else {
        under.t_max = t_top < t_max ? t_top : t_max;
        over.t_min = t_bottom > t_min ? t_bottom : t_min;
        next[0] = under, next[1] = over;
    }
    for (int c = 0; c < 2; c++)
        if (!(next[c].t_min <= next[c].t_max))
            next[c].node = -1; /* the ray misses this side */
    if (next[0].node < 0)
        next[0] = next[1], next[1].node = -1;
}

/* <<the iterative walk>> ch08 */
/* A walk of one ray through a tree. */
typedef struct {
    const kdtree_node *nodes;
    double low[3], high[3], inv[3]; /* origin -+ thickness, 1 / d */
    kdtree_todo now; /* node -1: take the next from the stack */
    kdtree_todo stack[KDTREE_MAX_DEPTH];
    int pending;
    long long visited; /* nodes, for --stats */
} kdtree_walk;

/* A leaf: its items are items[first .. first + count). */
typedef struct {
    int first, count;
} kdtree_leaf;

/* Starts a walk of the ray origin + t d, inv = 1 / d, over [t_min, t_max]
 * (where it lies inside t's root cell) through the non-empty tree t. */
static inline void kdtree_walk_start(kdtree_walk *w, const kdtree *t,
                                     vec3 origin, vec3 inv, double t_min,
                                     double t_max)
{
    assert(t->depth <= KDTREE_MAX_DEPTH); /* the stack has room */
    w->nodes = t->nodes;
    for (int k = 0; k < 3; k++) {
        w->low[k] = vec3_axis(origin, k) - t->thickness;
        w->high[k] = vec3_axis(origin, k) + t->thickness;
        w->inv[k] = vec3_axis(inv, k);
    }
    w->now = (kdtree_todo){0, t_min, t_max};
    w->pending = 0;
    w->visited = 0;
}

/* The next leaf the ray passes through, nearest first; false once no leaf
 * is left that could hold a hit nearer than best. */
static inline bool kdtree_walk_next(kdtree_walk *w, double best,
                                    kdtree_leaf *leaf)
{
    for (;;) {
        if (w->now.node < 0) {
            if (w->pending == 0)
                return false;
            w->now = w->stack[--w->pending];
            if (w->now.t_min > best * (1 + KDTREE_SLACK)) {
                w->now.node = -1; /* beyond the hit; one below may not be */
                continue;
            }
        }
        const kdtree_node *n = &w->nodes[w->now.node];
        int axis = (int)(n->bits & 3);
        w->visited++;
        if (axis == 3) {
            *leaf = (kdtree_leaf){(int)n->first, (int)(n->bits >> 2)};
            w->now.node = -1;
            return true;
        }
        kdtree_todo next[2];
        kdtree_children(n, w->now.node, w->low[axis], w->high[axis],
                        w->inv[axis], w->now.t_min, w->now.t_max, next);
        if (next[1].node >= 0)
            w->stack[w->pending++] = next[1];
        w->now = next[0];
    }
}

#endif
