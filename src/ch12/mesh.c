/* mesh.c: meshes, their normals, and ray-mesh intersection (chapter 4),
 * through a tree of the mesh from chapter 8 on. */
#include "mesh.h"

#include <stdlib.h>
#include <string.h>
#include "memory.h"
/* <<mesh.c includes>> ch06 */
#include "offset.h"
/* <<mesh.c includes>> += ch10 */
#include <float.h>
/* <<mesh.c includes>> += ch12 */
#include "pool.h"

/* <<mesh storage>> ch04 */
void mesh_free(mesh *m)
{
    free(m->vertices);
    free(m->normals);
    free(m->triangles);
    free(m->triangle_normals);
    free(m->source.path);
    /* <<free mesh members>> ch08 */
    mesh_free_tree(m);
    *m = (mesh){0};
}

long long mesh_bytes(const mesh *m)
{
    long long points = (long long)m->vertex_capacity + m->normal_capacity;
    long long corners =
        (long long)m->triangle_capacity + m->triangle_normals_capacity;
    return points * (long long)sizeof(vec3) +
           corners * (long long)sizeof(mesh_triangle);
}

bool mesh_source_equal(const mesh_source *a, const mesh_source *b)
{
    return a->scale == b->scale && a->offset.x == b->offset.x &&
           a->offset.y == b->offset.y && a->offset.z == b->offset.z &&
           a->smooth == b->smooth && a->path != NULL && b->path != NULL &&
           strcmp(a->path, b->path) == 0;
}

void mesh_compute_bounds(mesh *m)
{
    vec3 lo = {INFINITY, INFINITY, INFINITY};
    vec3 hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = m->vertices[k];
        lo = (vec3){fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z)};
        hi = (vec3){fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z)};
    }
    m->bounds = (box){lo, hi};
}

/* <<the mesh index>> ch04 */
/* FNV-1a over n bytes, continuing from h. */
static unsigned long long fnv1a(unsigned long long h, const void *bytes,
                                size_t n)
{
    const unsigned char *b = bytes;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 1099511628211ULL;
    return h;
}

/* Where the index starts looking for source. */
static size_t first_slot(const mesh_source *source, int size)
{
    const mesh_source *c = source; /* + 0.0: -0.0 hashes as 0.0, its equal */
    double numbers[4] = {c->scale + 0.0, c->offset.x + 0.0,
                         c->offset.y + 0.0, c->offset.z + 0.0};
    unsigned long long h = fnv1a(14695981039346656037ULL, c->path,
                                 strlen(c->path));
    h = fnv1a(h, numbers, sizeof numbers);
    h = fnv1a(h, &c->smooth, sizeof c->smooth);
    return (size_t)(h & (unsigned long long)(size - 1));
}

static size_t next_slot(const mesh_index *x, size_t slot)
{
    return (slot + 1) & (size_t)(x->size - 1);
}

void mesh_index_add(mesh_index *x, const mesh *meshes, int k)
{
    if (meshes[k].source.path == NULL)
        return; /* made in code: no source to find it by */
    size_t slot = first_slot(&meshes[k].source, x->size);
    while (x->slots[slot] != 0)
        slot = next_slot(x, slot);
    x->slots[slot] = k + 1;
}

bool mesh_index_reserve(mesh_index *x, const mesh *meshes, int count)
{
    if (2 * (count + 1) < x->size)
        return true;
    int size = x->size ? 2 * x->size : 64;
    int *slots = memory_alloc_zeroed((size_t)size, sizeof *slots);
    if (slots == NULL)
        return false;
    free(x->slots);
    x->slots = slots, x->size = size;
    for (int k = 0; k < count; k++)
        mesh_index_add(x, meshes, k);
    return true;
}

int mesh_index_find(const mesh_index *x, const mesh *meshes,
                    const mesh_source *source)
{
    if (x->size == 0 || source->path == NULL)
        return -1;
    size_t slot = first_slot(source, x->size);
    for (; x->slots[slot] != 0; slot = next_slot(x, slot)) {
        int k = x->slots[slot] - 1;
        if (mesh_source_equal(&meshes[k].source, source))
            return k;
    }
    return -1;
}

void mesh_index_free(mesh_index *x)
{
    free(x->slots);
    *x = (mesh_index){0};
}

/* <<smooth normals>> ch04 */
/* (b - a) x (c - a): the sheet's n, twice the area long. */
static vec3 face_normal(vec3 a, vec3 b, vec3 c)
{
    return vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
}

static vec3 triangle_normal(const mesh *m, const mesh_triangle *tri)
{
    const vec3 *p = m->vertices;
    return face_normal(p[tri->v[0]], p[tri->v[1]], p[tri->v[2]]);
}

bool mesh_smooth_normals(mesh *m)
{
    size_t count = (size_t)m->vertex_count + 1,
           faces = (size_t)m->triangle_count;
    vec3 *normals = memory_alloc_zeroed(count, sizeof *normals);
    mesh_triangle *corners = memory_alloc(faces, sizeof *corners);
    if (normals == NULL || corners == NULL) {
        free(normals), free(corners);
        return false;
    }
    for (int k = 0; k < m->triangle_count; k++) {
        const int *v = m->triangles[k].v;
        vec3 n = triangle_normal(m, &m->triangles[k]);
        for (int i = 0; i < 3; i++)
            normals[v[i]] = vec3_add(normals[v[i]], n);
        corners[k] = m->triangles[k]; /* vertex i uses normal i */
    }
    free(m->normals), free(m->triangle_normals);
    m->normals = normals;
    m->normal_count = m->normal_capacity = m->vertex_count;
    m->triangle_normals = corners;
    m->triangle_normals_capacity = m->triangle_count;
    return true;
}

