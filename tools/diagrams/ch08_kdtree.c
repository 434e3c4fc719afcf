/* ch08_kdtree.c: chapter 08's diagrams of a kd-tree, drawn by computation.
 *
 * Usage: ch08_kdtree OUTDIR
 *
 * Writes OUTDIR/ch08-diagram-kdtree.svg: twelve triangles in the plane, the
 * cells of the kd-tree that the surface area heuristic (in 2D: the
 * perimeter) builds over them, and one ray's walk: the leaves it visits,
 * numbered in order, up to the leaf where its nearest hit lies. And
 * OUTDIR/ch08-diagram-step.svg: one step of the walk, the interval
 * [t_min, t_max] of a ray in a cell against the plane that splits it, in
 * the cases the walk tells apart.
 *
 * Nothing is placed by eye: the tree is built and the ray walked by the
 * same rules as the chapter's program (in 2D and without clipping), and
 * every point drawn is computed. Only where a label goes is chosen by hand.
 * The palette and line widths are those of the other chapters' diagrams. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- style */
#define INK "#222222"
#define GUIDE "#8a8a8a"
#define C_RAY "#0072b2"
#define C_HIT "#d0361a"
#define C_PLANE "#5a4fcf"
#define F_BLUE "#dcebf7"
#define F_ORANGE "#fbe6c8"
#define F_GREY "#eeeeee"
#define LW_GEOM 1.5
#define LW_VEC 2.2
#define LW_GUIDE 1.0
#define FS_NOTE 13.5
#define FS_MATH 16.0

typedef struct {
    double x, y;
} v2;

static v2 V(double x, double y) { return (v2){x, y}; }
static v2 add(v2 a, v2 b) { return V(a.x + b.x, a.y + b.y); }
static v2 mul(v2 a, double s) { return V(a.x * s, a.y * s); }
static double axis_of(v2 p, int axis) { return axis == 0 ? p.x : p.y; }

/* ---------------------------------------------------------------- SVG */
static FILE *svg;
static double view_x, view_y, view_s; /* world (x, y) at (vx + s x, vy - s y) */

static v2 scr(v2 p) { return V(view_x + view_s * p.x, view_y - view_s * p.y); }

static void begin(const char *dir, const char *name, int w, int h, const char *title)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    svg = fopen(path, "w");
    if (!svg) {
        perror(path);
        exit(1);
    }
    fprintf(svg,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
            "viewBox=\"0 0 %d %d\">\n<title>%s</title>\n"
            "<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n",
            w, h, w, h, title, w, h);
}

static void finish(void)
{
    fprintf(svg, "</svg>\n");
    if (ferror(svg) || fclose(svg) != 0) {
        perror("diagram");
        exit(1);
    }
}

static void line(v2 a, v2 b, const char *colour, double width, const char *dash)
{
    v2 s = scr(a), e = scr(b);
    fprintf(svg, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                 "stroke-width=\"%.1f\"%s%s%s stroke-linecap=\"round\"/>\n",
            s.x, s.y, e.x, e.y, colour, width, dash ? " stroke-dasharray=\"" : "",
            dash ? dash : "", dash ? "\"" : "");
}

static void polygon(const v2 *p, int n, const char *fill, const char *colour, double width)
{
    fprintf(svg, "<path d=\"");
    for (int i = 0; i < n; i++) {
        v2 s = scr(p[i]);
        fprintf(svg, "%s%.1f %.1f", i ? " L" : "M", s.x, s.y);
    }
    fprintf(svg, "Z\" fill=\"%s\" stroke=\"%s\" stroke-width=\"%.1f\" "
                 "stroke-linejoin=\"round\"/>\n",
            fill, colour ? colour : "none", width);
}

static void rect(v2 a, v2 b, const char *fill, const char *colour, double width)
{
    v2 p[4] = {a, V(b.x, a.y), b, V(a.x, b.y)};
    polygon(p, 4, fill, colour, width);
}

static void dot(v2 p, const char *colour)
{
    v2 s = scr(p);
    fprintf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.6\" fill=\"%s\"/>\n", s.x, s.y, colour);
}

