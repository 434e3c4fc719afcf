/* kdtree.c: building kd-trees (chapter 8). See kdtree.h. */
#include "kdtree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "array.h"
#include "memory.h"

/* <<kd-tree storage>> ch08 */
kdtree_params kdtree_default_params(void)
{
    return (kdtree_params){.method = KDTREE_SAH,
                           .traversal_cost = 80,
                           .intersection_cost = 20,
                           .empty_bonus = 0.2};
}

void kdtree_free(kdtree *t)
{
    free(t->nodes);
    free(t->items);
    *t = (kdtree){0};
}

/* A node's 30 upper bits index its child above, or count its items. */
#define KDTREE_MAX_NODES (1 << 30)

long long kdtree_bytes(const kdtree *t)
{
    return (long long)t->node_capacity * sizeof *t->nodes +
           (long long)t->item_capacity * sizeof *t->items;
}

/* Appends n; its index, or -1 when out of memory. */
static int add_node(kdtree *t, kdtree_node n)
{
    kdtree_node *grown = array_grow(t->nodes, t->node_count,
                                    &t->node_capacity, KDTREE_MAX_NODES,
                                    sizeof n);
    if (grown == NULL)
        return -1;
    t->nodes = grown;
    t->nodes[t->node_count] = n;
    return t->node_count++;
}

/* Appends a leaf of the count items; false when out of memory. */
static bool add_leaf(kdtree *t, const int *items, int count, int depth)
{
    if (count > 0) { /* an empty leaf may come before any storage */
        int *grown = array_reserve(t->items, t->item_count + count,
                                   &t->item_capacity, KDTREE_MAX_NODES,
                                   sizeof *grown);
        if (grown == NULL)
            return false;
        t->items = grown;
        memcpy(t->items + t->item_count, items, (size_t)count * sizeof *items);
    }
    kdtree_node leaf = {.first = (uint32_t)t->item_count,
                        .bits = (uint32_t)count << 2 | 3};
    t->item_count += count;
    t->leaf_count++;
    t->depth = depth > t->depth ? depth : t->depth;
    return add_node(t, leaf) >= 0;
}

/* <<the builder>> ch08 */
/* What every node of one build shares. */
typedef struct {
    kdtree *tree;
    kdtree_params p;
    kdtree_clip clip;
    const void *context;
    unsigned char *side; /* per item: where the current split puts it */
    long long references, budget; /* item references: now, at most */
    int max_depth;
} builder;

enum { SIDE_BELOW = 1, SIDE_ABOVE = 2, SIDE_BOTH = 3 };

/* item cut to the cell: its box in *out; false if it misses the cell. */
static bool clip_item(const builder *b, int item, const box *cell, box *out)
{
    if (!b->clip(b->context, item, cell, out))
        return false;
    *out = box_cut(out, cell); /* rounding must not carry it outside */
    return box_is_valid(out);
}

