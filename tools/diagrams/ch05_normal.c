/* ch05_normal.c: chapter 05's diagram of the normal transform.
 *
 * Usage: ch05_normal > figures/ch05-diagram-normal.svg
 *
 * Left: the unit circle, a point p on it at 45 degrees, its normal n and
 * tangent t. Right: the same after A = diag(2, 1), which makes the circle
 * an ellipse: the point A p, the tangent A t, the sheet's A n, and the
 * inverse transpose (A^-1)^T n. Every point and direction is computed from
 * A; only where a label sits is chosen by hand, as an offset in pixels.
 * The angle between the two normals, acos(0.8) = 36.87 degrees, is
 * computed too and printed on the arc. Output is rounded to 0.1 px. */
#include <math.h>
#include <stdio.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define INK "#222222"
#define GUIDE "#8a8a8a"
#define C_TANGENT "#0072b2"
#define C_SHEET "#d0361a"  /* the sheet's M n: wrong */
#define C_NORMAL "#008a60" /* the inverse transpose: right */
#define SCALE 55.0         /* pixels per unit */
#define ARROW 1.25         /* length of the drawn normals and tangents */

typedef struct {
    double x, y;
} v2;

static const double A[2][2] = {{2, 0}, {0, 1}};

static v2 apply(const double m[2][2], v2 v)
{
    return (v2){m[0][0] * v.x + m[0][1] * v.y, m[1][0] * v.x + m[1][1] * v.y};
}

/* (A^-1)^T v: for a 2x2 matrix, the cofactor matrix over det. */
static v2 inverse_transpose(const double m[2][2], v2 v)
{
    double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    double c[2][2] = {{m[1][1] / det, -m[1][0] / det}, {-m[0][1] / det, m[0][0] / det}};
    return apply(c, v);
}

static v2 unit(v2 v)
{
    double l = hypot(v.x, v.y);
    return (v2){v.x / l, v.y / l};
}

static double cx, cy; /* the panel's origin on the page */

static v2 page(v2 p) { return (v2){cx + SCALE * p.x, cy - SCALE * p.y}; }

/* An arrow from from along dir, in color, with the marker head-ID. */
static void arrow(v2 from, v2 dir, const char *color, const char *id, const char *label,
                  double lx, double ly)
{
    v2 a = page(from), b = page((v2){from.x + ARROW * dir.x, from.y + ARROW * dir.y});
    printf("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
           "stroke-width=\"2.2\" marker-end=\"url(#head-%s)\"/>\n",
           a.x, a.y, b.x, b.y, color, id);
    printf("<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-family=\"serif\" font-size=\"17\" "
           "font-style=\"italic\">%s</text>\n",
           b.x + lx, b.y + ly, color, label);
}

static void curve(const double m[2][2])
{
    printf("<path d=\"");
    for (int k = 0; k <= 72; k++) {
        double th = 2 * M_PI * k / 72;
        v2 p = page(apply(m, (v2){cos(th), sin(th)}));
        printf("%c%.1f %.1f", k ? 'L' : 'M', p.x, p.y);
    }
    printf("Z\" fill=\"#eeeeee\" stroke=\"" INK "\" stroke-width=\"1.5\"/>\n");
}

static void marker(const char *id, const char *color)
{
    printf("<marker id=\"head-%s\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
           "markerHeight=\"7\" orient=\"auto\"><path d=\"M0 0L10 5L0 10z\" fill=\"%s\"/></marker>\n",
           id, color);
}

int main(void)
{
    const double I[2][2] = {{1, 0}, {0, 1}};
    v2 p = {cos(M_PI / 4), sin(M_PI / 4)}, n = p, t = {-p.y, p.x};
    v2 Ap = apply(A, p), At = unit(apply(A, t));
    v2 sheet = unit(apply(A, n)), right = unit(inverse_transpose(A, n));
    double angle = acos(sheet.x * right.x + sheet.y * right.y) * 180 / M_PI;
    double off_tangent = acos(fabs(sheet.x * At.x + sheet.y * At.y)) * 180 / M_PI;
    printf("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"300\" "
           "viewBox=\"0 0 720 300\">\n<title>The normal transform: M n against the inverse "
           "transpose</title>\n<rect width=\"720\" height=\"300\" fill=\"#ffffff\"/>\n<defs>\n");
    marker("t", C_TANGENT), marker("s", C_SHEET), marker("n", C_NORMAL), marker("g", GUIDE);
    printf("</defs>\n");
    /* left: the circle */
    cx = 150, cy = 160;
    curve(I);
    v2 q = page(p);
    printf("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"" INK "\"/>\n", q.x, q.y);
    arrow(p, n, C_NORMAL, "n", "n", 6, 4);
    arrow(p, (v2){-t.x, -t.y}, C_TANGENT, "t", "t", -4, 18);
    printf("<text x=\"%.1f\" y=\"285\" font-family=\"sans-serif\" font-size=\"13.5\" fill=\"" INK
           "\" text-anchor=\"middle\">the unit circle: n is perpendicular to t</text>\n", cx);
    /* the map between the panels */
    printf("<text x=\"275\" y=\"88\" font-family=\"serif\" font-size=\"17\" fill=\"" INK
           "\"><tspan font-style=\"italic\">A</tspan> = diag(2, 1)</text>\n"
           "<line x1=\"280\" y1=\"100\" x2=\"355\" y2=\"100\" stroke=\"" GUIDE
           "\" stroke-width=\"1\" marker-end=\"url(#head-g)\"/>\n");
    /* right: the ellipse */
    cx = 470, cy = 160;
    curve(A);
    q = page(Ap);
    printf("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"" INK "\"/>\n", q.x, q.y);
    arrow(Ap, (v2){-At.x, -At.y}, C_TANGENT, "t", "A t", -24, 20);
    arrow(Ap, sheet, C_SHEET, "s", "A n (sheet)", 4, 6);
    arrow(Ap, right, C_NORMAL, "n", "(A\u207b\u00b9)\u1d40 n", -62, -6);
    /* the arc between the two normals, with the computed angle */
    double r = 0.55, a0 = atan2(sheet.y, sheet.x), a1 = atan2(right.y, right.x);
    v2 s0 = page((v2){Ap.x + r * cos(a0), Ap.y + r * sin(a0)});
    v2 s1 = page((v2){Ap.x + r * cos(a1), Ap.y + r * sin(a1)});
    printf("<path d=\"M%.1f %.1fA%.1f %.1f 0 0 0 %.1f %.1f\" fill=\"none\" stroke=\"" INK
           "\" stroke-width=\"1\"/>\n",
           s0.x, s0.y, r * SCALE, r * SCALE, s1.x, s1.y);
    v2 mid = page((v2){Ap.x + (r + 0.22) * cos((a0 + a1) / 2), Ap.y + (r + 0.22) * sin((a0 + a1) / 2)});
    printf("<text x=\"%.1f\" y=\"%.1f\" font-family=\"sans-serif\" font-size=\"13\" fill=\"" INK
           "\">%.1f\u00b0</text>\n", mid.x - 8, mid.y + 4, angle);
    printf("<text x=\"%.1f\" y=\"285\" font-family=\"sans-serif\" font-size=\"13.5\" fill=\"" INK
           "\" text-anchor=\"middle\">after A: A n is %.1f\u00b0 from perpendicular to A t</text>\n",
           cx, 90 - off_tangent);
    printf("</svg>\n");
    return 0;
}