/* Text at world point p moved by (dx, dy) pixels; anchor start/middle/end. */
static void text(v2 p, double dx, double dy, const char *anchor, double size, const char *colour,
                 bool italic, const char *s)
{
    v2 q = scr(p);
    fprintf(svg, "<text x=\"%.1f\" y=\"%.1f\" font-family=\"%s\" font-size=\"%.1f\" "
                 "text-anchor=\"%s\" fill=\"%s\"%s>%s</text>\n",
            q.x + dx, q.y + dy, italic ? "serif" : "sans-serif", size, anchor, colour,
            italic ? " font-style=\"italic\"" : "", s);
}

/* An arrow from a to b in world coordinates. */
static void arrow(v2 a, v2 b, const char *colour, double width)
{
    line(a, b, colour, width, NULL);
    v2 s = scr(a), e = scr(b), d = V(e.x - s.x, e.y - s.y);
    double l = sqrt(d.x * d.x + d.y * d.y);
    d = V(d.x / l, d.y / l);
    v2 n = V(-d.y, d.x), h[3] = {e, add(e, add(mul(d, -11), mul(n, 4.5))),
                                 add(e, add(mul(d, -11), mul(n, -4.5)))};
    fprintf(svg, "<path d=\"M%.1f %.1f L%.1f %.1f L%.1f %.1fZ\" fill=\"%s\"/>\n", h[0].x,
            h[0].y, h[1].x, h[1].y, h[2].x, h[2].y, colour);
}

/* ---------------------------------------------------------------- the scene */
enum { N = 12 };

/* Twelve small triangles: a row along the bottom, a cluster at the top
 * right, a few alone: space that is empty, and space that is not. */
static const v2 tri[N][3] = {
    {{0.6, 0.5}, {1.5, 0.6}, {1.0, 1.4}}, {{1.9, 0.4}, {2.9, 0.5}, {2.3, 1.2}},
    {{3.2, 0.6}, {4.0, 0.4}, {3.7, 1.3}}, {{4.5, 0.5}, {5.3, 0.7}, {4.8, 1.3}},
    {{7.2, 4.2}, {7.9, 4.0}, {7.6, 4.9}}, {{8.1, 4.5}, {8.9, 4.3}, {8.4, 5.2}},
    {{7.5, 5.1}, {8.2, 5.3}, {7.7, 5.8}}, {{8.6, 5.0}, {9.4, 5.2}, {9.0, 5.8}},
    {{1.2, 4.6}, {2.0, 4.9}, {1.4, 5.6}}, {{5.4, 2.6}, {6.2, 2.9}, {5.7, 3.5}},
    {{8.8, 1.6}, {9.6, 1.9}, {9.1, 2.5}}, {{0.5, 2.6}, {1.1, 2.5}, {0.8, 3.3}}};

typedef struct {
    v2 lo, hi;
} box2;

static box2 tri_box(int k)
{
    box2 b = {tri[k][0], tri[k][0]};
    for (int c = 1; c < 3; c++)
        b.lo = V(fmin(b.lo.x, tri[k][c].x), fmin(b.lo.y, tri[k][c].y)),
        b.hi = V(fmax(b.hi.x, tri[k][c].x), fmax(b.hi.y, tri[k][c].y));
    return b;
}

/* ---------------------------------------------------------------- the tree */
typedef struct {
    int axis; /* -1: a leaf */
    double split;
    int below, above; /* children */
    box2 cell;
    int items[N], count, depth;
} node;

static node nodes[64];
static int n_nodes;
#define KT 15.0 /* the chapter's costs: K_T and K_I, and the empty bonus */
#define KI 20.0
#define BONUS 0.2

static double perimeter(box2 b) { return 2 * ((b.hi.x - b.lo.x) + (b.hi.y - b.lo.y)); }

/* The cost of the plane x on the axis of the cell holding items[0..n):
 * the SAH in 2D, where a ray meets a convex cell with a probability in
 * proportion to its perimeter. */
