/* bvh.c: building bounding volume hierarchies (chapter 9). See bvh.h. */
#include "bvh.h"

#include <assert.h>
#include <stdlib.h>
#include "memory.h"
/* <<bvh.c includes>> ch11 */
#include <stdatomic.h>

/* <<bvh storage>> ch09 */
bvh_params bvh_default_params(void)
{
    /* <<the default width>> ch11 */
    int width = 8;
    return (bvh_params){.width = width, .bins = 32, .max_leaf_items = 8,
                        .traversal_cost = 1, .intersection_cost = 1,
                        .min_items = 1, .item_group = 1};
}

/* p, its zeros replaced by the defaults. */
static bvh_params bvh_filled(const bvh_params *p)
{
    bvh_params d = bvh_default_params(), q = *p;
    q.width = q.width ? q.width : d.width;
    q.bins = q.bins ? q.bins : d.bins;
    q.max_leaf_items = q.max_leaf_items ? q.max_leaf_items : d.max_leaf_items;
    q.traversal_cost = q.traversal_cost ? q.traversal_cost
                                        : d.traversal_cost;
    q.intersection_cost = q.intersection_cost ? q.intersection_cost
                                              : d.intersection_cost;
    q.min_items = q.min_items ? q.min_items : d.min_items;
    q.item_group = q.item_group ? q.item_group : d.item_group;
    return q;
}

void bvh_free(bvh *t)
{
    free(t->nodes), free(t->items);
    /* <<free more of a bvh>> ch11 */
    free(t->nodes8);
    *t = (bvh){0};
}

long long bvh_bytes(const bvh *t)
{
    long long node = (long long)sizeof(bvh_node);
    /* <<the size of a wider node>> ch11 */
    if (t->width == 4 || t->width == 8)
        node = (long long)sizeof(bvh_node8);
    return t->node_capacity * node + (long long)t->item_count * sizeof(int);
}

/* <<a node's box in float>> ch09 */
/* The box b, widened by pad, in float and rounded outward: every point
 * of b lies inside it. */
static void bvh_set_box(float out[6], const box *b, double pad)
{
    for (int a = 0; a < 3; a++) {
        out[a] = bvh_float_down(vec3_axis(b->lo, a) - pad);
        out[a + 3] = bvh_float_up(vec3_axis(b->hi, a) + pad);
    }
}

static box box_empty(void)
{
    return (box){{INFINITY, INFINITY, INFINITY},
                 {-INFINITY, -INFINITY, -INFINITY}};
}

static box box_union(box a, box b)
{
    return (box){vec3_min(a.lo, b.lo), vec3_max(a.hi, b.hi)};
}

/* The largest of most and the coordinates of b, in magnitude: the boxes'
 * largest, times BVH_THICKNESS, is a build's pad. */
static double largest_coordinate(const box *b, double most)
{
    for (int a = 0; a < 3; a++) { /* not fmax: a call, on most machines */
        double lo = fabs(vec3_axis(b->lo, a)), hi = fabs(vec3_axis(b->hi, a));
        most = lo > most ? lo : most, most = hi > most ? hi : most;
    }
    return most;
}

bool bvh_ray_of(vec3 origin, vec3 inv, double t_min, double t_max,
                bvh_ray *out)
{
    for (int a = 0; a < 3; a++) {
        double o = vec3_axis(origin, a), i = vec3_axis(inv, a);
        if (!(fabs(o) <= 0x1p100) || !(fabs(i) >= 0x1p-100))
            return false;
        bool ahead = !signbit(i); /* d = +0 too: 1 / d = +inf */
        out->near[a] = ahead ? a : a + 3, out->far[a] = ahead ? a + 3 : a;
        /* rounded so that each t can only err outward */
        out->o_near[a] = ahead ? bvh_float_up(o) : bvh_float_down(o);
        out->o_far[a] = ahead ? bvh_float_down(o) : bvh_float_up(o);
        out->inv[a] = (float)i;
    }
    out->t_min = bvh_float_down(t_min);
    out->t_max = bvh_float_up(t_max * (1 + BVH_SLACK));
    return true;
}

/* <<the bins of a split>> ch09 */
/* What a build shares between its nodes: the items' boxes, which it
 * reads; their centers, made first; and the items, reordered range by
 * range. */