static int compare_ints(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Sorts the items of a leaf: by insertion, as leaves are short. */
static void sort_items(int *items, int n)
{
    if (n > 64) {
        qsort(items, (size_t)n, sizeof *items, compare_ints);
        return;
    }
    for (int i = 1; i < n; i++) {
        int item = items[i], j = i;
        for (; j > 0 && items[j - 1] > item; j--)
            items[j] = items[j - 1];
        items[j] = item;
    }
}

/* <<events>> ch08 */
/* An event: where an item's box starts or ends along one axis, or where
 * it lies when it is flat in that axis. */
typedef struct {
    double position;
    uint32_t tag; /* the type in the top 2 bits, the item below */
} event;

/* At one position: ends, then flat items, then starts. */
enum { EVENT_END, EVENT_PLANAR, EVENT_START };

#define MAX_ITEMS (1 << 30) /* a tag has 30 bits for the item */

static int event_type(event e) { return (int)(e.tag >> 30); }
static int event_item(event e) { return (int)(e.tag & 0x3fffffff); }

/* By position, then type (then item, so that the order is unique). */
static int compare_events(const void *a, const void *b)
{
    const event *x = a, *y = b;
    if (x->position != y->position)
        return x->position < y->position ? -1 : 1;
    return (x->tag > y->tag) - (x->tag < y->tag);
}

/* Appends the events of the item with box b on the axis to list. */
static int add_events(event *list, int n, const box *b, int axis, int item)
{
    double lo = vec3_axis(b->lo, axis), hi = vec3_axis(b->hi, axis);
    if (lo == hi) {
        list[n++] = (event){lo, (uint32_t)EVENT_PLANAR << 30 | item};
    } else {
        list[n++] = (event){lo, (uint32_t)EVENT_START << 30 | item};
        list[n++] = (event){hi, (uint32_t)EVENT_END << 30 | item};
    }
    return n;
}

/* <<sorting events by radix>> ch08 */
/* The bits of x, flipped so that they order like the numbers: the sign
 * bit of a positive number, every bit of a negative one. -0 is 0. */
static uint64_t position_key(double x)
{
    uint64_t u;
    x = x == 0 ? 0 : x;
    memcpy(&u, &x, sizeof u);
    return u >> 63 ? ~u : u | (uint64_t)1 << 63;
}

/* Byte pass of e's key: pass 0 is the type, 1 to 8 the position's bytes
 * from the least significant. */
static unsigned key_byte(event e, int pass)
{
    if (pass == 0)
        return (unsigned)event_type(e);
    return (unsigned)(position_key(e.position) >> 8 * (pass - 1) & 255);
}

/* Where each byte value starts in the sorted order, for every pass at
 * once: start[pass][byte]. False for a pass whose byte is the same for
 * every event (nothing to sort there). */
static void count_bytes(const event *e, int n, int start[9][257],
                        bool useful[9])
{
    memset(start, 0, 9 * sizeof start[0]);
    for (int i = 0; i < n; i++)
        for (int pass = 0; pass <= 8; pass++)
            start[pass][key_byte(e[i], pass) + 1]++;
    for (int pass = 0; pass <= 8; pass++) {
        useful[pass] = true;
        for (int b = 0; b < 256; b++) {
            useful[pass] = useful[pass] && start[pass][b + 1] < n;
            start[pass][b + 1] += start[pass][b];
        }
    }
}

/* Sorts list by position, then type, keeping the order of equal events;
 * false when out of memory (and then list is as it was). */
static bool radix_sort_events(event *list, int n)
{
    int start[9][257]; /* 9 kB */
    bool useful[9];
    event *spare = memory_alloc((size_t)n, sizeof *spare), *from = list;
    if (spare == NULL)
        return false;
    count_bytes(list, n, start, useful);
    for (int pass = 0; pass <= 8; pass++) {
        if (!useful[pass])
            continue;
        event *to = from == list ? spare : list;
        for (int i = 0; i < n; i++)
            to[start[pass][key_byte(from[i], pass)]++] = from[i];
        from = to;
    }
    if (from != list)
        memcpy(list, from, (size_t)n * sizeof *list);
    free(spare);
    return true;
}

/* Sorts list by position, then type: by insertion when it is short (most
 * are), by qsort up to 255, by radix, one byte of the position at a time,
 * when it is longer. */
static void sort_events(event *list, int n)
{
    if (n >= 256 && radix_sort_events(list, n))
        return;
    if (n > 16) { /* insertion sort takes n^2 / 4 steps */
        qsort(list, (size_t)n, sizeof *list, compare_events);
        return;
    }
    for (int i = 1; i < n; i++) {
        event e = list[i];
        int j = i;
        for (; j > 0 && compare_events(&list[j - 1], &e) > 0; j--)
            list[j] = list[j - 1];
        list[j] = e;
    }
}

typedef struct {
    event *e[3];
    int n[3];
    int count; /* items */
} event_lists;

static void free_events(event_lists *l)
{
    for (int k = 0; k < 3; k++)
        free(l->e[k]), l->e[k] = NULL;
}

/* Room for n events on each axis; false when out of memory. */
static bool alloc_events(event_lists *l, int n)
{
    *l = (event_lists){0};
    for (int k = 0; k < 3; k++)
        l->e[k] = memory_alloc((size_t)n, sizeof(event));
    if (l->e[0] && l->e[1] && l->e[2])
        return true;
    free_events(l);
    return false;
}

/* <<the surface area heuristic>> ch08 */
/* The best plane found so far: axis -1 while there is none. */
typedef struct {
    int axis;
    double position;
    bool flat_below;  /* the items lying in the plane go below */
    int below, above; /* items on each side */
    double cost;      /* times the cell's half area */
} split;

/* The cost of a split whose sides have the half areas a_below and a_above
 * and hold the given items, times the cell's half area a (so that no
 * division is needed: only costs of one cell are compared). */
static double sah(const builder *b, double a, double a_below, double a_above,
                  int below, int above)
{
    double discount = below == 0 || above == 0 ? 1 - b->p.empty_bonus : 1;
    return discount * (b->p.traversal_cost * a +
                       b->p.intersection_cost *
                           (a_below * below + a_above * above));
}

/* What the costs of the planes across one axis of a cell share: the
 * cell's extent on the axis, and its other two sides e1, e2. A box of
 * sides w, e1, e2 has the half area w (e1 + e2) + e1 e2. */
typedef struct {
    int axis;
    double lo, hi, rim, end, half_area; /* rim = e1 + e2, end = e1 e2 */
} axis_costs;

static axis_costs costs_across(const box *cell, int axis)
{
    vec3 e = vec3_sub(cell->hi, cell->lo);
    double e1 = vec3_axis(e, (axis + 1) % 3), e2 = vec3_axis(e, (axis + 2) % 3);
    axis_costs c = {axis, vec3_axis(cell->lo, axis), vec3_axis(cell->hi, axis),
                    e1 + e2, e1 * e2, 0};
    c.half_area = (c.hi - c.lo) * c.rim + c.end;
    return c;
}

/* Keeps the plane x in *best if it costs less. flat items lie in the
 * plane; the cheaper side gets them. */
static inline void consider(const builder *b, const axis_costs *c, double x,
                     int below, int flat, int above, split *best)
{
    if (!(x > c->lo && x < c->hi))
        return; /* a plane on the cell's face cuts nothing off */
    double a_below = (x - c->lo) * c->rim + c->end;
    double a_above = (c->hi - x) * c->rim + c->end;
    double cost = sah(b, c->half_area, a_below, a_above, below + flat, above);
    if (cost < best->cost)
        *best = (split){c->axis, x, true, below + flat, above, cost};
    if (flat == 0)
        return;
    cost = sah(b, c->half_area, a_below, a_above, below, above + flat);
    if (cost < best->cost)
        *best = (split){c->axis, x, false, below, above + flat, cost};
}

/* One sweep along the sorted events of an axis. At each position x, the
 * items that end there leave the count above, the flat ones lie in the
 * plane, and the ones that start there join the count below after it:
 * counted over all the events at x first, then the plane x considered. */
static void sweep(const builder *b, const box *cell, int axis,
                  const event *e, int n, int count, split *best)
{
    int below = 0, above = count, at[3] = {0, 0, 0};
    axis_costs c = costs_across(cell, axis);
    for (int i = 0; i < n; i++) {
        at[event_type(e[i])]++;
        if (i + 1 < n && e[i + 1].position == e[i].position)
            continue; /* more events at this position */
        above -= at[EVENT_PLANAR] + at[EVENT_END];
        consider(b, &c, e[i].position, below, at[EVENT_PLANAR], above, best);
        below += at[EVENT_START] + at[EVENT_PLANAR];
        at[0] = at[1] = at[2] = 0;
    }
}

/* The cheapest plane of the three axes, or axis -1 when a leaf costs
 * less, or when depth or memory say stop. */
static split find_split(builder *b, const event_lists *l, const box *cell,
                        int depth)
{
    double half_area = box_area(cell) / 2;
    split best = {.axis = -1,
                  .cost = b->p.intersection_cost * l->count * half_area};
    if (depth >= b->max_depth || l->count <= 1 || !(half_area > 0))
        return (split){.axis = -1};
    for (int k = 0; k < 3; k++)
        sweep(b, cell, k, l->e[k], l->n[k], l->count, &best);
    long long more = (long long)best.below + best.above - l->count;
    if (best.axis >= 0 && (b->references + more > b->budget ||
                           b->tree->node_count > 2 * b->budget))
        return (split){.axis = -1}; /* out of budget: memory stays bounded */
    return best;
}

/* <<classifying the items>> ch08 */
/* Marks each item of the sorted events e[0..n) on the split's axis with
 * the side (or sides) of the split plane it lies on. An item's start
 * comes before its end, so its end has the last word. */
static void classify(builder *b, const event *e, int n, split s)
{
    for (int i = 0; i < n; i++) {
        double x = e[i].position;
        int item = event_item(e[i]), type = event_type(e[i]);
        if (type == EVENT_START) /* until its end says otherwise: both */
            b->side[item] = x >= s.position ? SIDE_ABOVE : SIDE_BOTH;
        else if (type == EVENT_END && x <= s.position)
            b->side[item] = SIDE_BELOW;
        else if (type == EVENT_PLANAR)
            b->side[item] = x < s.position || (x == s.position &&
                                               s.flat_below)
                                ? SIDE_BELOW
                                : SIDE_ABOVE;
    }
}

/* <<the sweep build>> ch08 */
/* Leaf of the items of l: each item has one start or flat event on x. */
static bool leaf_of_events(builder *b, const event_lists *l, int depth)
{
    int *items = memory_alloc((size_t)l->count, sizeof *items), n = 0;
    if (items == NULL)
        return false;
    for (int i = 0; i < l->n[0]; i++)
        if (event_type(l->e[0][i]) != EVENT_END)
            items[n++] = event_item(l->e[0][i]);
    sort_items(items, n);
    bool ok = add_leaf(b->tree, items, n, depth);
    free(items);
    return ok;
}

/* The items on both sides of the split: the start events on its axis. */
static int *straddlers(const builder *b, const event *e, int n, int *count)
{
    int *items = memory_alloc((size_t)n, sizeof *items);
    *count = 0;
    for (int i = 0; items != NULL && i < n; i++)
        if (event_type(e[i]) == EVENT_START &&
            b->side[event_item(e[i])] == SIDE_BOTH)
            items[(*count)++] = event_item(e[i]);
    return items;
}

/* The events of the items cut to the cell, sorted; out->count of them
 * meet it. */
static bool cut_events(builder *b, const int *items, int n, const box *cell,
                       event_lists *out)
{
    if (!alloc_events(out, 2 * n))
        return false;
    for (int i = 0; i < n; i++) {
        box c;
        if (!clip_item(b, items[i], cell, &c))
            continue; /* a perfect split: it misses this side */
        for (int k = 0; k < 3; k++)
            out->n[k] = add_events(out->e[k], out->n[k], &c, k, items[i]);
        out->count++;
    }
    for (int k = 0; k < 3; k++)
        sort_events(out->e[k], out->n[k]);
    return true;
}

/* Copies to out[*n] the events of cut[*j..] that come before e (all of them
 * when e is NULL); the position of the next one that does not, or
 * infinity: a cheap test of whether to call again. */
static inline double flush_before(const event *e, const event_lists *cut, int k,
                           int *j, event *out, int *n)
{
    while (*j < cut->n[k] &&
           (e == NULL || compare_events(&cut->e[k][*j], e) < 0))
        out[(*n)++] = cut->e[k][(*j)++];
    return *j < cut->n[k] ? cut->e[k][*j].position : INFINITY;
}

/* The events of l's items on one side only go to that side, in order, with
 * the sorted events cut[0] (below) and cut[1] (above) merged in. Each event
 * is stored through a table indexed by its side, so that no branch waits
 * on the sides, which are random: the events of straddling items go to a
 * scratch slot that never advances. */
static void keep_sides(const builder *b, const event_lists *l,
                       const event_lists cut[2], event_lists *below,
                       event_lists *above)
{
    event scratch;
    for (int k = 0; k < 3; k++) {
        event *to[4] = {&scratch, below->e[k], above->e[k], &scratch};
        int n[4] = {0, 0, 0, 0}, items[4] = {0, 0, 0, 0}, jb = 0, ja = 0;
        double next_b = cut[0].n[k] ? cut[0].e[k][0].position : INFINITY;
        double next_a = cut[1].n[k] ? cut[1].e[k][0].position : INFINITY;
        for (int i = 0; i < l->n[k]; i++) {
            event e = l->e[k][i];
            int side = b->side[event_item(e)];
            if (next_b <= e.position)
                next_b = flush_before(&e, &cut[0], k, &jb, to[1], &n[1]);
            if (next_a <= e.position)
                next_a = flush_before(&e, &cut[1], k, &ja, to[2], &n[2]);
            to[side][n[side]] = e;
            n[side] += side != SIDE_BOTH;
            items[side] += event_type(e) != EVENT_END; /* once an item */
        }
        flush_before(NULL, &cut[0], k, &jb, to[1], &n[1]);
        flush_before(NULL, &cut[1], k, &ja, to[2], &n[2]);
        below->n[k] = n[1], above->n[k] = n[2];
        if (k == 0)
            below->count = items[1], above->count = items[2];
    }
    below->count += cut[0].count, above->count += cut[1].count;
}

static bool split_events(builder *b, const event_lists *l, const box *cell,
                         split s, event_lists *below, event_lists *above)
{
    int n;
    int *both = straddlers(b, l->e[s.axis], l->n[s.axis], &n);
    event_lists cut[2];
    memset(cut, 0, sizeof cut);
    bool ok = both != NULL && alloc_events(below, 2 * (l->count + n)) &&
              alloc_events(above, 2 * (l->count + n));
    for (int side = 0; ok && side < 2; side++) {
        box c = box_child(cell, s.axis, s.position, side);
        ok = cut_events(b, both, n, &c, &cut[side]);
    }
    if (ok)
        keep_sides(b, l, cut, below, above);
    else
        free_events(below), free_events(above);
    free(both), free_events(&cut[0]), free_events(&cut[1]);
    return ok;
}

static bool build_sweep(builder *b, event_lists *l, box cell, int depth)
{
    split s = find_split(b, l, &cell, depth);
    event_lists below = {0}, above = {0};
    bool ok;
    if (s.axis < 0) {
        ok = leaf_of_events(b, l, depth);
        free_events(l);
        return ok;
    }
    classify(b, l->e[s.axis], l->n[s.axis], s);
    ok = split_events(b, l, &cell, s, &below, &above);
    free_events(l);
    if (!ok)
        return false;
    b->references += below.count + above.count - l->count;
    int node = add_node(b->tree, (kdtree_node){.split = s.position,
                                               .bits = (uint32_t)s.axis});
    ok = node >= 0 && build_sweep(b, &below, box_child(&cell, s.axis,
                                  s.position, 0), depth + 1);
    if (ok)
        b->tree->nodes[node].bits |= (uint32_t)b->tree->node_count << 2;
    ok = ok && build_sweep(b, &above, box_child(&cell, s.axis, s.position,
                                                1), depth + 1);
    free_events(&below), free_events(&above); /* on failure, what is left */
    return ok;
}

/* <<the item lists of the other builds>> ch08 */
/* The items of a node, each with its box cut to the node's cell. */
typedef struct {
    int *items;
    box *boxes;
    int count;
} item_list;

static void free_items(item_list *l)
{
    free(l->items), free(l->boxes);
    *l = (item_list){0};
}

static bool alloc_items(item_list *l, int n)
{
    l->items = memory_alloc((size_t)n, sizeof *l->items);
    l->boxes = memory_alloc((size_t)n, sizeof *l->boxes);
    l->count = 0;
    if (l->items != NULL && l->boxes != NULL)
        return true;
    free_items(l);
    return false;
}

/* A leaf of l's items, in increasing order as every build makes them. */
static bool leaf_of_items(builder *b, item_list *l, int depth)
{
    sort_items(l->items, l->count);
    bool ok = add_leaf(b->tree, l->items, l->count, depth);
    free_items(l);
    return ok;
}

/* Appends item with its box bx, cut to the cell when it straddles. */
static void add_item(builder *b, item_list *to, int item, const box *bx,
                     const box *cell, bool straddles)
{
    box c = *bx;
    if (straddles && !clip_item(b, item, cell, &c))
        return;
    to->items[to->count] = item;
    to->boxes[to->count++] = c;
}

/* The items of l below and above the plane of s, by b->side. */
static bool split_items(builder *b, const item_list *l, const box *cell,
                        split s, item_list *below, item_list *above)
{
    box under = box_child(cell, s.axis, s.position, 0);
    box over = box_child(cell, s.axis, s.position, 1);
    if (!alloc_items(below, l->count))
        return false;
    if (!alloc_items(above, l->count))
        return free_items(below), false;
    for (int i = 0; i < l->count; i++) {
        int item = l->items[i], side = b->side[item];
        if (side & SIDE_BELOW)
            add_item(b, below, item, &l->boxes[i], &under, side == SIDE_BOTH);
        if (side & SIDE_ABOVE)
            add_item(b, above, item, &l->boxes[i], &over, side == SIDE_BOTH);
    }
    return true;
}

typedef bool (*item_build)(builder *b, item_list *l, box cell, int depth);

/* An interior node at s over cell, with children built by build from l,
 * which it frees. */
static bool split_node(builder *b, item_list *l, box cell, int depth,
                       split s, item_build build)
{
    item_list below, above;
    bool ok = split_items(b, l, &cell, s, &below, &above);
    b->references += ok ? below.count + above.count - l->count : 0;
    free_items(l);
    if (!ok)
        return false;
    int node = add_node(b->tree, (kdtree_node){.split = s.position,
                                               .bits = (uint32_t)s.axis});
    ok = node >= 0 && build(b, &below, box_child(&cell, s.axis, s.position,
                                                  0), depth + 1);
    if (ok)
        b->tree->nodes[node].bits |= (uint32_t)b->tree->node_count << 2;
    ok = ok && build(b, &above, box_child(&cell, s.axis, s.position, 1),
                     depth + 1);
    free_items(&below), free_items(&above);
    return ok;
}

/* <<the sorting build>> ch08 */
/* The node's events, made from its boxes and sorted: per node, this sort
 * is what makes the build O(N log^2 N). */
static bool events_of_items(const item_list *l, event_lists *ev)
{
    if (!alloc_events(ev, 2 * l->count))
        return false;
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < l->count; i++)
            ev->n[k] = add_events(ev->e[k], ev->n[k], &l->boxes[i], k,
                                  l->items[i]);
        sort_events(ev->e[k], ev->n[k]);
    }
    ev->count = l->count;
    return true;
}