/* <<intersecting a mesh>> ch04 */
/* n normalised, or the zero vector when it has no usable length. */
static vec3 unit_or_zero(vec3 n)
{
    double length = vec3_length(n);
    return length > 0 && isfinite(length) ? vec3_scale(n, 1 / length)
                                          : (vec3){0, 0, 0};
}

static bool is_zero(vec3 n) { return n.x == 0 && n.y == 0 && n.z == 0; }

static vec3 blended_normal(const mesh *m, int k, const double b[3])
{
    if (m->triangle_normals == NULL)
        return (vec3){0, 0, 0};
    const int *n = m->triangle_normals[k].v;
    if (n[0] < 0 || n[1] < 0 || n[2] < 0)
        return (vec3){0, 0, 0};
    vec3 sum = {0, 0, 0};
    for (int i = 0; i < 3; i++)
        sum = vec3_add(sum, vec3_scale(m->normals[n[i]], b[i]));
    return unit_or_zero(sum);
}

/* Point, normals and side for a hit with geometric normal n_g and shading
 * normal n (either may be zero: unusable). */
static void fill_triangle_hit(vec3 n_g, vec3 n, ray r, double t, hit *h)
{
    h->t = t;
    h->point = ray_at(r, t);
    if (is_zero(n_g))
        n_g = vec3_scale(r.dir, -1); /* too small for a normal: face the ray */
    h->geometric_normal = n_g;
    h->normal = is_zero(n) ? n_g : n;
    h->inside = vec3_dot(r.dir, n_g) > 0;
}

void triangle_fill_hit(vec3 a, vec3 b, vec3 c, ray r, double t, hit *h)
{
    fill_triangle_hit(unit_or_zero(face_normal(a, b, c)), (vec3){0, 0, 0},
                      r, t, h);
}

void mesh_fill_hit(const mesh *m, int k, ray r, const triangle_hit *th,
                   hit *h)
{
    vec3 n_g = unit_or_zero(triangle_normal(m, &m->triangles[k]));
    fill_triangle_hit(n_g, blended_normal(m, k, th->b), r, th->t, h);
}

mesh_ray mesh_ray_of(ray r)
{
    return (mesh_ray){r, ray_inverse_dir(r)};
}

int mesh_nearest(const mesh *m, const mesh_ray *mr, double t_min,
                 double t_max, triangle_hit *out, render_stats *stats)
{
    /* <<a search that tests the mesh's box itself>> ch11 */
    if (m->bvh_walk != 0) /* set only for a tree built */
        return mesh_search_bvh(m, mr, t_min, t_max, out, stats);
    stats->box_tests++;
    double near = t_min, far = t_max;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return -1; /* missing the box, the ray misses every triangle */
    /* <<search the mesh's tree>> ch08 */
    if (m->tree.node_count > 0)
        return mesh_search_tree(m, mr, near, far, t_min, t_max, out, stats);
    /* <<search the mesh's tree>> += ch09 */
    if (m->bvh.node_count > 0)
        return mesh_search_bvh(m, mr, t_min, t_max, out, stats);
    stats->triangle_tests += m->triangle_count;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    return triangle_nearest_watertight(&shear, m->vertices, m->triangles,
                                       m->triangle_count, t_min, t_max, out);
}

bool mesh_intersect(const mesh *m, ray r, double t_min, double t_max, hit *h,
                    long long *tests)
{
    mesh_ray mr = mesh_ray_of(r);
    render_stats stats = {0};
    triangle_hit th;
    int k = mesh_nearest(m, &mr, t_min, t_max, &th, &stats);
    *tests += stats.triangle_tests;
    if (k < 0)
        return false;
    mesh_fill_hit(m, k, r, &th, h);
    return true;
}
/* <<intersecting a mesh>> += ch08 */

/* Narrows *t_max and *found, the nearest hit so far and its triangle (-1:
 * none), by node's subtree, the ray in [t0, t1] inside its cell (w: its
 * shear). */
static void nearest_in(const mesh *m, const mesh_ray *mr,
                       const watertight_ray *w, int node, double t0,
                       double t1, double t_min, double *t_max, int *found,
                       triangle_hit *out, render_stats *stats)
{
    const kdtree_node *n = &m->tree.nodes[node];
    int axis = (int)(n->bits & 3);
    stats->kd_nodes++;
    if (axis == 3) {
        int first = (int)n->first, count = (int)(n->bits >> 2);
        stats->triangle_tests += count;
        int k = triangle_nearest_of_leaf(w, m->leaf_corners + first,
                                         m->tree.items + first, count, t_min,
                                         *t_max, *found, out);
        if (k >= 0)
            *t_max = out->t, *found = m->tree.items[first + k];
        return;
    }
    kdtree_todo next[2];
    double o = vec3_axis(mr->r.origin, axis), thick = m->tree.thickness;
    kdtree_children(n, node, o - thick, o + thick,
                    vec3_axis(mr->inv_dir, axis), t0, t1, next);
    for (int c = 0; c < 2 && next[c].node >= 0; c++) {
        if (next[c].t_min > *t_max * (1 + KDTREE_SLACK))
            break; /* a hit nearer than this cell is already found */
        nearest_in(m, mr, w, next[c].node, next[c].t_min, next[c].t_max,
                   t_min, t_max, found, out, stats);
    }
}

