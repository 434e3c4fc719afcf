/* diagrams.c: the book's explanatory diagrams, drawn by computation.
 *
 * Usage: diagrams OUTDIR [NAME...]
 *
 * Writes OUTDIR/chNN-diagram-NAME.svg for every diagram below, or only for
 * the NAMEs given (for example "ch02-diagram-sphere"). `make diagrams` runs
 * it on figures/.
 *
 * Nothing is placed by eye: each drawing sets up its geometry in world
 * coordinates and computes every derived point with the chapter's own
 * formula (the pixel centres of chapter 01, the closest approach and the
 * half-chord of chapter 02, r = 2n<n,l> - l and h = (l + v)/|l + v| of
 * chapter 03, the barycentric areas and the watertight shear of chapter 04,
 * and so on). Only where a label goes is chosen by hand, as an offset in
 * pixels from the point it names.
 *
 * The SVG is plain: generic font families, no scripts, no external
 * resources, a white background, and one palette and set of line widths for
 * every diagram (the "style" section). Output is rounded to 0.1 px, so it is
 * the same on every machine. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define DEG (M_PI / 180.0)

/* ---------------------------------------------------------------- style */
/* One colour per kind of thing, the same in every diagram (Okabe-Ito hues,
 * darkened where text in that colour must stay readable on white). */
#define INK "#222222"      /* geometry, points, axes */
#define GUIDE "#8a8a8a"    /* construction lines, extensions, dimensions */
#define C_RAY "#0072b2"    /* rays, d, v, the viewer's side */
#define C_N "#008a60"      /* normals n */
#define C_L "#bf8a00"      /* light: l, the light's position, the spot */
#define C_R "#d0361a"      /* reflected r */
#define C_H "#b4539a"      /* half vector h */
#define C_T "#5a4fcf"      /* tangent, transmitted t, the correct normal */
#define F_BLUE "#dcebf7"   /* fills, light tints of the above */
#define F_ORANGE "#fbe6c8"
#define F_GREEN "#d4efe2"
#define F_PURPLE "#eedcf0"
#define F_GREY "#eeeeee"
#define F_YELLOW "#fff2b8"

#define LW_GEOM 1.5  /* outlines, surfaces, axes */
#define LW_VEC 2.2   /* vectors and rays */
#define LW_GUIDE 1.0 /* construction and dimension lines */
#define DASH "5 4"
#define FS_MATH 17.0 /* math labels: serif, letters italic */
#define FS_NOTE 13.5 /* notes: sans-serif, upright */
#define FS_SMALL 13.0

/* ---------------------------------------------------------------- 2D and 3D vectors */
typedef struct {
    double x, y;
} v2;
typedef struct {
    double x, y, z;
} v3;

static v2 V(double x, double y) { return (v2){x, y}; }
static v2 add(v2 a, v2 b) { return V(a.x + b.x, a.y + b.y); }
static v2 sub(v2 a, v2 b) { return V(a.x - b.x, a.y - b.y); }
static v2 mul(v2 a, double s) { return V(a.x * s, a.y * s); }
static double dot(v2 a, v2 b) { return a.x * b.x + a.y * b.y; }
static double cross(v2 a, v2 b) { return a.x * b.y - a.y * b.x; }
static double len(v2 a) { return sqrt(dot(a, a)); }
static v2 unit(v2 a) { return mul(a, 1.0 / len(a)); }
static v2 perp(v2 a) { return V(-a.y, a.x); } /* a turned 90 degrees counter-clockwise */
static v2 lerp(v2 a, v2 b, double t) { return add(a, mul(sub(b, a), t)); }
static v2 polar(double angle) { return V(cos(angle), sin(angle)); }
static double angle_of(v2 a) { return atan2(a.y, a.x); }

static v3 V3(double x, double y, double z) { return (v3){x, y, z}; }
static v3 add3(v3 a, v3 b) { return V3(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 sub3(v3 a, v3 b) { return V3(a.x - b.x, a.y - b.y, a.z - b.z); }
static v3 mul3(v3 a, double s) { return V3(a.x * s, a.y * s, a.z * s); }
static double dot3(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 unit3(v3 a) { return mul3(a, 1.0 / sqrt(dot3(a, a))); }

static void require(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "diagrams: the geometry does not hold: %s\n", what);
        exit(1);
    }
}

/* ---------------------------------------------------------------- SVG output */
static FILE *svg;
static char svg_path[4096];
/* The view: world (x, y) is drawn at (view_x + view_s x, view_y - view_s y),
 * so y points up as in the chapters' figures. */
static double view_x, view_y, view_s = 1;

static void set_view(double x, double y, double scale)
{
    view_x = x, view_y = y, view_s = scale;
}

static v2 scr(v2 p) { return V(view_x + view_s * p.x, view_y - view_s * p.y); }

static void begin(const char *dir, const char *name, int width, int height, const char *title)
{
    snprintf(svg_path, sizeof svg_path, "%s/%s.svg", dir, name);
    svg = fopen(svg_path, "w");
    if (!svg) {
        perror(svg_path);
        exit(1);
    }
    fprintf(svg,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
            "viewBox=\"0 0 %d %d\">\n<title>%s</title>\n"
            "<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n",
            width, height, width, height, title, width, height);
    set_view(0, 0, 1);
}

static void finish(void)
{
    fprintf(svg, "</svg>\n");
    if (ferror(svg) || fclose(svg) != 0) {
        perror(svg_path);
        exit(1);
    }
    printf("wrote %s\n", svg_path);
}

static void stroke_attrs(const char *colour, double width, const char *dash)
{
    fprintf(svg, " stroke=\"%s\" stroke-width=\"%.1f\"", colour, width);
    if (dash)
        fprintf(svg, " stroke-dasharray=\"%s\"", dash);
}

/* Lines, polygons and circles in screen coordinates ... */
static void line_s(v2 a, v2 b, const char *colour, double width, const char *dash)
{
    fprintf(svg, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"", a.x, a.y, b.x, b.y);
    stroke_attrs(colour, width, dash);
    fprintf(svg, " stroke-linecap=\"round\"/>\n");
}

static void polygon_s(const v2 *p, int n, const char *fill, const char *colour, double width,
                      const char *dash)
{
    fprintf(svg, "<path d=\"");
    for (int i = 0; i < n; i++)
        fprintf(svg, "%s%.1f %.1f", i ? " L" : "M", p[i].x, p[i].y);
    fprintf(svg, "Z\" fill=\"%s\"", fill ? fill : "none");
    if (colour)
        stroke_attrs(colour, width, dash);
    fprintf(svg, " stroke-linejoin=\"round\"/>\n");
}

/* ... and in world coordinates. */
static void line(v2 a, v2 b, const char *colour, double width, const char *dash)
{
    line_s(scr(a), scr(b), colour, width, dash);
}

static void polygon(const v2 *p, int n, const char *fill, const char *colour, double width)
{
    v2 s[16];
    require(n <= 16, "polygon of at most 16 corners");
    for (int i = 0; i < n; i++)
        s[i] = scr(p[i]);
    polygon_s(s, n, fill, colour, width, NULL);
}

static void rect(v2 a, v2 b, const char *fill, const char *colour, double width)
{
    v2 p[4] = {a, V(b.x, a.y), b, V(a.x, b.y)};
    polygon(p, 4, fill, colour, width);
}

static void circle(v2 c, double radius, const char *fill, const char *colour, double width,
                   const char *dash)
{
    v2 s = scr(c);
    fprintf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\"", s.x, s.y,
            radius * view_s, fill ? fill : "none");
    if (colour)
        stroke_attrs(colour, width, dash);
    fprintf(svg, "/>\n");
}

/* A point: a filled disc of a fixed size on screen. */
static void point(v2 p, const char *colour)
{
    v2 s = scr(p);
    fprintf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.6\" fill=\"%s\"/>\n", s.x, s.y, colour);
}

/* An arrow in screen coordinates; the head (length hl, half width hw, in
 * pixels) ends exactly at b, and the shaft stops where the head begins. */
static void arrow_s(v2 a, v2 b, const char *colour, double width, double hl, double hw,
                    const char *dash)
{
    v2 u = unit(sub(b, a)), n = perp(u);
    v2 base = sub(b, mul(u, hl * 0.9));
    line_s(a, base, colour, width, dash);
    v2 head[3] = {b, add(sub(b, mul(u, hl)), mul(n, hw)), sub(sub(b, mul(u, hl)), mul(n, hw))};
    polygon_s(head, 3, colour, NULL, 0, NULL);
}