typedef struct {
    const box *bounds; /* of each item */
    vec3 *centers;     /* of each item's box */
    int *items;        /* a node's are items[b..e) */
    bvh_params p;
    double pad;        /* every box's, BVH_THICKNESS times the largest
                          coordinate */
} bvh_builder;

typedef struct {
    box b;
    int count;
} bvh_bin;

/* The bin of the center c on axis, for bins from lo, scale bins a unit. */
static int bin_of(vec3 c, int axis, double lo, double scale, int bins)
{
    int k = (int)((vec3_axis(c, axis) - lo) * scale);
    return k < 0 ? 0 : k >= bins ? bins - 1 : k;
}

/* <<a node's passes over its items>> ch09 */
/* The first pass, over every item of items[b..e): its center, its place
 * in the first order, and the largest coordinate of its box; the largest
 * of them. */
static double items_prepared(const bvh_builder *bd, int b, int e)
{
    double most = 0;
    for (int k = b; k < e; k++) {
        const box *bb = &bd->bounds[k];
        bd->centers[k] = vec3_scale(vec3_add(bb->lo, bb->hi), 0.5);
        bd->items[k] = k;
        most = largest_coordinate(bb, most);
    }
    return most;
}

/* The boxes around the items of items[b..e), and around their centers. */
static void items_boxed(const bvh_builder *bd, int b, int e, box *bounds,
                        box *centers)
{
    box bb = box_empty(), cb = box_empty();
    for (int i = b; i < e; i++) {
        int item = bd->items[i];
        bb = box_union(bb, bd->bounds[item]);
        cb = box_union(cb, (box){bd->centers[item], bd->centers[item]});
    }
    *bounds = bb, *centers = cb;
}

/* <<a node's items in bins>> ch09 */
/* The items of items[b..e) in their bins on axis, from lo, scale bins a
 * unit: each bin's count, and the box around its items' boxes. */
static void fill_bins(const bvh_builder *bd, int b, int e, int axis,
                      double lo, double scale, bvh_bin *bins)
{
    for (int k = 0; k < bd->p.bins; k++)
        bins[k] = (bvh_bin){box_empty(), 0};
    for (int i = b; i < e; i++) {
        int item = bd->items[i];
        bvh_bin *in = &bins[bin_of(bd->centers[item], axis, lo, scale,
                                   bd->p.bins)];
        in->count++, in->b = box_union(in->b, bd->bounds[item]);
    }
}

/* <<partitioning a node's items>> ch09 */
/* Puts the items of items[b..e) in bins below k first; the first of the
 * others. */
static int partition(const bvh_builder *bd, int b, int e, int axis,
                     double lo, double scale, int k)
{
    int *it = bd->items, i = b, j = e - 1;
    while (i <= j) {
        if (bin_of(bd->centers[it[i]], axis, lo, scale, bd->p.bins) < k) {
            i++;
        } else {
            int swap = it[i];
            it[i] = it[j], it[j--] = swap;
        }
    }
    return i;
}

/* <<a node's passes>> ch09 */
/* The passes over a node's items, each over items[b..e): the centers of
 * all count items first, then a node's boxes, bins and partition. */
static double pass_prepare(bvh_builder *bd, int count)
{
    return items_prepared(bd, 0, count);
}

static void pass_boxes(bvh_builder *bd, int b, int e, box *bounds,
                       box *centers)
{
    items_boxed(bd, b, e, bounds, centers);
}

static const bvh_bin *pass_bins(bvh_builder *bd, int b, int e, int axis,
                                double lo, double scale, bvh_bin *bins)
{
    fill_bins(bd, b, e, axis, lo, scale, bins);
    return bins;
}

static int pass_partition(bvh_builder *bd, int b, int e, int axis,
                          double lo, double scale, int k)
{
    return partition(bd, b, e, axis, lo, scale, k);
}

/* <<the binned split>> ch09 */
/* The tests of n items, item_group at a time. */
static double groups(const bvh_builder *bd, int n)
{
    return (n + bd->p.item_group - 1) / bd->p.item_group;
}