int mesh_nearest_recursive(const mesh *m, const mesh_ray *mr, double t_min,
                           double t_max, triangle_hit *out,
                           render_stats *stats)
{
    double near = t_min, far = t_max;
    if (m->tree.node_count == 0 ||
        !box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return mesh_nearest(m, mr, t_min, t_max, out, stats);
    int found = -1;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    nearest_in(m, mr, &shear, 0, near, far, t_min, &t_max, &found, out,
               stats);
    return found;
}

/* <<clipping a polygon>> ch08 */
/* The polygon poly[0..n) cut to the side of the plane coordinate axis =
 * at where sign * (coordinate - at) >= 0: one corner more at most. */
static int clip_polygon(const vec3 *poly, int n, int axis, double at,
                        double sign, vec3 *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        vec3 p = poly[i], q = poly[(i + 1) % n];
        double dp = sign * (vec3_axis(p, axis) - at);
        double dq = sign * (vec3_axis(q, axis) - at);
        if (dp >= 0)
            out[m++] = p;
        if ((dp >= 0) != (dq >= 0)) { /* the edge crosses the plane */
            vec3 x = vec3_lerp(p, q, dp / (dp - dq));
            vec3_set_axis(&x, axis, at); /* on the plane, exactly */
            out[m++] = x;
        }
    }
    return m;
}

/* The bounding box of the part of triangle item of the mesh context that
 * lies in the cell: the triangle cut by the cell's six planes. */
static bool clip_triangle(const void *context, int item, const box *cell,
                          box *out)
{
    const mesh *m = context;
    const int *v = m->triangles[item].v;
    vec3 corners[2][10] = {{m->vertices[v[0]], m->vertices[v[1]],
                            m->vertices[v[2]]}};
    vec3 *poly = corners[0], *spare = corners[1], *swap;
    box b = {vec3_min(poly[0], vec3_min(poly[1], poly[2])),
             vec3_max(poly[0], vec3_max(poly[1], poly[2]))};
    int n = 3;
    for (int k = 0; k < 3 && n > 0; k++) {
        double lo = vec3_axis(cell->lo, k), hi = vec3_axis(cell->hi, k);
        if (vec3_axis(b.lo, k) < lo) /* only the planes that cut it */
            n = clip_polygon(poly, n, k, lo, 1, spare),
            swap = poly, poly = spare, spare = swap;
        if (vec3_axis(b.hi, k) > hi)
            n = clip_polygon(poly, n, k, hi, -1, spare),
            swap = poly, poly = spare, spare = swap;
    }
    if (n == 0)
        return false;
    *out = (box){poly[0], poly[0]};
    for (int i = 1; i < n; i++)
        *out = (box){vec3_min(out->lo, poly[i]), vec3_max(out->hi, poly[i])};
    return true;
}

/* The triangles' corners in the order of the tree's leaves. */
static bool copy_leaf_corners(mesh *m)
{
    int n = m->tree.item_count;
    m->leaf_corners = memory_alloc((size_t)n, sizeof *m->leaf_corners);
    if (m->leaf_corners == NULL)
        return false;
    for (int i = 0; i < n; i++) {
        const int *v = m->triangles[m->tree.items[i]].v;
        for (int c = 0; c < 3; c++)
            m->leaf_corners[i].p[c] = m->vertices[v[c]];
    }
    return true;
}

void mesh_free_tree(mesh *m)
{
    kdtree_free(&m->tree);
    free(m->leaf_corners);
    m->leaf_corners = NULL;
    /* <<free the mesh's other trees>> ch09 */
    bvh_free(&m->bvh);
    /* <<free the mesh's other trees>> += ch10 */
    free(m->bvh_packets);
    m->bvh_packets = NULL, m->bvh_packet_count = 0, m->bvh_in_float = false;
    m->bvh_corners_in_float = false;
    /* <<free the mesh's other trees>> += ch11 */
    m->bvh_walk = 0;
}

long long mesh_tree_bytes(const mesh *m)
{
    long long corners = m->leaf_corners ? m->tree.item_count : 0;
    long long bytes = kdtree_bytes(&m->tree) +
                      corners * (long long)sizeof *m->leaf_corners;
    /* <<the bytes of the mesh's other trees>> ch09 */
    if (m->bvh.node_count > 0)
        bytes += bvh_bytes(&m->bvh);
    /* <<the bytes of the mesh's other trees>> += ch10 */
    if (m->bvh_packets != NULL)
        bytes += m->bvh_packet_count * (long long)sizeof *m->bvh_packets;
    return bytes;
}

bool mesh_build_tree(mesh *m, const kdtree_params *p)
{
    mesh_free_tree(m);
    kdtree_params q = *p;
    q.min_items = q.min_items > 0 ? q.min_items : MESH_TREE_MIN_TRIANGLES;
    box *bounds = memory_alloc((size_t)m->triangle_count, sizeof *bounds);
    bool ok = bounds != NULL;
    for (int k = 0; ok && k < m->triangle_count; k++) {
        const int *v = m->triangles[k].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]];
        vec3 c = m->vertices[v[2]];
        bounds[k] = (box){vec3_min(a, vec3_min(b, c)),
                          vec3_max(a, vec3_max(b, c))};
    }
    ok = ok && kdtree_build(&m->tree, m->triangle_count, bounds, clip_triangle,
                            m, &q);
    free(bounds);
    if (ok && m->tree.node_count > 0 && !copy_leaf_corners(m))
        ok = false, kdtree_free(&m->tree);
    return ok;
}

int mesh_search_tree(const mesh *m, const mesh_ray *mr, double near,
                     double far, double t_min, double t_max,
                     triangle_hit *out, render_stats *stats)
{
    kdtree_walk w;
    kdtree_leaf leaf;
    int found = -1;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    kdtree_walk_start(&w, &m->tree, mr->r.origin, mr->inv_dir, near, far);
    while (kdtree_walk_next(&w, t_max, &leaf)) {
        const triangle_corners *corners = m->leaf_corners + leaf.first;
        stats->triangle_tests += leaf.count;
        int k = out == NULL ? (triangle_any_corners(&shear, corners,
                                                    leaf.count, t_min, t_max)
                                   ? 0 : -1)
                            : triangle_nearest_of_leaf(
                                  &shear, corners,
                                  m->tree.items + leaf.first, leaf.count,
                                  t_min, t_max, found, out);
        if (k >= 0)
            found = m->tree.items[leaf.first + k], t_max = out ? out->t : t_max;
        if (k >= 0 && out == NULL)
            break; /* any hit blocks a shadow ray */
    }
    stats->kd_nodes += w.visited;
    return found;
}