static void arrow(v2 a, v2 b, const char *colour, double width)
{
    arrow_s(scr(a), scr(b), colour, width, 12, 4.5, NULL);
}

/* An arc of radius r pixels around c, from the direction at world angle a0
 * counter-clockwise to a1 (a1 > a0). */
static void arc(v2 c, double r, double a0, double a1, const char *colour, double width,
                const char *dash)
{
    v2 s = scr(c);
    v2 p0 = V(s.x + r * cos(a0), s.y - r * sin(a0));
    v2 p1 = V(s.x + r * cos(a1), s.y - r * sin(a1));
    fprintf(svg, "<path d=\"M%.1f %.1f A%.1f %.1f 0 %d 0 %.1f %.1f\" fill=\"none\"", p0.x, p0.y, r,
            r, a1 - a0 > M_PI, p1.x, p1.y);
    stroke_attrs(colour, width, dash);
    fprintf(svg, "/>\n");
}

/* ---------------------------------------------------------------- text */
/* XML-escaped bytes of one character starting at s; returns its length. */
static int put_char(char *out, const char *s)
{
    unsigned char c = (unsigned char)*s;
    if (c == '<')
        return strcpy(out, "&lt;"), 1;
    if (c == '>')
        return strcpy(out, "&gt;"), 1;
    if (c == '&')
        return strcpy(out, "&amp;"), 1;
    int n = c < 0x80 ? 1 : c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
    memcpy(out, s, (size_t)n);
    out[n] = '\0';
    return n;
}

/* Letters of a formula are italic: ASCII letters and lowercase Greek. */
static int is_math_letter(const char *s)
{
    unsigned char c = (unsigned char)s[0], d = (unsigned char)s[1];
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))
        return 1;
    return (c == 0xce && d >= 0xb1 && d <= 0xbf) || (c == 0xcf && d >= 0x80 && d <= 0x89);
}

/* A run of characters of one style, and the baseline shift so far. */
static struct {
    char text[1024];
    size_t n;
    int italic, level; /* level 0: baseline, 1: subscript, 2: superscript */
} run;
static double run_shift;

static void flush_run(double size)
{
    if (run.n == 0)
        return;
    double shift = run.level == 1 ? 0.28 * size : run.level == 2 ? -0.42 * size : 0;
    fprintf(svg, "<tspan");
    if (shift != run_shift)
        fprintf(svg, " dy=\"%.1f\"", shift - run_shift);
    run_shift = shift;
    if (run.italic)
        fprintf(svg, " font-style=\"italic\"");
    if (run.level)
        fprintf(svg, " font-size=\"%.1f\"", 0.72 * size);
    fprintf(svg, ">%.*s</tspan>", (int)run.n, run.text);
    run.n = 0;
}

static void run_add(const char *bytes, int italic, int level, double size)
{
    if (run.n && (italic != run.italic || level != run.level))
        flush_run(size);
    run.italic = italic, run.level = level;
    size_t k = strlen(bytes);
    require(run.n + k < sizeof run.text, "a label shorter than 1 KB");
    memcpy(run.text + run.n, bytes, k);
    run.n += k;
}

/* Writes the characters of s up to end at the given level. A formula's
 * markup: letters italic, everything else upright; \word an upright word
 * (\tan, \cos); _x or _{...} a subscript, ^x or ^{...} a superscript; a
 * space stays a space. */