/* <<the sweep over the bins>> ch09 */
/* The cheapest plane between the bins: the first bin above it, its cost
 * in *cost (infinity, and -1 returned, when no plane has items on both
 * sides); area is the node's (not 0). */
static int best_bin(const bvh_builder *bd, const bvh_bin *bins, double area,
                    double *cost)
{
    int n = bd->p.bins, right_count[BVH_MAX_BINS], left = 0, best = -1;
    double right_area[BVH_MAX_BINS];
    box sweep = box_empty();
    for (int k = n - 1, count = 0; k >= 1; k--) { /* from the right */
        sweep = box_union(sweep, bins[k].b), count += bins[k].count;
        right_area[k] = box_area(&sweep), right_count[k] = count;
    }
    sweep = box_empty(), *cost = INFINITY;
    for (int k = 1; k < n; k++) { /* from the left */
        sweep = box_union(sweep, bins[k - 1].b), left += bins[k - 1].count;
        if (left == 0 || right_count[k] == 0)
            continue;
        double tests = box_area(&sweep) * groups(bd, left) +
                       right_area[k] * groups(bd, right_count[k]);
        double c = bd->p.traversal_cost +
                   bd->p.intersection_cost * tests / area; /* C(split) */
        if (c < *cost)
            *cost = c, best = k;
    }
    return best;
}

/* Where the items of items[b..e), in the box bb, their centers in cb,
 * split: the first item of the upper side, the items reordered and the
 * axis in *axis; -1: a leaf. */
static int split_range(bvh_builder *bd, int b, int e, int depth,
                       const box *bb, const box *cb, int *axis)
{
    int items = e - b;
    vec3 size = vec3_sub(cb->hi, cb->lo);
    *axis = size.y > size.x ? 1 : 0; /* the longest side of the centers */
    *axis = size.z > vec3_axis(size, *axis) ? 2 : *axis;
    double lo = vec3_axis(cb->lo, *axis), extent = vec3_axis(size, *axis);
    if (items == 1)
        return -1;
    if (!(extent > 0) || depth >= BVH_MEDIAN_DEPTH) /* the middle */
        return items <= bd->p.max_leaf_items ? -1 : b + items / 2;
    double scale = bd->p.bins / extent, area = box_area(bb), cost;
    bvh_bin space[BVH_MAX_BINS];
    const bvh_bin *bins = pass_bins(bd, b, e, *axis, lo, scale, space);
    int k = best_bin(bd, bins, area > 0 ? area : 1, &cost);
    if (k < 0 || (items <= bd->p.max_leaf_items &&
                  bd->p.intersection_cost * groups(bd, items) <= cost))
        return k < 0 && items > bd->p.max_leaf_items ? b + items / 2 : -1;
    return pass_partition(bd, b, e, *axis, lo, scale, k);
}

/* <<building a range>> ch09 */
/* Builds the node of items[b..e) at t->nodes[t->node_count], and its
 * subtree after it: its first child's subtree first, then its second's. */
static void build_subtree(bvh_builder *bd, bvh *t, int b, int e, int depth)
{
    int k = t->node_count++;
    box bb, cb;
    pass_boxes(bd, b, e, &bb, &cb);
    bvh_set_box(t->nodes[k].box, &bb, bd->pad);
    int axis = 0, m = split_range(bd, b, e, depth, &bb, &cb, &axis);
    t->nodes[k].axis = (uint16_t)axis;
    t->depth = depth > t->depth ? depth : t->depth;
    if (m < 0) { /* a leaf: its items */
        t->nodes[k].index = (uint32_t)b;
        t->nodes[k].count = (uint16_t)(e - b);
        t->leaf_count++;
        return;
    }
    t->nodes[k].count = 0;
    build_subtree(bd, t, b, m, depth + 1);
    t->nodes[k].index = (uint32_t)t->node_count; /* the second child */
    build_subtree(bd, t, m, e, depth + 1);
}

/* <<more of a bvh build>> ch11 */
/* <<collapsing to wide nodes>> ch11 */
static double float_box_area(const float b[6])
{
    double x = b[3] - b[0], y = b[4] - b[1], z = b[5] - b[2];
    return x * y + y * z + z * x;
}