static double cost(box2 cell, const int *items, int n, int axis, double x)
{
    int below = 0, above = 0;
    for (int i = 0; i < n; i++) {
        box2 b = tri_box(items[i]);
        below += axis_of(b.lo, axis) < x;
        above += axis_of(b.hi, axis) > x;
    }
    box2 under = cell, over = cell;
    if (axis == 0)
        under.hi.x = over.lo.x = x;
    else
        under.hi.y = over.lo.y = x;
    double p = perimeter(cell);
    double c = KT + KI * (perimeter(under) / p * below + perimeter(over) / p * above);
    return below == 0 || above == 0 ? (1 - BONUS) * c : c;
}

static int build(box2 cell, const int *items, int n, int depth)
{
    int k = n_nodes++;
    node *nd = &nodes[k];
    *nd = (node){.axis = -1, .cell = cell, .count = n, .depth = depth};
    memcpy(nd->items, items, (size_t)n * sizeof *items);
    double best = KI * n;
    for (int axis = 0; axis < 2 && n > 1 && depth < 6; axis++)
        for (int i = 0; i < n; i++)
            for (int side = 0; side < 2; side++) { /* every box face: an event */
                box2 b = tri_box(items[i]);
                double x = axis_of(side ? b.hi : b.lo, axis);
                if (x <= axis_of(cell.lo, axis) || x >= axis_of(cell.hi, axis))
                    continue;
                double c = cost(cell, items, n, axis, x);
                if (c < best)
                    best = c, nd->axis = axis, nd->split = x;
            }
    if (nodes[k].axis < 0)
        return k;
    int below[N], above[N], nb = 0, na = 0, axis = nodes[k].axis;
    double x = nodes[k].split;
    for (int i = 0; i < n; i++) {
        box2 b = tri_box(items[i]);
        if (axis_of(b.lo, axis) < x)
            below[nb++] = items[i];
        if (axis_of(b.hi, axis) > x)
            above[na++] = items[i];
    }
    box2 under = cell, over = cell;
    if (axis == 0)
        under.hi.x = over.lo.x = x;
    else
        under.hi.y = over.lo.y = x;
    nodes[k].below = build(under, below, nb, depth + 1);
    nodes[k].above = build(over, above, na, depth + 1);
    return k;
}

/* ---------------------------------------------------------------- the walk */
static v2 ray_o, ray_d;

/* The ray's nearest hit on segment p-q of a triangle's edge, or infinity. */
static double hit_edge(v2 p, v2 q)
{
    v2 e = V(q.x - p.x, q.y - p.y);
    double det = ray_d.x * (-e.y) - ray_d.y * (-e.x);
    if (det == 0)
        return INFINITY;
    v2 w = V(p.x - ray_o.x, p.y - ray_o.y);
    double t = (w.x * (-e.y) - w.y * (-e.x)) / det;
    double s = (ray_d.x * w.y - ray_d.y * w.x) / det;
    return t > 0 && s >= 0 && s <= 1 ? t : INFINITY;
}

static double hit_triangle(int k)
{
    double t = INFINITY;
    for (int c = 0; c < 3; c++)
        t = fmin(t, hit_edge(tri[k][c], tri[k][(c + 1) % 3]));
    return t;
}

static int visited[32], n_visited;
static double visit_t[32][2], best_t = INFINITY;

/* The recursive walk, front to back, stopping at the nearest hit. */
static void walk(int k, double t0, double t1)
{
    if (t0 > best_t)
        return;
    node *nd = &nodes[k];
    if (nd->axis < 0) {
        visited[n_visited] = k, visit_t[n_visited][0] = t0, visit_t[n_visited++][1] = t1;
        for (int i = 0; i < nd->count; i++)
            best_t = fmin(best_t, hit_triangle(nd->items[i]));
        return;
    }
    double o = axis_of(ray_o, nd->axis), d = axis_of(ray_d, nd->axis);
    double t_split = (nd->split - o) / d;
    int near = o < nd->split ? nd->below : nd->above;
    int far = near == nd->below ? nd->above : nd->below;
    if (t_split > t1 || t_split <= 0) {
        walk(near, t0, t1);
    } else if (t_split < t0) {
        walk(far, t0, t1);
    } else {
        walk(near, t0, t_split);
        if (best_t > t_split)
            walk(far, t_split, t1);
    }
}