static bool build_sorting(builder *b, item_list *l, box cell, int depth)
{
    event_lists ev;
    if (!events_of_items(l, &ev))
        return free_items(l), false;
    split s = find_split(b, &ev, &cell, depth);
    if (s.axis >= 0)
        classify(b, ev.e[s.axis], ev.n[s.axis], s);
    free_events(&ev);
    if (s.axis < 0)
        return leaf_of_items(b, l, depth);
    return split_node(b, l, cell, depth, s, build_sorting);
}

/* <<the median build>> ch08 */
/* The middle of the cell's longest axis, kept only if the surface area
 * heuristic says that it pays; axis -1: the node is a leaf. */
static split median_split(builder *b, const item_list *l, const box *cell,
                          int depth)
{
    vec3 e = vec3_sub(cell->hi, cell->lo);
    int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    axis_costs c = costs_across(cell, axis);
    split s = {.axis = -1,
               .cost = b->p.intersection_cost * l->count * c.half_area};
    double x = 0.5 * (c.lo + c.hi);
    if (depth >= b->max_depth || l->count <= 1 || !(c.half_area > 0))
        return (split){.axis = -1};
    int below = 0, above = 0;
    for (int i = 0; i < l->count; i++) {
        below += vec3_axis(l->boxes[i].lo, axis) < x ||
                 vec3_axis(l->boxes[i].hi, axis) <= x;
        above += vec3_axis(l->boxes[i].hi, axis) > x;
    }
    consider(b, &c, x, below, 0, above, &s);
    long long more = (long long)s.below + s.above - l->count;
    if (s.axis >= 0 && (b->references + more > b->budget ||
                        b->tree->node_count > 2 * b->budget))
        s.axis = -1; /* out of budget: memory stays bounded */
    return s;
}