/* <<the costs of a collapse>> ch11 */
/* What binary node k's subtree adds to the sum of the wide nodes' areas
 * when its place may take up to i lanes: cost[i - 1], i = 1 to the width
 * (the surface area heuristic's price of the node tests a ray makes). */
typedef struct {
    float cost[8];
} bvh_slots;

/* The cheapest share of j >= 2 lanes between interior binary node k's
 * two children, m to the first and j - m to the second: its cost, and
 * in *first the smallest m that costs it. */
static float cheapest_share(const bvh_node *nodes, const bvh_slots *s,
                            int k, int j, int *first)
{
    const float *l = s[k + 1].cost, *r = s[nodes[k].index].cost;
    float best = l[0] + r[j - 2];
    *first = 1;
    for (int m = 2; m < j; m++)
        if (l[m - 1] + r[j - m - 1] < best)
            best = l[m - 1] + r[j - m - 1], *first = m;
    return best;
}

/* <<pricing the collapse>> ch11 */
/* s[k] for each of the count binary nodes, children (numbered after
 * their parent) before parents, for a tree width wide. */
static void price_collapse(const bvh_node *nodes, int count, int width,
                           bvh_slots *s)
{
    for (int k = count - 1; k >= 0; k--) {
        float *c = s[k].cost;
        int m;
        if (nodes[k].count != 0) { /* a leaf: nothing */
            for (int i = 0; i < width; i++)
                c[i] = 0;
            continue;
        }
        c[0] = (float)float_box_area(nodes[k].box) +
               cheapest_share(nodes, s, k, width, &m); /* a wide node */
        for (int i = 2; i <= width; i++) { /* or lanes handed down */
            float shared = cheapest_share(nodes, s, k, i, &m);
            c[i - 1] = shared < c[0] ? shared : c[0];
        }
    }
}

/* <<opening a node's children>> ch11 */
/* Binary node k in up to i lanes, as kids[*n] and on: itself, or, when
 * handing the lanes down to its children costs no more, what they are
 * in their shares. */
static void take_lanes(const bvh_node *nodes, const bvh_slots *s, int k,
                       int i, int kids[8], int *n)
{
    int m = 0;
    if (nodes[k].count == 0 && i >= 2 &&
        cheapest_share(nodes, s, k, i, &m) <= s[k].cost[0]) {
        take_lanes(nodes, s, k + 1, m, kids, n);
        take_lanes(nodes, s, (int)nodes[k].index, i - m, kids, n);
    } else
        kids[(*n)++] = k;
}

/* The children of the wide node made from interior binary node k: its
 * two children in their cheapest share of width lanes. Their count. */
static int open_children(const bvh_node *nodes, const bvh_slots *s, int k,
                         int width, int kids[8])
{
    int m, n = 0;
    cheapest_share(nodes, s, k, width, &m);
    take_lanes(nodes, s, k + 1, m, kids, &n);
    take_lanes(nodes, s, (int)nodes[k].index, width - m, kids, &n);
    return n;
}

/* How far lane c of n lies along octant o's diagonal (empty: -inf). */
static double along_octant(const bvh_node8 *n, int c, int o)
{
    if (n->face[0][c] > n->face[1][c])
        return -INFINITY; /* an unused lane */
    double far = 0;
    for (int a = 0; a < 3; a++) {
        double centre = (double)n->face[2 * a][c] + n->face[2 * a + 1][c];
        far += (o >> a & 1) ? -centre : centre;
    }
    return far;
}

/* <<the octant orders of a node>> ch11 */
/* n's order for each octant: the lanes farthest first (insertion sort,
 * equal ones in the order of their lanes). */
static void order_children(bvh_node8 *n)
{
    for (int k = 0; k < 8; k++)
        n->order[k] = 0;
    for (int o = 0; o < 8; o++) {
        int lane[8];
        for (int k = 0; k < 8; k++) {
            int j = k;
            for (; j > 0 && along_octant(n, lane[j - 1], o) <
                                along_octant(n, k, o); j--)
                lane[j] = lane[j - 1];
            lane[j] = k;
        }
        for (int k = 0; k < 8; k++)
            n->order[k] |= (uint32_t)lane[k] << 3 * o;
    }
}

/* Moves the children of kids[0..n) that are nodes (count 0) before the
 * leaves, each kind in its order; returns how many are nodes. */