/* The interval in which the ray is inside the box, as the slab test finds
 * it. */
static int clip(box2 b, double *t0, double *t1)
{
    *t0 = 0, *t1 = INFINITY;
    for (int a = 0; a < 2; a++) {
        double o = axis_of(ray_o, a), d = axis_of(ray_d, a);
        double n = (axis_of(b.lo, a) - o) / d, f = (axis_of(b.hi, a) - o) / d;
        *t0 = fmax(*t0, fmin(n, f)), *t1 = fmin(*t1, fmax(n, f));
    }
    return *t0 <= *t1;
}

static v2 at(double t) { return add(ray_o, mul(ray_d, t)); }

/* ---------------------------------------------------------------- diagram 1 */
static void draw_tree(const char *dir)
{
    int all[N];
    for (int k = 0; k < N; k++)
        all[k] = k;
    box2 root = tri_box(0);
    for (int k = 1; k < N; k++) {
        box2 b = tri_box(k);
        root.lo = V(fmin(root.lo.x, b.lo.x), fmin(root.lo.y, b.lo.y));
        root.hi = V(fmax(root.hi.x, b.hi.x), fmax(root.hi.y, b.hi.y));
    }
    build(root, all, N, 0);
    ray_o = V(-0.6, 4.4); /* aimed at the middle of triangle 9 */
    v2 aim = V((tri[9][0].x + tri[9][1].x + tri[9][2].x) / 3,
               (tri[9][0].y + tri[9][1].y + tri[9][2].y) / 3);
    double len = hypot(aim.x - ray_o.x, aim.y - ray_o.y);
    ray_d = V((aim.x - ray_o.x) / len, (aim.y - ray_o.y) / len);
    double t0, t1;
    if (!clip(root, &t0, &t1)) {
        fprintf(stderr, "ch08_kdtree: the ray misses the root cell\n");
        exit(1);
    }
    walk(0, t0, t1);
    if (!isfinite(best_t)) {
        fprintf(stderr, "ch08_kdtree: the ray hits nothing\n");
        exit(1);
    }

    begin(dir, "ch08-diagram-kdtree", 700, 470,
          "A kd-tree over twelve triangles, and one ray's walk");
    view_x = 40, view_y = 400, view_s = 62;
    rect(V(root.lo.x, root.lo.y), V(root.hi.x, root.hi.y), F_GREY, NULL, 0);
    for (int v = 0; v < n_visited; v++) { /* the leaves the ray visits */
        box2 c = nodes[visited[v]].cell;
        rect(c.lo, c.hi, v == n_visited - 1 ? F_ORANGE : F_BLUE, NULL, 0);
    }
    for (int k = 0; k < N; k++)
        polygon(tri[k], 3, "#ffffff", INK, LW_GEOM);
    for (int k = 0; k < n_nodes; k++) { /* the planes, thinner as they go deeper */
        node *nd = &nodes[k];
        if (nd->axis < 0)
            continue;
        v2 a = nd->axis == 0 ? V(nd->split, nd->cell.lo.y) : V(nd->cell.lo.x, nd->split);
        v2 b = nd->axis == 0 ? V(nd->split, nd->cell.hi.y) : V(nd->cell.hi.x, nd->split);
        line(a, b, C_PLANE, fmax(0.8, 2.6 - 0.4 * nd->depth), NULL);
        char label[16]; /* room for any int */
        snprintf(label, sizeof label, "%d", nd->depth + 1);
        if (nd->axis == 0)
            text(b, 0, -4, "middle", 11, C_PLANE, false, label);
        else
            text(b, 4, 4, "start", 11, C_PLANE, false, label);
    }
    rect(root.lo, root.hi, "none", INK, LW_GEOM);
    arrow(ray_o, at(best_t), C_RAY, LW_VEC);
    line(at(best_t), at(t1 + 0.8), C_RAY, LW_GUIDE, "5 4");
    dot(at(best_t), C_HIT);
    text(at(best_t), 30, 34, "start", FS_NOTE, C_HIT, false, "the nearest hit");
    dot(at(t0), C_RAY);
    text(at(t0), -2, -10, "end", FS_MATH, C_RAY, true, "t<tspan baseline-shift=\"sub\" "
                                                       "font-size=\"11\">min</tspan>");
    dot(at(t1), C_RAY);
    text(at(t1), 6, 16, "start", FS_MATH, C_RAY, true, "t<tspan baseline-shift=\"sub\" "
                                                      "font-size=\"11\">max</tspan>");
    for (int v = 0; v < n_visited; v++) { /* where the walk enters each leaf */
        char label[16]; /* room for any int */
        snprintf(label, sizeof label, "%d", v + 1);
        v2 mid = at(0.5 * (fmax(visit_t[v][0], t0) + fmin(visit_t[v][1], best_t)));
        text(mid, 0, -10, "middle", FS_NOTE, INK, false, label);
    }
    text(V(root.lo.x, root.lo.y), 0, 30, "start", FS_NOTE, INK, false,
         "Planes numbered by depth. Blue: the leaves the walk visits, in order;");
    text(V(root.lo.x, root.lo.y), 0, 48, "start", FS_NOTE, INK, false,
         "orange: the leaf of the nearest hit, where the walk stops.");
    finish();
}