/* Marks each item of l with its side (or sides) of the plane of s. */
static void classify_boxes(builder *b, const item_list *l, split s)
{
    for (int i = 0; i < l->count; i++) {
        double lo = vec3_axis(l->boxes[i].lo, s.axis);
        double hi = vec3_axis(l->boxes[i].hi, s.axis);
        int side = hi < s.position || (hi == s.position && lo < hi)
                       ? SIDE_BELOW
                   : lo > s.position || (lo == s.position && lo < hi)
                       ? SIDE_ABOVE
                   : lo == hi ? SIDE_BELOW /* flat, in the plane */
                              : SIDE_BOTH;
        b->side[l->items[i]] = (unsigned char)side;
    }
}

static bool build_median(builder *b, item_list *l, box cell, int depth)
{
    split s = median_split(b, l, &cell, depth);
    if (s.axis < 0)
        return leaf_of_items(b, l, depth);
    classify_boxes(b, l, s);
    return split_node(b, l, cell, depth, s, build_median);
}

/* <<starting a build>> ch08 */
/* The root cell: the union of the items' boxes (empty boxes, of items
 * that are never hit, left out); false when there is none. */
static bool root_cell(const box *bounds, int count, box *root)
{
    *root = (box){{INFINITY, INFINITY, INFINITY},
                  {-INFINITY, -INFINITY, -INFINITY}};
    for (int i = 0; i < count; i++)
        if (box_is_valid(&bounds[i]))
            *root = (box){vec3_min(root->lo, bounds[i].lo),
                          vec3_max(root->hi, bounds[i].hi)};
    return box_is_valid(root);
}