static int nodes_first(const bvh_node *nodes, int kids[8], int n)
{
    int sorted[8], m = 0;
    for (int c = 0; c < n; c++)
        if (nodes[kids[c]].count == 0)
            sorted[m++] = kids[c];
    int interior = m;
    for (int c = 0; c < n; c++)
        if (nodes[kids[c]].count != 0)
            sorted[m++] = kids[c];
    memcpy(kids, sorted, (size_t)n * sizeof *kids);
    return interior;
}

/* Fills wide node w with the children of binary node k, and the wide
 * nodes below it from t->node_count on: its children that are nodes
 * first, in numbers that follow one another, then theirs. */
static void collapse(bvh *t, const bvh_node *nodes, const bvh_slots *s,
                     int k, int w)
{
    int kids[8], n = 1;
    kids[0] = k; /* a root that is a leaf: one child */
    if (nodes[k].count == 0)
        n = open_children(nodes, s, k, t->width, kids);
    int interior = nodes_first(nodes, kids, n);
    uint32_t first = (uint32_t)t->node_count; /* lane 0's number */
    t->node_count += interior;
    bvh_node8 *node = &t->nodes8[w];
    for (int c = 0; c < 8; c++) {
        for (int a = 0; a < 3; a++) /* no box yet: lo +inf, hi -inf */
            node->face[2 * a][c] = INFINITY, node->face[2 * a + 1][c] =
                                                 -INFINITY;
        node->child[c] = bvh_leaf_word(0, 0); /* unused: an empty leaf */
    }
    for (int c = 0; c < n; c++) {
        const bvh_node *kid = &nodes[kids[c]];
        for (int a = 0; a < 3; a++)
            node->face[2 * a][c] = kid->box[a],
            node->face[2 * a + 1][c] = kid->box[a + 3];
        assert(kid->count < 16);
        node->child[c] = c < interior ? first + (uint32_t)c
                                      : bvh_leaf_word(kid->index, kid->count);
    }
    order_children(node);
    node->order[0] |= (uint32_t)interior << BVH_NODES_SHIFT;
    for (int c = 0; c < interior; c++)
        collapse(t, nodes, s, kids[c], (int)(first + (uint32_t)c));
}

/* t's wide nodes in an array of their number, which the collapse knows
 * only at its end (kept larger when a smaller one cannot be had). */
static void shrink_wide(bvh *t)
{
    size_t size = sizeof(bvh_node8);
    void *fit = memory_alloc_aligned(64, (size_t)t->node_count, size);
    if (fit == NULL)
        return;
    memcpy(fit, t->nodes8, (size_t)t->node_count * size);
    free(t->nodes8);
    t->nodes8 = fit, t->node_capacity = t->node_count;
}

/* t's binary nodes collapsed into nodes of t->width; false: no memory. */
static bool make_wide(bvh *t)
{
    int most = t->node_count - t->leaf_count + 1; /* wide nodes at most */
    bvh_slots *s = memory_alloc_zeroed((size_t)t->node_count, sizeof *s);
    t->nodes8 = memory_alloc_aligned(64, (size_t)most, sizeof(bvh_node8));
    if (s == NULL || t->nodes8 == NULL)
        return free(s), false;
    price_collapse(t->nodes, t->node_count, t->width, s);
    bvh_node *binary = t->nodes;
    t->nodes = NULL, t->node_count = 1, t->node_capacity = most;
    collapse(t, binary, s, 0, 0);
    free(binary), free(s);
    shrink_wide(t);
    t->avx2 = bvh_walks_with_avx2();
    t->avx512 = t->avx2 && bvh_walks_with_avx512();
    return true;
}

/* <<choosing AVX2 when the program runs>> ch11 */
/* Set by bvh_allow_avx2 (the tests); read when a tree is built. */
static atomic_bool avx2_forbidden;

bool bvh_walks_with_avx2(void)
{
#if BVH_HAS_AVX2_PATH
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
           !atomic_load(&avx2_forbidden);
#else
    return false;
#endif
}

void bvh_allow_avx2(bool allowed)
{
    atomic_store(&avx2_forbidden, !allowed);
}

/* Set by bvh_allow_avx512 (the tests). */
static atomic_bool avx512_forbidden;