bool mesh_occluded(const mesh *m, const mesh_ray *mr, double t_min,
                   double t_max, render_stats *stats)
{
    /* <<a shadow ray's search that tests the box itself>> ch11 */
    if (m->bvh_walk != 0)
        return mesh_search_bvh(m, mr, t_min, t_max, NULL, stats) >= 0;
    double near = t_min, far = t_max;
    stats->box_tests++;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return false;
    if (m->tree.node_count > 0)
        return mesh_search_tree(m, mr, near, far, t_min, t_max, NULL,
                                stats) >= 0;
    /* <<a shadow ray through the mesh's other trees>> ch09 */
    if (m->bvh.node_count > 0)
        return mesh_search_bvh(m, mr, t_min, t_max, NULL, stats) >= 0;
    triangle_hit unused;
    stats->triangle_tests += m->triangle_count;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    return triangle_nearest_watertight(&shear, m->vertices, m->triangles,
                                       m->triangle_count, t_min, t_max,
                                       &unused) >= 0;
}
/* <<intersecting a mesh>> += ch09 */

/* In the order of mesh_accelerator, from MESH_ACCELERATOR_KDTREE. */
static const char *const accelerator_names[] = {
    "kdtree", "bvh",
    /* <<more accelerator names>> ch10 */
    "bvh-float",
};

const char *mesh_accelerator_name(mesh_accelerator a)
{
    return a == MESH_ACCELERATOR_DEFAULT ? "default"
                                         : accelerator_names[a - 1];
}

/* The bounding boxes of m's triangles [first, end), into bounds. */
static void triangle_boxes(const mesh *m, box *bounds, int first, int end)
{
    for (int k = first; k < end; k++) {
        const int *v = m->triangles[k].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]];
        vec3 c = m->vertices[v[2]];
        bounds[k] = (box){vec3_min(a, vec3_min(b, c)),
                          vec3_max(a, vec3_max(b, c))};
    }
}

/* <<what a mesh's BVH is made with>> ch10 */
/* <<the leaves of a node's references>> ch11 */
/* The references of a node of t that may be leaves: a binary node is
 * one itself, a wide node holds eight. */
static int leaf_refs(const bvh *t)
{
    return t->width == 2 ? 1 : 8;
}

/* The leaf of reference c of node k of t: its item count (0: none)
 * and, in *first, its first item (or packet). */
static uint32_t leaf_of(const bvh *t, int k, int c, uint32_t *first)
{
    if (t->width == 2)
        return *first = t->nodes[k].index, t->nodes[k].count;
    uint32_t word = t->nodes8[k].child[c];
    *first = word & BVH_FIRST_MASK;
    return word & BVH_LEAF ? word >> BVH_COUNT_SHIFT & 15 : 0;
}

/* Points that leaf, of count items, at its first packet. */
static void leaf_packed(bvh *t, int k, int c, uint32_t count,
                        uint32_t packet)
{
    if (t->width == 2)
        t->nodes[k].index = packet;
    else
        t->nodes8[k].child[c] = bvh_leaf_word(packet, count);
}

/* Packs each leaf of m's BVH in nodes [from, to) into packets of its
 * own from packets[next] on, leaf after leaf, and points the leaf at its
 * first packet (packets NULL: only counts); the packet after the last. */
static int pack_leaves(mesh *m, triangle_packet *packets, int from, int to,
                       int next)
{
    bvh *t = &m->bvh;
    int refs = leaf_refs(t);
    for (int k = from; k < to; k++)
        for (int c = 0; c < refs; c++) {
            uint32_t first, count = leaf_of(t, k, c, &first);
            if (count == 0)
                continue;
            if (packets != NULL)
                triangle_packets_fill(packets + next, m->vertices,
                                      m->triangles, t->items + first,
                                      (int)count),
                    leaf_packed(t, k, c, count, (uint32_t)next);
            next += triangle_packets_needed((int)count);
        }
    return next;
}

/* Is every coordinate of m's corners a float, the same number rounded? */
static bool corners_in_float(const mesh *m)
{
    for (int k = 0; k < m->vertex_count; k++)
        for (int axis = 0; axis < 3; axis++) {
            double x = vec3_axis(m->vertices[k], axis);
            if ((double)(float)x != x)
                return false;
        }
    return true;
}

/* <<making a mesh's packets>> ch12 */
/* The work around a mesh's build, in pieces for the pool: pieces of its
 * triangles for their boxes, then of the tree's nodes for their
 * packets. */
typedef struct {
    mesh *m;
    box *bounds;
    triangle_packet *packets;
    int pieces;
    int first[MESH_BVH_PIECES + 1]; /* the first packet of each piece */
} mesh_pieces;

/* Where piece k of n of count things begins. */
static int piece_start(int count, int k, int n)
{
    return (int)((long long)count * k / n);
}

/* The pieces of m's count triangles or nodes. */
static int pieces_of(int count)
{
    int pieces = 1 + count / BVH_SHARED_ITEMS;
    return pieces < MESH_BVH_PIECES ? pieces : MESH_BVH_PIECES;
}