/* ---------------------------------------------------------------- diagram 2 */

/* One case: a cell from x = 0 to 4 split at x = 2 (a thick plane), a ray
 * from o along d; what the walk does, in words. */
static void draw_case(double left, const char *title, v2 o, v2 d, double t0, double t1,
                      const char *what)
{
    view_x = left, view_y = 290, view_s = 42;
    rect(V(0, 0), V(4, 4), F_GREY, INK, LW_GEOM);
    rect(V(1.92, 0), V(2.08, 4), "#e2defa", NULL, 0); /* the plane's thickness, */
    line(V(2, 0), V(2, 4), C_PLANE, 2.0, NULL);         /* much exaggerated */
    text(V(2, 4), 0, -6, "middle", 12, C_PLANE, false, "split");
    text(V(1, 0), 0, 18, "middle", 12, INK, false, "below");
    text(V(3, 0), 0, 18, "middle", 12, INK, false, "above");
    ray_o = o, ray_d = d;
    line(at(0), at(t0), C_RAY, LW_GUIDE, "5 4");
    arrow(at(t0), at(t1), C_RAY, LW_VEC);
    dot(at(t0), C_RAY);
    dot(at(t1), C_RAY);
    double t_split = (2 - o.x) / d.x;
    if (isfinite(t_split) && t_split > -0.5 && t_split < t1 + 2)
        dot(at(t_split), C_PLANE);
    text(V(2, 0), 0, 42, "middle", FS_NOTE, INK, false, title);
    text(V(2, 0), 0, 60, "middle", 12.5, C_PLANE, false, what);
}

static void draw_step(const char *dir)
{
    begin(dir, "ch08-diagram-step", 780, 370,
          "One step of the walk: the ray's interval against a cell's plane");
    double s = 1 / sqrt(1 + 0.25);
    v2 d = V(s, 0.5 * s), down = V(0.5 * s, -s);
    draw_case(30, "crosses inside [t_min, t_max]", V(-0.6, 0.95), d, 0.6 / s, 4.6 / s,
              "near side, then far side");
    draw_case(220, "crosses beyond t_max", V(-0.6, 0.4), d, 0.6 / s, 2.1 / s,
              "near side only");
    draw_case(410, "crossed before t_min", V(1.3, 6.3), down, 2.3 / s, 2.7 * 2 / s,
              "far side only");
    draw_case(600, "lies in the plane", V(2, -0.6), V(0, 1), 0.6, 4.6, "both sides, whole");
    finish();
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "figures";
    draw_tree(dir);
    draw_step(dir);
    return 0;
}