bool bvh_walks_with_avx512(void)
{
#if BVH_HAS_AVX2_PATH
    return bvh_walks_with_avx2() && __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("popcnt") &&
           !atomic_load(&avx512_forbidden);
#else
    return false;
#endif
}

void bvh_allow_avx512(bool allowed)
{
    atomic_store(&avx512_forbidden, !allowed);
}

uint32_t bvh_set_lanes[256];
int32_t bvh_octant_rows[8][6];

/* Fills bvh_set_lanes before main runs (GCC's and Clang's constructor),
 * so that no walk finds it half made. */
__attribute__((constructor)) static void fill_set_lanes(void)
{
    for (unsigned mask = 0; mask < 256; mask++) {
        uint32_t set = 0, count = 0;
        for (unsigned c = 0; c < 8; c++)
            if (mask >> c & 1)
                set |= c << 3 * count++;
        bvh_set_lanes[mask] = set | count << 24;
    }
    for (unsigned octant = 0; octant < 8; octant++)
        for (int a = 0; a < 3; a++) {
            int down = octant >> a & 1; /* enters by the upper face */
            int32_t row = (int32_t)sizeof(float[8]); /* bytes */
            bvh_octant_rows[octant][2 * a] = (2 * a + down) * row;
            bvh_octant_rows[octant][2 * a + 1] = (2 * a + 1 - down) * row;
        }
}

const char *bvh_vector_width_name(const bvh *t)
{
    if (t->width != 2 && t->avx512)
        return "AVX-512VL chosen at run time";
    if (t->width != 2 && t->avx2)
        return "AVX2 chosen at run time";
#if defined(RT_SCALAR)
    return "scalar";
#elif defined(__AVX__)
    return "AVX";
#elif defined(__SSE2__)
    return "SSE2";
#else
    return "vector extensions";
#endif
}

/* <<starting a bvh build>> ch09 */
/* The builder's own arrays for count items; false: no memory (what was
 * made is freed by builder_free). */
static bool builder_made(bvh_builder *bd, size_t count)
{
    bd->centers = memory_alloc(count, sizeof *bd->centers);
    bool made = bd->centers != NULL;
    return made;
}

static void builder_free(bvh_builder *bd)
{
    free(bd->centers);
}

/* <<building the binary tree>> ch09 */
/* The binary tree of bd's count items in t. */
static void build_binary(bvh_builder *bd, int count, bvh *t)
{
    bd->pad = BVH_THICKNESS * pass_prepare(bd, count);
    build_subtree(bd, t, 0, count, 0);
}

/* t's binary nodes in an array of their number (kept larger when even a
 * smaller one cannot be had). */
static bool shrink_binary(bvh *t)
{
    bvh_node *fit = memory_resize(t->nodes, (size_t)t->node_count,
                                  sizeof *fit);
    t->nodes = fit != NULL ? fit : t->nodes;
    t->node_capacity = fit != NULL ? t->node_count : t->node_capacity;
    return true;
}

bool bvh_build(bvh *t, int count, const box *bounds, const bvh_params *p)
{
    bvh_params q = bvh_filled(p);
    /* <<the widths a build makes>> ch11 */
    assert(q.width == 2 || q.width == 4 || q.width == 8);
    assert(q.bins >= 2 && q.bins <= BVH_MAX_BINS);
    assert(q.max_leaf_items >= 1 && q.max_leaf_items <= 15);
    *t = (bvh){.width = q.width};
    if (count < q.min_items || count < 1)
        return true;
    size_t n = (size_t)count, slots = 2 * n - 1;
    bvh_builder bd = {.bounds = bounds, .p = q};
    t->items = bd.items = memory_alloc(n, sizeof *t->items);
    t->nodes = memory_alloc(slots, sizeof *t->nodes);
    bool ok = builder_made(&bd, n) && t->items && t->nodes;
    t->node_capacity = (int)slots, t->item_count = ok ? count : 0;
    if (ok)
        build_binary(&bd, count, t);
    builder_free(&bd);
    /* <<the tree made of the binary nodes>> ch11 */
    ok = ok && (q.width == 2 ? shrink_binary(t) : make_wide(t));
    if (!ok)
        bvh_free(t);
    return ok;
}