static void box_piece(void *pieces, int piece)
{
    mesh_pieces *w = pieces;
    int count = w->m->triangle_count;
    triangle_boxes(w->m, w->bounds, piece_start(count, piece, w->pieces),
                   piece_start(count, piece + 1, w->pieces));
}

/* The boxes of m's triangles, into bounds, on threads threads. */
static void triangles_boxed(mesh *m, box *bounds, int threads)
{
    mesh_pieces w = {.m = m, .bounds = bounds,
                     .pieces = pieces_of(m->triangle_count)};
    pool_for(w.pieces, threads, box_piece, &w);
}

static void pack_piece(void *pieces, int piece)
{
    mesh_pieces *w = pieces;
    int nodes = w->m->bvh.node_count;
    pack_leaves(w->m, w->packets, piece_start(nodes, piece, w->pieces),
                piece_start(nodes, piece + 1, w->pieces), w->first[piece]);
}

/* m's BVH's packets, piece by piece on the build's threads, each piece's
 * first packet counted beforehand; false: no memory. */
static bool make_packets(mesh *m)
{
    int nodes = m->bvh.node_count;
    mesh_pieces w = {.m = m, .pieces = pieces_of(m->triangle_count)};
    for (int k = 0; k < w.pieces; k++)
        w.first[k + 1] =
            pack_leaves(m, NULL, piece_start(nodes, k, w.pieces),
                        piece_start(nodes, k + 1, w.pieces), w.first[k]);
    w.packets = memory_alloc_aligned(_Alignof(triangle_packet),
                                     (size_t)w.first[w.pieces],
                                     sizeof(triangle_packet));
    if (w.packets == NULL)
        return false;
    pool_for(w.pieces, m->bvh.build_threads, pack_piece, &w);
    m->bvh_packets = w.packets;
    m->bvh_packet_count = w.first[w.pieces];
    m->bvh_corners_in_float = corners_in_float(m);
    return true;
}

bool mesh_build_bvh(mesh *m, const bvh_params *p)
{
    mesh_free_tree(m);
    bvh_params q = *p;
    q.min_items = q.min_items > 0 ? q.min_items : MESH_TREE_MIN_TRIANGLES;
    /* <<a mesh's own bvh parameters>> ch10 */
    q.item_group = q.item_group > 0 ? q.item_group : PACKET_W;
    /* <<a mesh's own bvh parameters>> += ch11 */
    /* a wide node tests eight boxes at once: a box at half a packet */
    int width = q.width > 0 ? q.width : bvh_default_params().width;
    if (width > 2 && q.traversal_cost == 0) /* 0: the mesh's default */
        q.traversal_cost = 0.5;
    box *bounds = memory_alloc((size_t)m->triangle_count, sizeof *bounds);
    if (bounds != NULL)
        /* <<the boxes of a mesh's triangles>> ch12 */
        triangles_boxed(m, bounds, q.threads);
    bool ok = bounds != NULL &&
              bvh_build(&m->bvh, m->triangle_count, bounds, &q);
    free(bounds);
    if (!ok || m->bvh.node_count == 0)
        return ok;
    /* <<the leaves of a mesh's BVH made>> ch10 */
    if (!make_packets(m))
        return bvh_free(&m->bvh), false;
    /* <<the leaves of a mesh's BVH made>> += ch11 */
    m->bvh_walk = m->bvh.width == 2 ? 0 : m->bvh.avx512 ? 6 : m->bvh.avx2 ? 4 : 2;
    return true;
}

/* Every triangle of m, for a ray the float tests cannot take. */
static int mesh_search_all(const mesh *m, const mesh_ray *mr, double t_min,
                           double t_max, triangle_hit *out,
                           render_stats *stats)
{
    triangle_hit unused;
    stats->triangle_tests += m->triangle_count;
    watertight_ray shear = watertight_ray_of(mr->r);
    return triangle_nearest_watertight(&shear, m->vertices, m->triangles,
                                       m->triangle_count, t_min, t_max,
                                       out != NULL ? out : &unused);
}

/* <<the search of a mesh's BVH>> ch10 */
/* The triangles of a leaf, its packets: the nearest hit by the tie rule
 * (best: the nearest triangle so far, -1: none) into *out, or with out
 * NULL any hit; its index in m, or -1. in_float: decided in float. */
static inline __attribute__((always_inline)) int
bvh_leaf_test(const mesh *m, const packet_ray *r, bvh_leaf leaf,
              bool in_float, double t_min, double t_max, int best,
              triangle_hit *out, long long *decided)
{
    const triangle_packet *p = m->bvh_packets + leaf.first;
    int n = triangle_packets_needed(leaf.count);
    if (in_float && out == NULL)
        return triangle_packets_any_float(r, p, n, t_min, t_max) ? 0 : -1;
    if (in_float)
        return triangle_packets_nearest_float(r, p, n, t_min, t_max, best,
                                              out);
    /* corners that are floats already: read from the packet, at hand */
    const vec3 *v = m->bvh_corners_in_float ? NULL : m->vertices;
    if (out == NULL)
        return triangle_packets_any_in_mesh(r, p, n, v, m->triangles, t_min,
                                            t_max, decided) ? 0 : -1;
    return triangle_packets_nearest_in_mesh(r, p, n, v, m->triangles, t_min,
                                            t_max, best, out, decided);
}

