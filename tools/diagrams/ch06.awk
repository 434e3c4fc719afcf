# ch06.awk: the diagrams of chapter 06, as SVG on standard output.
#   awk -v which=shadow-ray -f tools/diagrams/ch06.awk > figures/ch06-diagram-shadow-ray.svg
#   awk -v which=reflection -f tools/diagrams/ch06.awk > figures/ch06-diagram-reflection.svg
# shadow-ray: a surface, the computed hit point below it, its error box, the
# offset along the geometric normal past the box, and the shadow ray to the
# light. reflection: i, n and r = i - 2 n <n, i>, with equal angles.
function line(x1, y1, x2, y2, style) {
    printf "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" %s/>\n", x1, y1, x2, y2, style
}
function arrow(x1, y1, x2, y2, color,    a, hx, hy) {
    line(x1, y1, x2, y2, "stroke=\"" color "\" stroke-width=\"2.5\"")
    a = atan2(y2 - y1, x2 - x1)
    hx = 12 * cos(a); hy = 12 * sin(a)
    printf "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\"/>\n", x2, y2, \
        x2 - hx - 0.45 * hy, y2 - hy + 0.45 * hx, x2 - hx + 0.45 * hy, y2 - hy - 0.45 * hx, color
}
function text(x, y, s, extra) {
    printf "<text x=\"%.1f\" y=\"%.1f\" font-family=\"Helvetica, sans-serif\" font-size=\"15\" %s>%s</text>\n", x, y, extra, s
}
function header(w, h) {
    printf "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n", w, h, w, h
    printf "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", w, h
}
function shadow_ray() {
    header(560, 300)
    # the surface, y = 200, with its inside shaded
    printf "<rect x=\"20\" y=\"200\" width=\"520\" height=\"80\" fill=\"#e8e4dc\"/>\n"
    line(20, 200, 540, 200, "stroke=\"#555\" stroke-width=\"2\"")
    text(30, 270, "inside the object", "fill=\"#777\"")
    # the computed point p, a little below the surface, and its error box
    px = 200; py = 206
    printf "<rect x=\"%d\" y=\"%d\" width=\"36\" height=\"24\" fill=\"none\" stroke=\"#d95f02\" stroke-dasharray=\"4,3\"/>\n", px - 18, py - 12
    printf "<circle cx=\"%d\" cy=\"%d\" r=\"4\" fill=\"#d95f02\"/>\n", px, py
    text(px - 110, py + 34, "computed p, error box p &#177; e", "fill=\"#d95f02\"")
    # the offset along n_g to just past the box
    ox = px; oy = py - 22
    arrow(px, py, ox, oy + 3, "#1b9e77")
    printf "<circle cx=\"%d\" cy=\"%d\" r=\"4\" fill=\"#1b9e77\"/>\n", ox, oy
    text(ox + 8, oy - 4, "origin p + d n_g", "fill=\"#1b9e77\"")
    # the shadow ray to the light, and the light
    lx = 480; ly = 40
    arrow(ox, oy, lx - 12, ly + 9, "#333")
    printf "<circle cx=\"%d\" cy=\"%d\" r=\"11\" fill=\"#f2c14e\" stroke=\"#a67c00\"/>\n", lx, ly
    text(lx - 40, ly - 18, "light", "")
    text(330, 112, "shadow ray, t in (0, r)", "fill=\"#333\"")
    # a naive ray from p itself meets the surface again at a tiny t
    line(px, py, px + 16, py - 6, "stroke=\"#c00\" stroke-width=\"2\" stroke-dasharray=\"3,2\"")
    printf "<circle cx=\"%d\" cy=\"%d\" r=\"3\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/>\n", px + 17, 200
    text(px + 30, 222, "from p itself: a self-hit", "fill=\"#c00\"")
    text(20, 30, "d = &#10216;|n_g|, e&#10217;: the error box's reach along the normal", "")
    print "</svg>"
}
function reflection(   cx, cy, len, th, ix, iy, rx, ry) {
    header(560, 300)
    cx = 280; cy = 240; len = 170; th = 50 * atan2(1, 1) / 45   # 50 degrees
    printf "<rect x=\"20\" y=\"%d\" width=\"520\" height=\"50\" fill=\"#dfe9f3\"/>\n", cy
    line(20, cy, 540, cy, "stroke=\"#555\" stroke-width=\"2\"")
    text(30, cy + 35, "mirror", "fill=\"#777\"")
    # i arrives travelling towards the surface; r leaves at the same angle
    ix = cx - len * sin(th); iy = cy - len * cos(th)
    rx = cx + len * sin(th); ry = cy - len * cos(th)
    arrow(ix, iy, cx - 4, cy - 4, "#d95f02")
    arrow(cx, cy, rx, ry, "#1b9e77")
    arrow(cx, cy, cx, cy - 120, "#333")
    text(30, iy - 12, "i (the ray's direction)", "fill=\"#d95f02\"")
    text(rx - 30, ry - 14, "r = i &#8722; 2n&#10216;n, i&#10217;", "fill=\"#1b9e77\"")
    text(cx + 8, cy - 110, "n", "fill=\"#333\"")
    # the equal angles
    printf "<path d=\"M %.1f %.1f A 50 50 0 0 1 %.1f %.1f\" fill=\"none\" stroke=\"#d95f02\"/>\n", cx - 50 * sin(th), cy - 50 * cos(th), cx, cy - 50
    printf "<path d=\"M %.1f %.1f A 50 50 0 0 1 %.1f %.1f\" fill=\"none\" stroke=\"#1b9e77\"/>\n", cx, cy - 58, cx + 58 * sin(th), cy - 58 * cos(th)
    text(cx - 42, cy - 62, "&#952;", "fill=\"#d95f02\"")
    text(cx + 20, cy - 68, "&#952;", "fill=\"#1b9e77\"")
    text(20, 28, "&#10216;n, r&#10217; = &#8722;&#10216;n, i&#10217;: the same angle, on the other side;", "")
    text(20, 48, "r is a sum of i and n, so it lies in their plane", "")
    print "</svg>"
}
BEGIN {
    if (which == "shadow-ray") shadow_ray()
    else if (which == "reflection") reflection()
    else { print "ch06.awk: which= shadow-ray or reflection" > "/dev/stderr"; exit 1 }
}