/* The plane thickness for the walk: see KDTREE_THICKNESS. */
static double thickness_of(const box *root)
{
    vec3 far = vec3_max(vec3_scale(root->lo, -1), root->hi);
    double largest = fmax(far.x, fmax(far.y, far.z));
    vec3 e = vec3_sub(root->hi, root->lo);
    largest = fmax(largest, fmax(e.x, fmax(e.y, e.z)));
    return KDTREE_THICKNESS * largest;
}

/* The sweep build's first events: every item's, sorted once. */
static bool start_sweep(builder *b, const box *bounds, int count,
                        const box *root)
{
    event_lists l;
    if (!alloc_events(&l, 2 * count))
        return false;
    for (int i = 0; i < count; i++) {
        if (!box_is_valid(&bounds[i]))
            continue;
        for (int k = 0; k < 3; k++)
            l.n[k] = add_events(l.e[k], l.n[k], &bounds[i], k, i);
        l.count++;
    }
    for (int k = 0; k < 3; k++)
        sort_events(l.e[k], l.n[k]);
    b->references = l.count;
    return build_sweep(b, &l, *root, 0);
}

/* The other builds' first item list. */
static bool start_items(builder *b, const box *bounds, int count,
                        const box *root, item_build build)
{
    item_list l;
    if (!alloc_items(&l, count))
        return false;
    for (int i = 0; i < count; i++)
        if (box_is_valid(&bounds[i])) {
            l.items[l.count] = i;
            l.boxes[l.count++] = bounds[i];
        }
    b->references = l.count;
    return build(b, &l, *root, 0);
}