/* The walk of m's binary BVH: chapter 9's, its leaves of packets. */
static int search_bvh2(const mesh *m, const mesh_ray *mr, double t_min,
                       double t_max, triangle_hit *out, render_stats *stats)
{
    bvh_ray r;
    if (!bvh_ray_of(mr->r.origin, mr->inv_dir, t_min, t_max, &r))
        return mesh_search_all(m, mr, t_min, t_max, out, stats);
    bvh_walk w;
    bvh_leaf leaf;
    int found = -1;
    long long decided = 0;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    packet_ray pr = packet_ray_of(&shear); /* which must outlive pr */
    bvh_walk_start(&w, &m->bvh, &r);
    w.sorted = out != NULL; /* any hit will do: no order to keep */
    while (bvh_walk_next(&w, t_max, &leaf)) {
        stats->triangle_tests += leaf.count;
        int k = bvh_leaf_test(m, &pr, leaf, m->bvh_in_float, t_min, t_max,
                              found, out, &decided);
        if (k < 0)
            continue;
        found = k;
        if (out == NULL)
            break; /* any hit blocks a shadow ray */
        t_max = out->t;
    }
    stats->bvh_nodes += w.visited;
    return found;
}

/* <<the walks of other trees>> ch11 */
#if defined(__SSE2__) && !defined(RT_SCALAR)
typedef double bvh_d2 __attribute__((vector_size(16), aligned(8)));

/* Lane 0 of the entry (near) and exit (far) of the slabs of one or two
 * axes, the exit widened: chapter 4's swap, with no branch. minpd(x, y)
 * is x < y ? x : y, and y for a NaN; maxpd(x, y) is x > y ? x : y. */
#define bvh_slabs2(lo, hi, near, far, widen)                                 \
    (near = __builtin_ia32_minpd(hi, lo),                                    \
     far = __builtin_ia32_maxpd(lo, hi) * (widen))
#endif

/* Chapter 4's box_clip of b, inline, with no branch but its answer:
 * does mr miss b in [t_min, t_max]? The same roundings, the same answer. */
BVH_INLINE bool bvh_misses_box(const box *b, const mesh_ray *mr,
                               double t_min, double t_max)
{
    const double widen = 1 + 2 * (3 * (DBL_EPSILON / 2) /
                                  (1 - 3 * (DBL_EPSILON / 2)));
#if defined(__SSE2__) && !defined(RT_SCALAR) /* x and y in two lanes */
    bvh_d2 o = *(const bvh_d2 *)&mr->r.origin.x;
    bvh_d2 q = *(const bvh_d2 *)&mr->inv_dir.x;
    bvh_d2 oz = {mr->r.origin.z, 0}, qz = {mr->inv_dir.z, 0};
    bvh_d2 near, far, near_z, far_z;
    bvh_slabs2((*(const bvh_d2 *)&b->lo.x - o) * q,
               (*(const bvh_d2 *)&b->hi.x - o) * q, near, far, widen);
    bvh_slabs2(((bvh_d2){b->lo.z, 0} - oz) * qz,
               ((bvh_d2){b->hi.z, 0} - oz) * qz, near_z, far_z, widen);
    /* maxsd(x, y) is x > y ? x : y in lane 0, y for a NaN: x, y, z */
    bvh_d2 t0 = {t_min, t_min}, t1 = {t_max, t_max};
    t0 = __builtin_ia32_maxsd(near, t0), t1 = __builtin_ia32_minsd(far, t1);
    near = __builtin_shufflevector(near, near, 1, 1); /* y in lane 0 */
    far = __builtin_shufflevector(far, far, 1, 1);
    t0 = __builtin_ia32_maxsd(near, t0), t1 = __builtin_ia32_minsd(far, t1);
    t0 = __builtin_ia32_maxsd(near_z, t0);
    t1 = __builtin_ia32_minsd(far_z, t1);
    return t0[0] > t1[0];
#else
    for (int a = 0; a < 3; a++) {
        double o = vec3_axis(mr->r.origin, a), q = vec3_axis(mr->inv_dir, a);
        double lo = (vec3_axis(b->lo, a) - o) * q;
        double hi = (vec3_axis(b->hi, a) - o) * q;
        bool swap = lo > hi; /* false for a NaN, as box_clip's */
        double near = swap ? hi : lo, far = (swap ? lo : hi) * widen;
        t_min = near > t_min ? near : t_min;
        t_max = far < t_max ? far : t_max;
    }
    return t_min > t_max;
#endif
}

/* The instructions a copy of the wide walk is compiled for. */
typedef enum { BVH_PLAIN, BVH_AVX2, BVH_AVX512 } bvh_isa;

/* The top of the stack into *now, skipping the children that start
 * beyond bound (the nearest hit); false when none is left. */
BVH_INLINE bool bvh_pop(const uint32_t *stack, const float *entry, int *top,
                        float bound, uint32_t *now)
{
    int k = *top;
    while (k > 0 && !(entry[k - 1] <= bound))
        k--; /* beyond the nearest hit */
    if (k == 0)
        return false;
    *now = stack[--k], *top = k;
    return true;
}

/* The word of n's child in lane c: a node's number by an addition to
 * child[0]'s, read with the node, so that the next node's address waits
 * on no load; a leaf's word read. */
BVH_INLINE uint32_t bvh_child_in_lane(const bvh_node8 *n, int c)
{
    if (c < bvh_child_nodes(n))
        return n->child[0] + (uint32_t)c;
    return n->child[c];
}

/* Lane k of the entries of a node test, taken from the vector that
 * t_near copies by a permutation, not read back from t_near: a load of
 * what was just stored waits for the store. Only where AVX2 is. */
BVH_AVX2_TARGET static inline float bvh_entry_avx2(const float t_near[8],
                                                   int k)
{
#if BVH_HAS_AVX2_PATH
    bvh_f8 t;
    memcpy(&t, t_near, sizeof t); /* the vector, still in its register */
    return __builtin_ia32_permvarsf256(t, (bvh_i8){0} + k)[0];
#else
    return t_near[k];
#endif
}

/* Two children of n met (lanes a < b of its mask): the nearer, by where
 * the ray enters it (a on a tie), is the next node; the other is pushed.
 * Both nodes (b is, then a is): their numbers by additions, as above.
 * avx2: the entries taken by bvh_entry_avx2. */