static void put_math(const char *s, const char *end, int level, double size)
{
    char buf[16];
    while (s < end) {
        if ((*s == '_' || *s == '^') && s + 1 < end) {
            int sub_level = *s == '_' ? 1 : 2;
            s++;
            const char *stop;
            if (*s == '{') {
                stop = strchr(s, '}');
                require(stop && stop < end, "a closed brace in a label");
                put_math(s + 1, stop, sub_level, size);
                s = stop + 1;
            } else {
                stop = s + put_char(buf, s);
                put_math(s, stop, sub_level, size);
                s = stop;
            }
        } else if (*s == '\\') {
            s++;
            while (s < end && ((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z'))) {
                buf[0] = *s++, buf[1] = '\0';
                run_add(buf, 0, level, size);
            }
        } else if (*s == ' ') {
            /* kept by xml:space="preserve"; upright at the run's level */
            run_add(" ", 0, level, size);
            s++;
        } else {
            int italic = is_math_letter(s);
            s += put_char(buf, s);
            /* a combining mark (U+0300..U+036F, as the tilde of p̃) stays
             * with its letter */
            while (s < end && (((unsigned char)s[0] == 0xcc && (unsigned char)s[1] >= 0x80) ||
                               ((unsigned char)s[0] == 0xcd && (unsigned char)s[1] < 0xb0)))
                s += put_char(buf + strlen(buf), s);
            run_add(buf, italic, level, size);
        }
    }
}

/* Text whose middle (vertically) is at the screen point p, anchored
 * "start", "middle" or "end" horizontally, on a white halo that keeps it
 * readable where it crosses a line. */
static void text_s(v2 p, const char *anchor, const char *colour, double size, int math,
                   const char *s)
{
    fprintf(svg,
            "<text x=\"%.1f\" y=\"%.1f\" font-family=\"%s\" font-size=\"%.1f\" fill=\"%s\" "
            "text-anchor=\"%s\" xml:space=\"preserve\" stroke=\"#ffffff\" stroke-width=\"3.5\" "
            "stroke-linejoin=\"round\" paint-order=\"stroke\">",
            p.x, p.y + 0.35 * size, math ? "serif" : "sans-serif", size, colour, anchor);
    if (math) {
        run.n = 0, run_shift = 0;
        put_math(s, s + strlen(s), 0, size);
        flush_run(size);
    } else {
        char buf[16];
        while (*s) {
            s += put_char(buf, s);
            fputs(buf, svg);
        }
    }
    fprintf(svg, "</text>\n");
}

/* A formula label at world point p, moved by (dx, dy) pixels (dy down). */
static void math(v2 p, double dx, double dy, const char *anchor, const char *colour,
                 const char *s)
{
    text_s(add(scr(p), V(dx, dy)), anchor, colour, FS_MATH, 1, s);
}

static void math_small(v2 p, double dx, double dy, const char *anchor, const char *colour,
                       const char *s)
{
    text_s(add(scr(p), V(dx, dy)), anchor, colour, FS_SMALL + 1, 1, s);
}

/* A note in words at world point p, moved by (dx, dy) pixels. */
static void note(v2 p, double dx, double dy, const char *anchor, const char *colour,
                 const char *s)
{
    text_s(add(scr(p), V(dx, dy)), anchor, colour, FS_NOTE, 0, s);
}

/* ---------------------------------------------------------------- annotations */
/* The angle at c between the world directions a and b (less than 180
 * degrees), marked by an arc of r pixels; its label, if any, sits on the
 * bisector at lr pixels from c. */
static void angle(v2 c, v2 a, v2 b, double r, const char *colour, const char *label, double lr)
{
    double a0 = angle_of(a), a1 = angle_of(b);
    if (cross(a, b) < 0) {
        double t = a0;
        a0 = a1, a1 = t;
    }
    if (a1 < a0)
        a1 += 2 * M_PI;
    arc(c, r, a0, a1, colour, LW_GUIDE + 0.2, NULL);
    if (label) {
        double m = 0.5 * (a0 + a1);
        text_s(add(scr(c), V(lr * cos(m), -lr * sin(m))), "middle", colour, FS_MATH, 1, label);
    }
}

/* The right angle at c between the world directions a and b. */
static void right_angle(v2 c, v2 a, v2 b, double size, const char *colour)
{
    v2 s = scr(c), ua = unit(V(a.x, -a.y)), ub = unit(V(b.x, -b.y));
    v2 p[3] = {add(s, mul(ua, size)), add(s, add(mul(ua, size), mul(ub, size))),
               add(s, mul(ub, size))};
    fprintf(svg, "<path d=\"M%.1f %.1f L%.1f %.1f L%.1f %.1f\" fill=\"none\"", p[0].x, p[0].y,
            p[1].x, p[1].y, p[2].x, p[2].y);
    stroke_attrs(colour, LW_GUIDE, NULL);
    fprintf(svg, "/>\n");
}

/* A dimension line for the distance from a to b, drawn off pixels to the
 * left of the direction a -> b on screen (above it when a -> b runs to the
 * right), with extension lines and the label lo pixels further out. */
static void dimension(v2 a, v2 b, double off, const char *label, double lo, const char *anchor)
{
    v2 sa = scr(a), sb = scr(b);
    v2 u = unit(sub(sb, sa)), n = V(u.y, -u.x);
    v2 da = add(sa, mul(n, off)), db = add(sb, mul(n, off));
    double sgn = off < 0 ? -1 : 1;
    line_s(add(sa, mul(n, 4 * sgn)), add(da, mul(n, 4 * sgn)), GUIDE, LW_GUIDE, NULL);
    line_s(add(sb, mul(n, 4 * sgn)), add(db, mul(n, 4 * sgn)), GUIDE, LW_GUIDE, NULL);
    v2 mid = lerp(da, db, 0.5);
    arrow_s(mid, da, GUIDE, LW_GUIDE, 8, 3, NULL);
    arrow_s(mid, db, GUIDE, LW_GUIDE, 8, 3, NULL);
    if (label)
        text_s(add(mid, mul(n, lo)), anchor, INK, FS_MATH, 1, label);
}

/* Hatching under a surface running from a to b (world), on its right side
 * as seen walking from a to b: the inside of a solid. */
static void hatch(v2 a, v2 b, double spacing, double depth)
{
    v2 sa = scr(a), sb = scr(b), u = unit(sub(sb, sa)), n = V(-u.y, u.x);
    double l = len(sub(sb, sa));
    for (double t = spacing * 0.5; t < l; t += spacing) {
        v2 p = add(sa, mul(u, t));
        line_s(p, add(p, add(mul(n, depth), mul(u, -depth))), GUIDE, LW_GUIDE, NULL);
    }
}

/* ================================================================ chapter 01 */
/* The field of view from above: eye at the origin, x to the right and z up
 * the page (seen from +y in the left-handed frame), the image plane z = 1,
 * and w pixels of size s = 2 tan(alpha/2)/w with their centres. */
static void ch01_fov(const char *dir)
{
    const double alpha = 60 * DEG;
    const int w = 6;
    const double half = tan(alpha / 2), s = 2 * half / w;
    begin(dir, "ch01-diagram-fov", 600, 500, "The field of view seen from above");
    set_view(300, 460, 330);

    v2 eye = V(0, 0), left = V(-half, 1), right = V(half, 1);
    /* the plane, a little wider than the image, and the axes */
    line(V(-half - 0.12, 1), V(half + 0.12, 1), GUIDE, LW_GEOM, DASH);
    line(left, right, INK, LW_GEOM + 0.5, NULL);
    arrow(eye, V(0, 1.22), GUIDE, LW_GUIDE);
    math(V(0, 1.22), 10, 4, "start", GUIDE, "z");
    arrow(eye, V(0.3, 0), GUIDE, LW_GUIDE);
    math(V(0.3, 0), 0, 14, "middle", GUIDE, "x");
    /* the two edge rays and the angles */
    line(eye, left, INK, LW_GEOM, NULL);
    line(eye, right, INK, LW_GEOM, NULL);
    angle(eye, left, V(0, 1), 92, INK, "α/2", 110);
    angle(eye, left, right, 175, GUIDE, NULL, 0);
    math(eye, 0, -185, "middle", INK, "α");

    /* the pixels: boundaries at -tan(alpha/2) + i s, centres half a pixel in */
    for (int i = 0; i <= w; i++) {
        v2 b = V(-half + i * s, 1);
        line_s(add(scr(b), V(0, -7)), add(scr(b), V(0, 7)), INK, LW_GEOM, NULL);
    }
    for (int i = 0; i < w; i++) {
        v2 c = V(-half + (i + 0.5) * s, 1);
        point(c, C_RAY);
        char idx[16];
        snprintf(idx, sizeof idx, "%d", i);
        math_small(c, 0, -19, "middle", INK, idx);
    }
    math_small(V(-half, 1), -6, -19, "end", INK, "i =");

    /* one pixel ray, with its unit direction d ending short of the plane */
    const int pick = 4;
    v2 centre = V(-half + (pick + 0.5) * s, 1);
    line(eye, centre, C_RAY, LW_GUIDE, DASH);
    v2 d = unit(centre);
    arrow(eye, d, C_RAY, LW_VEC);
    math(mul(d, 0.72), 12, 4, "start", C_RAY, "d");
    math(centre, 8, 20, "start", C_RAY, "x_{ij}");

    /* dimensions: the half-pixel offset, one pixel, the width */
    dimension(left, V(-half + 0.5 * s, 1), 42, "s/2", 15, "middle");
    dimension(V(-half + (w - 1) * s, 1), right, 42, "s", 15, "middle");
    dimension(left, right, 82, "2 \\tan(α/2)", 15, "middle");

    /* the edges' coordinates and the plane's name */
    /* low enough that the edge rays have moved inwards, clear of the text */
    math(left, 30, 64, "end", INK, "x = −\\tan(α/2)");
    math(right, -30, 64, "start", INK, "x = \\tan(α/2)");
    note(V(half + 0.12, 1), 0, 16, "end", GUIDE, "z = 1");
    point(eye, INK);
    note(eye, 0, 20, "middle", INK, "eye (0, 0, 0)");
    finish();
}

/* The image plane seen from the eye: w x h square pixels of size s, pixel
 * (i, j) in column i and row j, and its centre half a pixel in. */
static void ch01_grid(const char *dir)
{
    const int w = 8, h = 5, pi = 6, pj = 3;
    const double p = 40; /* pixels per pixel, on the page */
    begin(dir, "ch01-diagram-grid", 600, 372, "The pixel grid on the image plane");
    /* World units here are pixel sizes s; the image's centre, where the z
     * axis pierces the plane, is the origin. */
    set_view(90 + p * w / 2, 64 + p * h / 2, p);
    double L = -w / 2.0, R = w / 2.0, T = h / 2.0, B = -h / 2.0;
    rect(V(L + pi, T - pj), V(L + pi + 1, T - pj - 1), F_BLUE, NULL, 0);
    for (int i = 0; i <= w; i++)
        line(V(L + i, T), V(L + i, B), INK, i == 0 || i == w ? LW_GEOM + 0.5 : LW_GUIDE, NULL);
    for (int j = 0; j <= h; j++)
        line(V(L, T - j), V(R, T - j), INK, j == 0 || j == h ? LW_GEOM + 0.5 : LW_GUIDE, NULL);
    for (int i = 0; i < w; i++) {
        char idx[16];
        snprintf(idx, sizeof idx, "%d", i);
        math_small(V(L + i + 0.5, T), 0, -14, "middle", INK, idx);
    }
    for (int j = 0; j < h; j++) {
        char idx[16];
        snprintf(idx, sizeof idx, "%d", j);
        math_small(V(L, T - j - 0.5), -14, 0, "middle", INK, idx);
    }
    math(V(R, T), 14, -14, "middle", INK, "i");
    math(V(L, B), -14, 14, "middle", INK, "j");

    /* the axes through the image's centre */
    arrow(V(0, 0), V(1.5, 0), GUIDE, LW_GUIDE + 0.4);
    math(V(1.5, 0), 0, -12, "middle", GUIDE, "x");
    arrow(V(0, 0), V(0, 1.5), GUIDE, LW_GUIDE + 0.4);
    math(V(0, 1.5), -12, 4, "middle", GUIDE, "y");
    point(V(0, 0), GUIDE);
    math_small(V(0, 0), 8, 13, "start", GUIDE, "(0, 0, 1)");

    /* pixel (i, j), its centre, and the centre's distances from the edges */
    v2 c = V(L + pi + 0.5, T - pj - 0.5);
    dimension(V(L, c.y), c, -0.0001, NULL, 0, "middle");
    dimension(V(c.x, T), c, 0.0001, NULL, 0, "middle");
    math(V(L + 2.0, c.y), 0, -11, "middle", INK, "(i + ½) s");
    math(V(c.x, T - 1.5), -7, 0, "end", INK, "(j + ½) s");
    point(c, C_RAY);
    v2 tag = V(R + 0.6, c.y + 1.4);
    line(c, tag, C_RAY, LW_GUIDE, NULL);
    math(tag, 4, 0, "start", C_RAY, "(x_{ij}, y_{ij}, 1)");
    v2 tag2 = V(R + 0.6, c.y - 0.9);
    line(V(L + pi + 0.8, T - pj - 0.85), tag2, INK, LW_GUIDE, NULL);
    char pixel[48];
    snprintf(pixel, sizeof pixel, "\\pixel (i, j) = (%d, %d)", pi, pj);
    math_small(tag2, 4, 0, "start", INK, pixel);

    /* the image's size */
    dimension(V(L, B), V(R, B), -24, "w s = 2 \\tan(α/2)", -14, "middle");
    dimension(V(L, B), V(L, T), 36, "h s", 10, "end");
    /* the centre's coordinates */
    math(V(0, B), 60, 78, "middle", INK,
         "x_{ij} = −\\tan(α/2) + (i + ½) s,    y_{ij} = h s/2 − (j + ½) s");
    finish();
}

/* ================================================================ chapter 02 */
/* The ray o + t d, the sphere (c, r), and the sheet's right triangles: the
 * closest approach at <c - o, d> along the ray, at distance D from c, and the
 * half-chord sqrt(r^2 - D^2) either side of it, ending at t0 and t1. */
static void ch02_sphere(const char *dir)
{
    v2 o = V(0, 0), d = V(1, 0), c = V(4.6, 1.4);
    const double r = 2.6;
    double a = dot(sub(c, o), d);                 /* along the ray to the closest point */
    v2 m = add(o, mul(d, a));                     /* the closest point */
    double D = len(sub(c, m));                    /* centre to line */
    double half = sqrt(r * r - D * D);            /* half the chord */
    double t0 = a - half, t1 = a + half;          /* the two hits */
    v2 p0 = add(o, mul(d, t0)), p1 = add(o, mul(d, t1));
    require(D < r && t0 > 0, "the ray enters the sphere in front of its origin");
    require(fabs(len(sub(p0, c)) - r) < 1e-12 && fabs(len(sub(p1, c)) - r) < 1e-12,
            "both hits lie on the sphere");

    begin(dir, "ch02-diagram-sphere", 600, 455, "A ray and a sphere");
    set_view(40, 262, 58);
    circle(c, r, F_BLUE, INK, LW_GEOM, NULL);
    /* the ray: dashed inside the sphere's chord, a unit d at the origin */
    v2 end = add(o, mul(d, 9.3));
    arrow(o, end, C_RAY, LW_GEOM);
    math(end, -2, -16, "end", C_RAY, "γ(t) = o + t d");
    arrow(o, d, C_RAY, LW_VEC + 0.8);
    math(lerp(o, d, 0.5), 0, -16, "middle", C_RAY, "d");
    /* the centre, the distance D and the radius to the far hit */
    line(c, m, INK, LW_GEOM, DASH);
    right_angle(m, sub(c, m), mul(d, -1), 10, INK);
    line(c, p1, INK, LW_GEOM, NULL);
    math(lerp(c, m, 0.4), -8, 0, "end", INK, "D");
    math(lerp(c, p1, 0.5), 10, -6, "start", INK, "r");
    point(c, INK);
    math(c, 0, -16, "middle", INK, "c");
    /* the points */
    point(o, INK);
    math(o, -6, 14, "end", INK, "o");
    point(m, INK);
    point(p0, C_RAY);
    point(p1, C_RAY);
    math(p0, -10, -14, "end", C_RAY, "γ(t_0)");
    math(p1, 9, 15, "start", C_RAY, "γ(t_1)");
    /* the half-chords, either side of the ray, inside the sphere */
    dimension(p0, m, 14, NULL, 0, "middle");
    dimension(m, p1, -14, NULL, 0, "middle");
    math_small(lerp(p0, m, 0.5), 0, -29, "middle", INK, "√(r^2 − D^2)");
    math_small(lerp(m, p1, 0.5), 0, 29, "middle", INK, "√(r^2 − D^2)");
    /* distances along the ray, under the sphere */
    double below = (r - D) * view_s; /* how far the sphere reaches below the ray */
    dimension(o, m, -(below + 26), "⟨c − o, d⟩", -14, "middle");
    dimension(o, p0, -(below + 62), "t_0", -14, "middle");
    dimension(o, p1, -(below + 98), "t_1", -14, "middle");
    finish();
}

/* ================================================================ chapter 03 */
/* At a surface point p: the normal n, the light direction l, the viewer v,
 * the mirror direction r = 2 n <n, l> - l and the half vector
 * h = (l + v) / |l + v|, all unit vectors, with their angles. */
static void ch03_vectors(const char *dir)
{
    v2 p = V(0, 0), n = V(0, 1);
    v2 l = polar((90 + 45) * DEG), v = polar(15 * DEG);
    v2 r = sub(mul(n, 2 * dot(n, l)), l);
    v2 h = unit(add(l, v));
    v2 foot = mul(n, dot(n, l)); /* <n, l> n: the part of l along n */
    require(fabs(len(r) - 1) < 1e-12, "r is a unit vector");
    /* the angle from r to v is twice the angle from n to h */
    require(fabs(acos(dot(r, v)) - 2 * acos(dot(n, h))) < 1e-12, "angle(r, v) = 2 angle(n, h)");

    begin(dir, "ch03-diagram-vectors", 600, 330, "The vectors at a surface point");
    set_view(300, 270, 215);
    line(V(-1.3, 0), V(1.3, 0), INK, LW_GEOM, NULL);
    hatch(V(-1.3, 0), V(1.3, 0), 14, 9);
    /* the mirror construction: l's part along n is kept, the rest flipped */
    line(l, r, GUIDE, LW_GUIDE, DASH);
    point(foot, GUIDE);
    math(foot, -10, -12, "end", GUIDE, "⟨n, l⟩ n");
    /* the angles */
    angle(p, n, l, 84, C_L, "φ", 101);
    angle(p, r, n, 84, C_R, "φ", 101);
    angle(p, v, r, 185, C_RAY, "α", 202);
    angle(p, h, n, 178, C_H, "α/2", 197);
    /* the vectors */
    arrow(p, n, C_N, LW_VEC);
    arrow(p, l, C_L, LW_VEC);
    arrow(p, r, C_R, LW_VEC);
    arrow(p, v, C_RAY, LW_VEC);
    arrow(p, h, C_H, LW_VEC);
    math(n, 0, -14, "middle", C_N, "n");
    math(l, -8, -8, "end", C_L, "l");
    math(r, 6, -12, "start", C_R, "r");
    math(v, 10, -2, "start", C_RAY, "v");
    math(h, 8, -12, "start", C_H, "h");
    note(l, -10, 12, "end", C_L, "to the light");
    note(v, 10, 16, "start", C_RAY, "to the eye");
    point(p, INK);
    math(p, 0, 16, "middle", INK, "p");
    finish();
}

/* A spot light at q with unit axis d and cut-off angle Theta_L: a point p
 * inside the cone at the angle Theta, cos Theta = <-l, d>, and a point
 * outside it; beside it the intensity cos^k Theta against Theta, with the
 * hard edge at Theta_L. */
static void ch03_spot(const char *dir)
{
    const double theta_l = 35 * DEG, k = 8;
    v2 q = V(1.6, 3.0), d = polar(-80 * DEG);
    double floor_y = 0;
    /* the cone's two edges, d turned by +-Theta_L, down to the floor */
    v2 e1 = polar(angle_of(d) + theta_l), e2 = polar(angle_of(d) - theta_l);
    v2 f1 = add(q, mul(e1, (floor_y - q.y) / e1.y)), f2 = add(q, mul(e2, (floor_y - q.y) / e2.y));
    v2 p = add(q, mul(polar(-100 * DEG), (floor_y - q.y) / sin(-100 * DEG)));
    v2 outside = V(5.0, floor_y);
    v2 l = unit(sub(q, p)), lo = unit(sub(q, outside));
    double theta = acos(dot(mul(l, -1), d)), theta_out = acos(dot(mul(lo, -1), d));
    require(theta < theta_l && theta_out > theta_l, "p inside the cone, the other point outside");

    begin(dir, "ch03-diagram-spot", 600, 300, "A spot light's cone");
    set_view(30, 250, 70);
    /* the lit cone */
    v2 cone[3] = {q, f1, f2};
    polygon(cone, 3, F_YELLOW, NULL, 0);
    line(V(-0.1, floor_y), V(5.4, floor_y), INK, LW_GEOM, NULL);
    hatch(V(-0.1, floor_y), V(5.4, floor_y), 14, 9);
    line(q, f1, C_L, LW_GEOM, NULL);
    line(q, f2, C_L, LW_GEOM, NULL);
    /* the axis, the direction to p, the angles */
    line(q, p, C_L, LW_GUIDE, DASH);
    line(q, outside, GUIDE, LW_GUIDE, DASH);
    angle(q, d, e1, 66, C_L, "Θ_L", 86);
    angle(q, d, sub(p, q), 118, INK, "Θ", 136);
    arrow(q, add(q, mul(d, 2.3)), INK, LW_VEC);
    math(add(q, mul(d, 2.3)), 12, -4, "start", INK, "d");
    /* the light's direction at p: the dashed line from q is -l */
    arrow(p, add(p, mul(l, 0.85)), C_L, LW_VEC);
    math(add(p, mul(l, 0.85)), -10, 2, "end", C_L, "l");
    math(lerp(q, p, 0.5), -10, 0, "end", C_L, "−l");
    point(q, C_L);
    math(q, -10, -6, "end", C_L, "q");
    point(p, INK);
    math(p, 0, 17, "middle", INK, "p");
    point(outside, INK);
    note(outside, 14, 19, "end", INK, "outside the cone: no light");

    /* the intensity against the angle: cos^k Theta inside, 0 outside */
    double gx = 432, gy = 205, gw = 140, gh = 150; /* the plot's origin and size */
    double th_max = 70 * DEG;
    line_s(V(gx, gy), V(gx + gw + 8, gy), INK, LW_GUIDE, NULL);
    line_s(V(gx, gy), V(gx, gy - gh - 8), INK, LW_GUIDE, NULL);
    fprintf(svg, "<path d=\"");
    int steps = 48;
    for (int i = 0; i <= steps; i++) {
        double th = theta_l * i / steps;
        fprintf(svg, "%s%.1f %.1f", i ? " L" : "M", gx + gw * th / th_max,
                gy - gh * pow(cos(th), k));
    }
    fprintf(svg, "\" fill=\"none\"");
    stroke_attrs(C_L, LW_VEC, NULL);
    fprintf(svg, "/>\n");
    double xe = gx + gw * theta_l / th_max, ye = gy - gh * pow(cos(theta_l), k);
    line_s(V(xe, ye), V(xe, gy), C_L, LW_GUIDE, DASH);
    line_s(V(xe, gy), V(gx + gw, gy), C_L, LW_VEC, NULL);
    line_s(V(xe, gy), V(xe, gy + 5), INK, LW_GUIDE, NULL);
    text_s(V(xe, gy + 17), "middle", INK, FS_MATH, 1, "Θ_L");
    text_s(V(gx + gw + 4, gy + 17), "end", INK, FS_MATH, 1, "Θ");
    line_s(V(gx - 5, gy - gh), V(gx, gy - gh), INK, LW_GUIDE, NULL);
    text_s(V(gx - 8, gy - gh), "end", INK, FS_SMALL, 1, "1");
    text_s(V(gx - 8, gy), "end", INK, FS_SMALL, 1, "0");
    text_s(V(gx + 0.3 * gw, gy - 0.92 * gh), "start", C_L, FS_MATH, 1, "\\cos^k Θ");
    text_s(V(xe + 6, gy - 30), "start", INK, FS_NOTE, 0, "hard edge");
    /* the point p on the curve */
    v2 at = V(gx + gw * theta / th_max, gy - gh * pow(cos(theta), k));
    line_s(at, V(at.x, gy), GUIDE, LW_GUIDE, DASH);
    fprintf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.6\" fill=\"%s\"/>\n", at.x, at.y, INK);
    text_s(add(at, V(-8, 8)), "end", INK, FS_MATH, 1, "p");
    text_s(V(gx + gw / 2, gy + 42), "middle", INK, FS_SMALL + 1, 1, "\\intensity / I,  k = 8");
    finish();
}

/* ================================================================ chapter 04 */
/* Barycentric coordinates as areas: the point p splits the triangle
 * p1 p2 p3 into three, and the one opposite p_i, of area w_i, gives
 * lambda_i = w_i / W. */
static void ch04_barycentric(const char *dir)
{
    v2 pt[3] = {V(0, 0), V(6.2, 0.7), V(2.3, 4.4)};
    /* p from chosen weights; the areas must give them back */
    const double chosen[3] = {0.25, 0.40, 0.35};
    v2 p = add(add(mul(pt[0], chosen[0]), mul(pt[1], chosen[1])), mul(pt[2], chosen[2]));
    double W = 0.5 * cross(sub(pt[1], pt[0]), sub(pt[2], pt[0]));
    double lambda[3];
    for (int i = 0; i < 3; i++) {
        v2 a = pt[(i + 1) % 3], b = pt[(i + 2) % 3];
        lambda[i] = 0.5 * cross(sub(a, p), sub(b, p)) / W; /* signed area w_i over W */
        require(fabs(lambda[i] - chosen[i]) < 1e-12, "lambda_i = w_i / W");
    }
    require(W > 0, "the triangle is counter-clockwise");

    begin(dir, "ch04-diagram-barycentric", 600, 400, "Barycentric coordinates as areas");
    set_view(95, 328, 68);
    const char *fill[3] = {F_ORANGE, F_GREEN, F_PURPLE};
    const char *ink[3] = {C_L, C_N, C_H};
    for (int i = 0; i < 3; i++) {
        v2 tri[3] = {p, pt[(i + 1) % 3], pt[(i + 2) % 3]};
        polygon(tri, 3, fill[i], NULL, 0);
        char label[64];
        snprintf(label, sizeof label, "w_%d", i + 1);
        v2 centroid = mul(add(add(tri[0], tri[1]), tri[2]), 1.0 / 3);
        math(centroid, 0, 0, "middle", INK, label);
    }
    for (int i = 0; i < 3; i++)
        line(p, pt[i], INK, LW_GUIDE, DASH);
    polygon(pt, 3, NULL, INK, LW_GEOM + 0.5);
    const double lx[3] = {-8, 10, 0}, ly[3] = {8, 6, -16};
    const char *anchor[3] = {"end", "start", "middle"};
    for (int i = 0; i < 3; i++) {
        char label[16];
        snprintf(label, sizeof label, "p_%d", i + 1);
        point(pt[i], INK);
        math(pt[i], lx[i], ly[i], anchor[i], ink[i], label);
    }
    point(p, INK);
    math(p, 0, 17, "middle", INK, "p");

    char line1[160];
    snprintf(line1, sizeof line1, "λ_i = w_i / W:   λ_1 = %.2f,  λ_2 = %.2f,  λ_3 = %.2f", lambda[0],
             lambda[1], lambda[2]);
    text_s(V(300, 360), "middle", INK, FS_MATH, 1, line1);
    text_s(V(300, 385), "middle", INK, FS_MATH, 1, "p = λ_1 p_1 + λ_2 p_2 + λ_3 p_3");
    finish();
}

/* The view of the 3D scene in the watertight figure: turned 35 degrees
 * about y and tilted 20 degrees down, so that x runs to the right, y up and
 * z into the page, up and to the right (the left-handed frame of chapter 01). */
static v2 view3(v3 p)
{
    const double yaw = 35 * DEG, tilt = 20 * DEG;
    double x = p.x * cos(yaw) + p.z * sin(yaw), depth = -p.x * sin(yaw) + p.z * cos(yaw);
    return V(x, p.y * cos(tilt) + depth * sin(tilt));
}

/* Sets the view so that the points fit the screen box (x0, y0)-(x1, y1). */
static void fit(const v2 *pts, int n, double x0, double y0, double x1, double y1)
{
    double lo_x = pts[0].x, hi_x = pts[0].x, lo_y = pts[0].y, hi_y = pts[0].y;
    for (int i = 1; i < n; i++) {
        lo_x = fmin(lo_x, pts[i].x), hi_x = fmax(hi_x, pts[i].x);
        lo_y = fmin(lo_y, pts[i].y), hi_y = fmax(hi_y, pts[i].y);
    }
    double scale = fmin((x1 - x0) / (hi_x - lo_x), (y1 - y0) / (hi_y - lo_y));
    set_view(0.5 * (x0 + x1) - scale * 0.5 * (lo_x + hi_x),
             0.5 * (y0 + y1) + scale * 0.5 * (lo_y + hi_y), scale);
}

/* The watertight test's change of space: before, a ray o + t d and a
 * triangle a b c in the world; after translating by -o, permuting the axes
 * so that d's largest component is z, and shearing, the ray is the z axis
 * and the test is whether (0, 0) is inside the sheared triangle A B C seen
 * along z, which the signs of the edge functions U, V, W decide (the names
 * are the chapter's code's). */
static void ch04_shear(const char *dir)
{
    v3 o = V3(1.5, 0.4, 0.0), d = unit3(V3(0.32, 0.22, 1));
    v3 hit = add3(o, mul3(d, 4.0));
    v3 tri[3] = {add3(hit, V3(-3.0, -1.6, 1.0)), add3(hit, V3(0.5, 2.8, -0.5)),
                 add3(hit, V3(2.9, -1.3, -0.8))};
    /* The chapter's shear: d's largest component is z here, so the axes
     * keep their order. */
    require(fabs(d.z) > fabs(d.x) && fabs(d.z) > fabs(d.y) && d.z > 0, "d runs along z");
    double sx = d.x / d.z, sy = d.y / d.z;
    v2 s[3];
    for (int i = 0; i < 3; i++) {
        v3 a = sub3(tri[i], o);
        s[i] = V(a.x - sx * a.z, a.y - sy * a.z);
    }
    v2 A = s[0], B = s[1], C = s[2];
    double U = C.x * B.y - C.y * B.x, Vv = A.x * C.y - A.y * C.x, Wv = B.x * A.y - B.y * A.x;
    require((U > 0 && Vv > 0 && Wv > 0) || (U < 0 && Vv < 0 && Wv < 0),
            "the edge functions agree: the ray hits");
    const char *sign = U > 0 ? ">" : "<", *other = U > 0 ? "<" : ">";

    begin(dir, "ch04-diagram-shear", 600, 345, "The watertight test's shear");
    /* ---- before: the world in 3D */
    text_s(V(150, 20), "middle", INK, FS_NOTE, 0, "before: a ray and a triangle");
    v3 far = add3(o, mul3(d, 7.0));
    v2 T[3], frame[5];
    for (int i = 0; i < 3; i++)
        T[i] = frame[i] = view3(tri[i]);
    frame[3] = view3(o), frame[4] = view3(far);
    /* the axes' directions, drawn apart in a corner */
    set_view(118, 312, 34);
    const char *axis[3] = {"x", "y", "z"};
    v3 axes[3] = {V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
    const double tx[3] = {8, 0, 6}, ty[3] = {4, -10, -8};
    for (int i = 0; i < 3; i++) {
        arrow(V(0, 0), view3(axes[i]), GUIDE, LW_GUIDE + 0.4);
        math(view3(axes[i]), tx[i], ty[i], i == 1 ? "middle" : "start", GUIDE, axis[i]);
    }
    fit(frame, 5, 50, 50, 290, 290);
    /* the ray behind the triangle first, so that the triangle covers it */
    arrow(view3(hit), view3(far), C_RAY, LW_GEOM);
    fprintf(svg, "<g opacity=\"0.85\">\n");
    polygon(T, 3, F_GREY, INK, LW_GEOM + 0.5);
    fprintf(svg, "</g>\n");
    line(view3(o), view3(hit), C_RAY, LW_GEOM, NULL);
    arrow(view3(o), view3(add3(o, mul3(d, 1.5))), C_RAY, LW_VEC + 0.8);
    math(view3(add3(o, mul3(d, 0.8))), 4, 14, "start", C_RAY, "d");
    point(view3(hit), C_RAY);
    point(view3(o), INK);
    math(view3(o), -8, 6, "end", INK, "o");
    /* the code's names: a, b, c in the world, A, B, C once sheared */
    const char *names[3] = {"a", "b", "c"}, *sheared[3] = {"A", "B", "C"};
    const double bx[3] = {-8, 0, 8}, by[3] = {6, -14, 8};
    const char *banchor[3] = {"end", "middle", "start"};
    for (int i = 0; i < 3; i++) {
        point(T[i], INK);
        math(T[i], bx[i], by[i], banchor[i], INK, names[i]);
    }

    /* ---- after: the sheared xy plane, the ray pierces it at the origin */
    line_s(V(312, 40), V(312, 320), GUIDE, LW_GUIDE, "2 4");
    text_s(V(460, 20), "middle", INK, FS_NOTE, 0, "after: the ray is the z axis");
    v2 box[5] = {A, B, C, V(0, 0), V(0, 0)};
    fit(box, 4, 360, 70, 560, 285);
    /* each edge's line, extended, and the sign its edge function would have
     * beyond it; the edge opposite A is U's, opposite B V's, opposite C W's */
    const char *fname[3] = {"U", "V", "W"};
    for (int i = 0; i < 3; i++) {
        v2 a = s[(i + 1) % 3], b = s[(i + 2) % 3];
        v2 u = unit(sub(b, a));
        line(sub(a, mul(u, 34 / view_s)), add(b, mul(u, 34 / view_s)), GUIDE, LW_GUIDE, DASH);
    }
    polygon(s, 3, F_GREY, INK, LW_GEOM + 0.5);
    for (int i = 0; i < 3; i++) {
        v2 a = s[(i + 1) % 3], b = s[(i + 2) % 3];
        v2 mid = lerp(a, b, 0.5);
        v2 nrm = unit(perp(sub(b, a)));
        if (dot(nrm, sub(mid, s[i])) < 0) /* away from the opposite corner */
            nrm = mul(nrm, -1);
        char label[32];
        snprintf(label, sizeof label, "%s %s 0", fname[i], other);
        math(add(mid, mul(nrm, 26 / view_s)), 0, 0, "middle", INK, label);
    }
    double axis_len = 52 / view_s;
    arrow(V(0, 0), V(axis_len, 0), GUIDE, LW_GUIDE + 0.4);
    math(V(axis_len, 0), 8, 2, "start", GUIDE, "x");
    arrow(V(0, 0), V(0, axis_len), GUIDE, LW_GUIDE + 0.4);
    math(V(0, axis_len), 0, -12, "middle", GUIDE, "y");
    /* the ray, going into the page: a circled cross */
    v2 c0 = scr(V(0, 0));
    fprintf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"7\" fill=\"#ffffff\"", c0.x, c0.y);
    stroke_attrs(C_RAY, LW_GEOM, NULL);
    fprintf(svg, "/>\n");
    line_s(add(c0, V(-4.9, -4.9)), add(c0, V(4.9, 4.9)), C_RAY, LW_GEOM, NULL);
    line_s(add(c0, V(-4.9, 4.9)), add(c0, V(4.9, -4.9)), C_RAY, LW_GEOM, NULL);
    char inside[48];
    snprintf(inside, sizeof inside, "U, V, W %s 0", sign);
    math(V(0, 0), 0, 24, "middle", C_RAY, inside);
    const double ax[3] = {-10, 0, -4}, ay[3] = {-10, -20, 18};
    const char *aanchor[3] = {"end", "middle", "end"};
    for (int i = 0; i < 3; i++) {
        point(s[i], INK);
        math(s[i], ax[i], ay[i], aanchor[i], INK, sheared[i]);
    }
    finish();
}

/* ================================================================ chapter 05 */
/* A closed curve as a path of many computed points, in world coordinates. */
static void ellipse(v2 c, double rx, double ry, const char *fill, const char *colour)
{
    fprintf(svg, "<path d=\"");
    for (int i = 0; i < 96; i++) {
        double a = 2 * M_PI * i / 96;
        v2 p = scr(add(c, V(rx * cos(a), ry * sin(a))));
        fprintf(svg, "%s%.1f %.1f", i ? " L" : "M", p.x, p.y);
    }
    fprintf(svg, "Z\" fill=\"%s\"", fill);
    stroke_attrs(colour, LW_GEOM, NULL);
    fprintf(svg, "/>\n");
}

/* Transforming a normal: on the unit circle at p, the tangent t and the
 * normal n; after the non-uniform scale M = diag(sx, sy) the circle is an
 * ellipse, M t is still tangent to it, M n is no longer perpendicular to
 * M t, and (M^-1)^T n = diag(1/sx, 1/sy) n is. */
static void ch05_normal(const char *dir)
{
    const double mx = 1.8, my = 0.6, theta = 55 * DEG, show = 0.85;
    v2 p = polar(theta), t = V(-sin(theta), cos(theta)), n = p;
    v2 Mp = V(mx * p.x, my * p.y), Mt = V(mx * t.x, my * t.y), Mn = V(mx * n.x, my * n.y);
    v2 good = V(n.x / mx, n.y / my); /* (M^-1)^T n: M is diagonal, so is its inverse */
    /* M t is tangent: it is the derivative of M (cos a, sin a) at a = theta */
    v2 tangent = V(-mx * sin(theta), my * cos(theta));
    require(fabs(cross(Mt, tangent)) < 1e-12, "M t is tangent to the ellipse");
    require(fabs(dot(good, Mt)) < 1e-12, "(M^-1)^T n is perpendicular to M t");
    double wrong = acos(dot(unit(Mn), unit(Mt))) / DEG;
    require(fabs(wrong - 90) > 20, "M n is visibly not perpendicular");

    begin(dir, "ch05-diagram-normal", 600, 300, "Transforming a normal");
    /* ---- before */
    set_view(112, 170, 70);
    text_s(V(112, 22), "middle", INK, FS_NOTE, 0, "before");
    circle(V(0, 0), 1, F_GREY, INK, LW_GEOM, NULL);
    right_angle(p, t, n, 10, INK);
    arrow(p, add(p, mul(unit(t), show)), C_T, LW_VEC);
    arrow(p, add(p, mul(unit(n), show)), C_N, LW_VEC);
    math(add(p, mul(unit(t), show)), -8, -8, "end", C_T, "t");
    math(add(p, mul(unit(n), show)), 8, -6, "start", C_N, "n");
    point(p, INK);
    math(p, -8, 12, "end", INK, "p");

    /* ---- the transform */
    arrow_s(V(212, 170), V(270, 170), INK, LW_GEOM, 10, 4, NULL);
    text_s(V(241, 152), "middle", INK, FS_MATH, 1, "M");
    text_s(V(241, 190), "middle", INK, FS_SMALL, 1, "\\diag(1.8, 0.6)");

    /* ---- after */
    set_view(420, 185, 70);
    text_s(V(420, 22), "middle", INK, FS_NOTE, 0, "after");
    ellipse(V(0, 0), mx, my, F_GREY, INK);
    right_angle(Mp, Mt, good, 10, C_N);
    arrow(Mp, add(Mp, mul(unit(Mt), show)), C_T, LW_VEC);
    arrow_s(scr(Mp), scr(add(Mp, mul(unit(Mn), show))), C_R, LW_VEC, 12, 4.5, DASH);
    arrow(Mp, add(Mp, mul(unit(good), show)), C_N, LW_VEC);
    math(add(Mp, mul(unit(Mt), show)), -6, -12, "end", C_T, "M t");
    math(add(Mp, mul(unit(Mn), show)), -4, 17, "start", C_R, "M n");
    math(add(Mp, mul(unit(good), show)), 0, -14, "middle", C_N, "(M^{−1})^T n");
    char note_text[64];
    snprintf(note_text, sizeof note_text, "\\angle(M n, M t) = %.0f°", wrong);
    text_s(V(420, 278), "middle", C_R, FS_SMALL + 1, 1, note_text);
    point(Mp, INK);
    math(Mp, -4, 16, "end", INK, "M p");
    finish();
}

/* ================================================================ chapter 06 */
/* The shadow ray's offset: the exact hit p lies on the surface, the
 * computed one is somewhere in an error box around p~; moving p~ along the
 * geometric normal by delta = |n_x| e_x + |n_y| e_y puts the whole box
 * behind the start of the shadow ray. Started at p~ itself, the ray can
 * hit the very surface it leaves. */
static void ch06_offset(const char *dir)
{
    v2 u = polar(10 * DEG), n = perp(u); /* the surface's direction and normal */
    v2 p = V(0, 0);                      /* the exact hit */
    v2 e = V(0.26, 0.22);                /* the error bound, per axis */
    v2 pc = add(p, V(0.2, -0.16));       /* the computed hit, below the surface */
    require(fabs(pc.x - p.x) <= e.x && fabs(pc.y - p.y) <= e.y, "p lies in the error box");
    double delta = fabs(n.x) * e.x + fabs(n.y) * e.y;
    v2 start = add(pc, mul(n, delta)); /* where the shadow ray starts */
    for (int i = 0; i < 4; i++) {      /* every corner of the box is behind it */
        v2 corner = add(pc, V(i & 1 ? e.x : -e.x, i & 2 ? e.y : -e.y));
        require(dot(sub(corner, pc), n) <= delta + 1e-12, "the box is behind the offset plane");
    }
    v2 l = unit(V(0.75, 1)); /* towards the light */
    double t_self = -dot(sub(pc, p), n) / dot(l, n); /* where the ray from p~ meets the surface */
    require(t_self > 0, "the ray from p~ crosses the surface");
    v2 self = add(pc, mul(l, t_self));

    begin(dir, "ch06-diagram-offset", 600, 350, "Offsetting the shadow ray's origin");
    set_view(250, 205, 250);
    /* the solid below the surface */
    v2 a = add(p, mul(u, -1.0)), b = add(p, mul(u, 1.4));
    v2 solid[4] = {a, b, add(b, mul(n, -0.5)), add(a, mul(n, -0.5))};
    polygon(solid, 4, F_GREY, NULL, 0);
    line(a, b, INK, LW_GEOM + 0.5, NULL);
    arrow(add(p, mul(u, -0.75)), add(add(p, mul(u, -0.75)), mul(n, 0.4)), C_N, LW_VEC);
    math(add(add(p, mul(u, -0.75)), mul(n, 0.4)), 10, -4, "start", C_N, "n_g");
    /* the error box, and the plane through the offset point that clears it */
    rect(sub(pc, e), add(pc, e), "none", C_R, LW_GUIDE + 0.3);
    line(add(start, mul(u, -0.55)), add(start, mul(u, 0.65)), GUIDE, LW_GUIDE, DASH);
    dimension(add(pc, V(-e.x, -e.y)), add(pc, V(e.x, -e.y)), -10, "2 e_x", -14, "middle");
    dimension(add(pc, V(e.x, -e.y)), add(pc, V(e.x, e.y)), -10, "2 e_y", -12, "start");
    /* the ray from p~ meets its own surface */
    line(pc, self, C_R, LW_GEOM, DASH);
    v2 ss = scr(self);
    line_s(add(ss, V(-5, -5)), add(ss, V(5, 5)), C_R, LW_GEOM + 0.5, NULL);
    line_s(add(ss, V(-5, 5)), add(ss, V(5, -5)), C_R, LW_GEOM + 0.5, NULL);
    v2 tag = V(pc.x + e.x + 0.2, self.y + 0.2);
    line(self, tag, C_R, LW_GUIDE, NULL);
    note(tag, 4, -2, "start", C_R, "self-intersection");
    /* the offset and the shadow ray */
    arrow(pc, start, C_N, LW_VEC);
    arrow(start, add(start, mul(l, 0.62)), C_L, LW_VEC);
    note(add(start, mul(l, 0.62)), 8, 4, "start", C_L, "shadow ray, to the light");
    point(p, INK);
    math(p, -8, 14, "end", INK, "p");
    point(pc, C_R);
    math(pc, 10, 12, "start", C_R, "p̃");
    point(start, C_N);
    math(start, -10, -8, "end", C_N, "p̃ + d n_g");
    text_s(V(20, 30), "start", INK, FS_MATH, 1, "d = |n_x| e_x + |n_y| e_y");
    finish();
}

/* The mirror direction for an incoming direction i (towards the surface):
 * r = i - 2 n <n, i>, drawn as i followed by -2 <n, i> n. */
static void ch06_reflect(const char *dir)
{
    v2 n = V(0, 1), i = polar(-50 * DEG);
    double ni = dot(n, i);
    v2 r = sub(i, mul(n, 2 * ni));
    require(fabs(len(r) - 1) < 1e-12 && fabs(dot(r, n) + ni) < 1e-12, "r mirrors i about n");
    v2 p = V(0, 0);

    begin(dir, "ch06-diagram-reflect", 600, 310, "The reflection vector");
    set_view(300, 165, 125);
    line(V(-1.8, 0), V(1.8, 0), INK, LW_GEOM, NULL);
    hatch(V(-1.8, 0), V(1.8, 0), 14, 9);
    /* i arriving at p, r leaving it */
    arrow(sub(p, i), p, C_RAY, LW_VEC);
    math(lerp(sub(p, i), p, 0.4), -10, -8, "end", C_RAY, "i");
    arrow(p, r, C_R, LW_VEC);
    math(r, 10, -4, "start", C_R, "r");
    arrow(p, mul(n, 0.7), C_N, LW_VEC);
    math(mul(n, 0.7), 0, -14, "middle", C_N, "n");
    /* the construction: i again from p, then -2 <n, i> n back up to r */
    arrow_s(scr(p), scr(i), C_RAY, LW_GUIDE + 0.3, 10, 4, DASH);
    math(lerp(p, i, 0.55), -10, 6, "end", C_RAY, "i");
    arrow(i, r, C_N, LW_GUIDE + 0.6);
    math(lerp(i, r, 0.22), 10, 0, "start", C_N, "−2 ⟨n, i⟩ n");
    line(V(0, ni), i, GUIDE, LW_GUIDE, DASH);
    point(V(0, ni), GUIDE);
    math(V(0, ni), -8, 0, "end", GUIDE, "⟨n, i⟩ n");
    line(V(0, ni), V(0, 0), GUIDE, LW_GUIDE, DASH);
    angle(p, mul(i, -1), n, 46, INK, "θ", 62);
    angle(p, n, r, 46, INK, "θ", 62);
    point(p, INK);
    math(p, -6, 16, "end", INK, "p");
    text_s(V(20, 30), "start", INK, FS_MATH, 1, "r = i − 2 n ⟨n, i⟩");
    finish();
}

/* ================================================================ chapter 07 */
/* Refraction at an interface between media of indices eta1 (above) and
 * eta2 (below): the incident direction i, the normal n, the mirror
 * direction r and the transmitted direction t = eta i + (eta c1 - c2) n,
 * eta = eta1/eta2, c1 = -<n, i>, c2 = sqrt(1 - eta^2 (1 - c1^2)), which
 * obeys Snell's law eta1 sin theta1 = eta2 sin theta2. (The chapter writes
 * eta for the indices, since n is the normal.) */
static void ch07_refraction(const char *dir)
{
    const double n1 = 1.0, n2 = 1.5, theta1 = 50 * DEG;
    v2 n = V(0, 1), i = V(sin(theta1), -cos(theta1));
    double eta = n1 / n2, c1 = -dot(n, i), c2 = sqrt(1 - eta * eta * (1 - c1 * c1));
    v2 t = add(mul(i, eta), mul(n, eta * c1 - c2));
    v2 r = add(i, mul(n, 2 * c1));
    double theta2 = acos(dot(t, mul(n, -1)));
    require(fabs(n1 * sin(theta1) - n2 * sin(theta2)) < 1e-12, "Snell's law");
    require(fabs(len(t) - 1) < 1e-12, "t is a unit vector");
    v2 p = V(0, 0);

    begin(dir, "ch07-diagram-refraction", 600, 335, "Refraction");
    set_view(300, 170, 140);
    rect(V(-2.1, 0), V(2.1, -1.15), F_BLUE, NULL, 0);
    line(V(-2.1, 0), V(2.1, 0), INK, LW_GEOM, NULL);
    line(V(0, 1.1), V(0, -1.1), GUIDE, LW_GUIDE, DASH);
    arrow(sub(p, i), p, C_RAY, LW_VEC);
    math(lerp(sub(p, i), p, 0.3), -11, 13, "middle", C_RAY, "i");
    arrow(p, r, C_R, LW_VEC);
    math(r, 10, -2, "start", C_R, "r");
    arrow(p, t, C_T, LW_VEC);
    math(t, 10, 4, "start", C_T, "t");
    arrow(p, mul(n, 0.75), C_N, LW_VEC);
    math(mul(n, 0.75), 10, -8, "start", C_N, "n");
    angle(p, mul(i, -1), n, 62, C_RAY, "θ_1", 80);
    angle(p, n, r, 62, C_R, "θ_1", 80);
    angle(p, mul(n, -1), t, 62, C_T, "θ_2", 80);
    point(p, INK);
    math(V(-2.1, 0.0), 10, -16, "start", INK, "η_1 = 1.0");
    math(V(-2.1, 0.0), 10, 18, "start", INK, "η_2 = 1.5");
    text_s(V(20, 30), "start", INK, FS_MATH, 1, "η_1 \\sin θ_1 = η_2 \\sin θ_2");
    finish();
}

/* The sheet's construction of the refracted direction: the incident
 * direction i is the sum of a = n<n, i>, along the normal, and b = i - a,
 * along the surface; the refracted direction is t = alpha a + beta b with
 * beta = eta1/eta2 and alpha = cos theta2 / cos theta1. Each sum is drawn
 * head to tail: i's above the surface (a, then b), t's below (beta b, then
 * alpha a). */
static void ch07_construction(const char *dir)
{
    const double eta = 1.0 / 1.5, theta1 = 50 * DEG;
    v2 n = V(0, 1), i = V(sin(theta1), -cos(theta1));
    v2 a = mul(n, dot(n, i)), b = sub(i, a);
    double beta = eta, radicand = 1 + (1 - beta * beta) * dot(b, b) / dot(a, a);
    double alpha = sqrt(radicand);
    v2 t = add(mul(a, alpha), mul(b, beta));
    double c1 = -dot(n, i), c2 = sqrt(1 - eta * eta * (1 - c1 * c1));
    v2 t_std = add(mul(i, eta), mul(n, eta * c1 - c2));
    require(fabs(len(t) - 1) < 1e-12, "t is a unit vector");
    require(len(sub(t, t_std)) < 1e-12, "the sheet's t is the standard one");
    require(fabs(alpha - c2 / c1) < 1e-12, "alpha = cos theta2 / cos theta1");
    v2 p = V(0, 0), s = sub(p, i); /* the incident ray runs from s to p */

    begin(dir, "ch07-diagram-construction", 600, 360, "The sheet's refraction");
    set_view(330, 175, 170);
    rect(V(-1.85, 0), V(1.6, -1.1), F_BLUE, NULL, 0);
    line(V(-1.85, 0), V(1.6, 0), INK, LW_GEOM, NULL);
    line(V(0, 0.95), V(0, -1.05), GUIDE, LW_GUIDE, DASH);
    /* i = a + b, head to tail above the surface */
    arrow(s, p, C_RAY, LW_VEC);
    math(lerp(s, p, 0.55), 8, -10, "start", C_RAY, "i");
    arrow(s, add(s, a), C_N, LW_VEC - 0.4);
    math(lerp(s, add(s, a), 0.5), -8, 0, "end", C_N, "a = n ⟨n, i⟩");
    arrow(add(s, a), p, C_R, LW_VEC - 0.4);
    math(lerp(add(s, a), p, 0.45), 0, 16, "middle", C_R, "b = i − a");
    /* t = beta b + alpha a, head to tail below it */
    arrow(p, add(p, mul(b, beta)), C_R, LW_VEC - 0.4);
    math(lerp(p, add(p, mul(b, beta)), 0.5), 0, -14, "middle", C_R, "β b");
    arrow(add(p, mul(b, beta)), add(p, t), C_N, LW_VEC - 0.4);
    math(lerp(add(p, mul(b, beta)), add(p, t), 0.5), 8, 0, "start", C_N, "α a");
    arrow(p, add(p, t), C_T, LW_VEC);
    math(lerp(p, add(p, t), 0.62), -10, 6, "end", C_T, "t");
    arrow(p, mul(n, 0.6), C_N, LW_VEC);
    math(mul(n, 0.6), 10, -6, "start", C_N, "n");
    point(p, INK);
    math(V(1.6, 0.0), -10, -16, "end", INK, "η_1 = 1.0");
    math(V(1.6, 0.0), -10, 18, "end", INK, "η_2 = 1.5");
    text_s(V(20, 30), "start", INK, FS_MATH, 1, "t = α a + β b");
    text_s(V(20, 56), "start", INK, FS_MATH, 1, "β = η_1 / η_2,  α = \\cos θ_2 / \\cos θ_1");
    finish();
}


/* ---------------------------------------------------------------- main */
typedef struct {
    const char *name;
    void (*draw)(const char *dir);
} diagram;

static const diagram diagrams[] = {
    {"ch01-diagram-fov", ch01_fov},
    {"ch01-diagram-grid", ch01_grid},
    {"ch02-diagram-sphere", ch02_sphere},
    {"ch03-diagram-vectors", ch03_vectors},
    {"ch03-diagram-spot", ch03_spot},
    {"ch04-diagram-barycentric", ch04_barycentric},
    {"ch04-diagram-shear", ch04_shear},
    {"ch05-diagram-normal", ch05_normal},
    {"ch06-diagram-offset", ch06_offset},
    {"ch06-diagram-reflect", ch06_reflect},
    {"ch07-diagram-refraction", ch07_refraction},
    {"ch07-diagram-construction", ch07_construction},
};

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s OUTDIR [NAME...]\n", argv[0]);
        return 2;
    }
    size_t count = sizeof diagrams / sizeof diagrams[0];
    for (size_t i = 0; i < count; i++) {
        int wanted = argc == 2;
        for (int a = 2; a < argc; a++)
            wanted |= strcmp(argv[a], diagrams[i].name) == 0;
        if (wanted)
            diagrams[i].draw(argv[1]);
    }
    for (int a = 2; a < argc; a++) {
        int known = 0;
        for (size_t i = 0; i < count; i++)
            known |= strcmp(argv[a], diagrams[i].name) == 0;
        if (!known) {
            fprintf(stderr, "%s: no diagram named %s\n", argv[0], argv[a]);
            return 2;
        }
    }
    return 0;
}