bool kdtree_build(kdtree *t, int count, const box *bounds, kdtree_clip clip,
                  const void *context, const kdtree_params *p)
{
    kdtree_free(t);
    builder b = {.tree = t, .p = *p, .clip = clip, .context = context};
    box root;
    if (p->method == KDTREE_NONE || count < p->min_items ||
        count >= MAX_ITEMS || !root_cell(bounds, count, &root))
        return true; /* no tree: the items are searched one by one */
    int depth = (int)(8 + 1.3 * log2(count)); /* Havran's rule, pbrt's */
    b.max_depth = p->max_depth > 0 ? p->max_depth : depth;
    b.max_depth = b.max_depth < KDTREE_MAX_DEPTH ? b.max_depth
                                                 : KDTREE_MAX_DEPTH;
    b.budget = KDTREE_REFERENCES_PER_ITEM * (long long)count + 64;
    b.side = memory_alloc((size_t)count, 1);
    t->bounds = root;
    t->thickness = thickness_of(&root);
    bool ok = b.side != NULL &&
              (p->method == KDTREE_SAH
                   ? start_sweep(&b, bounds, count, &root)
                   : start_items(&b, bounds, count, &root,
                                 p->method == KDTREE_MEDIAN ? build_median
                                                            : build_sorting));
    free(b.side);
    if (!ok)
        kdtree_free(t);
    return ok;
}