BVH_INLINE uint32_t bvh_take_two(uint32_t *stack, float *entry, int *top,
                                 const bvh_node8 *n, unsigned hit,
                                 const float t_near[8], bool avx2)
{
    int a = __builtin_ctz(hit), b = __builtin_ctz(hit & (hit - 1));
    float t_a = avx2 ? bvh_entry_avx2(t_near, a) : t_near[a];
    float t_b = avx2 ? bvh_entry_avx2(t_near, b) : t_near[b];
    uint32_t child_a, child_b;
    if (b < bvh_child_nodes(n))
        child_a = n->child[0] + (uint32_t)a,
        child_b = n->child[0] + (uint32_t)b;
    else
        child_a = n->child[a], child_b = n->child[b];
    bool a_first = t_a <= t_b;
    stack[*top] = a_first ? child_b : child_a;
    entry[*top] = a_first ? t_b : t_a;
    ++*top;
    return a_first ? child_a : child_b;
}

/* The walk of m's wide BVH for mr, its nodes tested with AVX2 unless isa
 * is BVH_PLAIN (the caller's instructions must allow isa), its leaves
 * decided in float when in_float; both constants where it is inlined. */
BVH_INLINE int search_bvh8(const mesh *m, const mesh_ray *mr, double t_min,
                           double t_max, triangle_hit *out,
                           render_stats *stats, bvh_isa isa, bool in_float)
{
    bool avx2 = isa != BVH_PLAIN;
    bvh_ray r;  /* the plain walk's ray */
    bvh_ray8 v; /* AVX2's, in vectors */
    unsigned shift;
    float ray_bound; /* the bound of the boxes that no hit has narrowed */
    if (avx2 ? !bvh_ray8_setup_avx2(mr->r.origin, mr->inv_dir, t_min, t_max,
                                    &v, &ray_bound, &shift)
             : !bvh_wide_ray_of(mr->r.origin, mr->inv_dir, t_min, t_max, &r,
                                &shift))
        return mesh_search_all(m, mr, t_min, t_max, out, stats);
    if (!avx2)
        ray_bound = r.t_max;
    const bvh_node8 *tree = m->bvh.nodes8; /* a local: never read again */
    uint32_t stack[BVH_STACK8], now = 0; /* the root */
    float entry[BVH_STACK8], bound = ray_bound;
    int top = 0, found = -1;
    long long nodes = 0, tests = 0, decided = 0;
    watertight_ray shear; /* chapter 4's, which pr points to */
    packet_ray pr;
    bool made = false; /* both made at the first leaf, if any */
    for (;;) {
        while (!(now & BVH_LEAF)) { /* the nodes, down to a leaf */
            const bvh_node8 *n = &tree[now];
            float t_near[8];
            int32_t met[8]; /* AVX2's lanes met, for its pushes */
            unsigned hit = avx2 ? bvh_node8_lanes_avx2(n, &v, bound, t_near,
                                                       met)
                                : bvh_node8_test(n, &r, bound, t_near);
            unsigned rest = hit & (hit - 1); /* hit less its lowest lane */
            nodes++;
            if (hit == 0 && !bvh_pop(stack, entry, &top, bound, &now))
                goto done; /* none, and nothing left */
            else if (hit != 0 && rest == 0) /* one: descend */
                now = bvh_child_in_lane(n, __builtin_ctz(hit));
            else if (hit != 0 && (rest & (rest - 1)) == 0) /* two */
                now = bvh_take_two(stack, entry, &top, n, hit, t_near,
                                   avx2);
            else if (hit != 0 && isa == BVH_AVX512) /* more: push, */
                top = bvh_push8_avx512(stack, entry, top, n, met, t_near,
                                       shift, &now) - 1; /* take the nearest */
            else if (hit != 0 && avx2)
                top = bvh_push8_avx2(stack, entry, top, n, met, t_near,
                                     shift, &now) - 1;
            else if (hit != 0) {
                top = bvh_push8(stack, entry, top, n, hit, t_near, shift);
                now = stack[--top];
            }
        }
        /* <<a leaf of the wide walk>> ch11 */
        bvh_leaf leaf = {(int)(now & BVH_FIRST_MASK),
                         (int)(now >> BVH_COUNT_SHIFT & 15)};
        if (!made) /* the shear, and the packets' constants from it */
            shear = watertight_ray_of(mr->r), pr = packet_ray_of(&shear), made = true;
        tests += leaf.count;
        int k = bvh_leaf_test(m, &pr, leaf, in_float, t_min, t_max, found, out,
                              &decided);
        if (k >= 0 && out == NULL) {
            found = k;
            break; /* any hit blocks a shadow ray */
        }
        if (k >= 0) {
            found = k, t_max = out->t; /* a float, on the float path */
            float b = in_float ? bvh_bound_after((float)t_max)
                               : float_up_by_bits(t_max * (1 + BVH_SLACK));
            bound = b < ray_bound ? b : ray_bound;
        }
        if (!bvh_pop(stack, entry, &top, bound, &now))
            break;
    }
done:
    stats->bvh_nodes += nodes, stats->triangle_tests += tests;
    return found;
}

/* The wide walk compiled for AVX2, every call in it inlined (flatten):
 * called only where the processor has it. */
BVH_AVX2_TARGET __attribute__((flatten)) static int
search_avx2_exact(const mesh *m, const mesh_ray *mr, double t_min,
                  double t_max, triangle_hit *out, render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_AVX2, false);
}

BVH_AVX2_TARGET __attribute__((flatten)) static int
search_avx2_float(const mesh *m, const mesh_ray *mr, double t_min,
                  double t_max, triangle_hit *out, render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_AVX2, true);
}

/* The same walk compiled for AVX-512VL: thirty-two vector registers. */
BVH_AVX512_TARGET __attribute__((flatten)) static int
search_avx512_exact(const mesh *m, const mesh_ray *mr, double t_min,
                    double t_max, triangle_hit *out, render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_AVX512, false);
}

BVH_AVX512_TARGET __attribute__((flatten)) static int
search_avx512_float(const mesh *m, const mesh_ray *mr, double t_min,
                    double t_max, triangle_hit *out, render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_AVX512, true);
}

/* The wide walk compiled for the build's own instructions. */
static int search_plain_exact(const mesh *m, const mesh_ray *mr,
                              double t_min, double t_max, triangle_hit *out,
                              render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_PLAIN, false);
}

static int search_plain_float(const mesh *m, const mesh_ray *mr,
                              double t_min, double t_max, triangle_hit *out,
                              render_stats *stats)
{
    return search_bvh8(m, mr, t_min, t_max, out, stats, BVH_PLAIN, true);
}

typedef int (*bvh_search)(const mesh *m, const mesh_ray *mr, double t_min,
                          double t_max, triangle_hit *out,
                          render_stats *stats);

/* By m->bvh_walk, then 1 more for the float path (0 and 1: the binary
 * walk, which mesh_search_bvh calls without the table). */
static const bvh_search searches[8] = {
    search_bvh2,       search_bvh2,         search_plain_exact,
    search_plain_float, search_avx2_exact,  search_avx2_float,
    search_avx512_exact, search_avx512_float};

int mesh_search_bvh(const mesh *m, const mesh_ray *mr, double t_min,
                    double t_max, triangle_hit *out, render_stats *stats)
{
    /* <<the walk of another tree chosen>> ch11 */
    if (m->bvh_walk != 0) { /* the wide walk: its box tested here */
        stats->box_tests++;
        if (bvh_misses_box(&m->bounds, mr, t_min, t_max))
            return -1; /* missing the box, the ray misses every triangle */
        return searches[m->bvh_walk + m->bvh_in_float](m, mr, t_min, t_max,
                                                        out, stats);
    }
    return search_bvh2(m, mr, t_min, t_max, out, stats);
}

/* <<the triangle's hit-point bound>> ch06 */
/* How wrong the watertight test's t can be for a ray that starts at p
 * near the triangle (a, b, c), as a distance from its plane, when the
 * test rounds to the unit u. */
static double triangle_test_error(vec3 a, vec3 b, vec3 c, vec3 p, double u)
{
    vec3 corners[3] = {a, b, c};
    double M = 0; /* the triangle's reach from p: largest coordinate */
    for (int k = 0; k < 3; k++) {
        vec3 r = vec3_abs(vec3_sub(corners[k], p));
        M = fmax(M, fmax(r.x, fmax(r.y, r.z)));
    }
    double twice_area = vec3_length(vec3_cross(vec3_sub(b, a),
                                               vec3_sub(c, a)));
    if (!(twice_area > 0))
        return INFINITY; /* never hit: the test rejects it */
    return sqrt(3) * (gamma_of_unit(3, u) * M +
                      48 * gamma_of_unit(4, u) * M * M * M / twice_area);
}

void triangle_refine_hit(vec3 a, vec3 b, vec3 c, const double w[3], hit *h)
{
    vec3 pa = vec3_scale(a, w[0]), pb = vec3_scale(b, w[1]),
         pc = vec3_scale(c, w[2]);
    h->point = vec3_add(vec3_add(pa, pb), pc);
    vec3 sum = vec3_add(vec3_add(vec3_abs(pa), vec3_abs(pb)), vec3_abs(pc));
    double test = triangle_test_error(a, b, c, h->point, DBL_EPSILON / 2);
    h->error = vec3_add(vec3_scale(sum, gamma_bound(7)),
                        (vec3){test, test, test});
}

void mesh_refine_hit(const mesh *m, int k, const double w[3], hit *h)
{
    const int *v = m->triangles[k].v;
    vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
    /* <<a mesh hit's bound for another test>> ch10 */
    if (m->bvh_in_float) { /* its rays meet it again in float */
        triangle_refine_float_hit(a, b, c, w, h);
        return;
    }
    triangle_refine_hit(a, b, c, w, h);
}
/* <<the triangle's hit-point bound>> += ch10 */

/* Covers the bound's own roundings, and the origin's move by the offset,
 * which float rounds too. */
#define FLOAT_BOUND_MARGIN (1 + 0x1p-10)

void triangle_refine_float_hit(vec3 a, vec3 b, vec3 c, const double w[3],
                               hit *h)
{
    const double u = FLT_EPSILON / 2;   /* float's unit roundoff */
    triangle_refine_hit(a, b, c, w, h); /* the point; double's bound */
    vec3 sum = vec3_add(vec3_add(vec3_abs(vec3_scale(a, w[0])),
                                 vec3_abs(vec3_scale(b, w[1]))),
                        vec3_abs(vec3_scale(c, w[2])));
    vec3 weights = vec3_scale(sum, gamma_of_unit(5, u)); /* float's w */
    vec3 reach = vec3_max(vec3_max(vec3_abs(a), vec3_abs(b)),
                          vec3_max(vec3_abs(c), vec3_abs(h->point)));
    vec3 inputs = vec3_scale(reach, 2 * u); /* corners, origin to float */
    double test = triangle_test_error(a, b, c, h->point, u);
    vec3 more = vec3_add(vec3_add(weights, inputs), (vec3){test, test, test});
    h->error = vec3_add(h->error, vec3_scale(more, FLOAT_BOUND_MARGIN));
}
