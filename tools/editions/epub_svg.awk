# epub_svg.awk -- an SVG figure as EPUB's SVG 1.1 allows it, drawn the same.
#
# Usage: awk -f tools/editions/epub_svg.awk FIGURE.svg > COPY.svg   (tools/editions/epub.sh)
# Two things that browsers draw but EPUB's schema refuses, changed in the
# EPUB's copy only (the figures and the HTML book keep theirs):
#   paint-order="V"  (tools/diagrams: text on a white halo) becomes the
#                    same property in the tag's style, style="paint-order:V";
#   a repeated id    (gnuplot's multiplot numbers each plot's groups from
#                    gnuplot_plot_1 again) becomes ID-2, ID-3, ... from its
#                    second use on; gnuplot never refers to these ids.

# The tag of text that holds position at: from the last "<" before it to
# the first ">" after it.
function tag_bounds(text, at,    i) {
    tag_start = 1
    for (i = at; i > 0; i--) if (substr(text, i, 1) == "<") { tag_start = i; break }
    tag_end = length(text)
    i = index(substr(text, at), ">")
    if (i > 0) tag_end = at + i - 1
}

function fix_paint_order(text,    value, before, after, tag, at) {
    while (match(text, /[ \t]paint-order="[^"]*"/)) {
        value = substr(text, RSTART + 14, RLENGTH - 15)
        before = substr(text, 1, RSTART - 1)
        after = substr(text, RSTART + RLENGTH)
        tag_bounds(before after, RSTART)
        tag = substr(before after, tag_start, tag_end - tag_start + 1)
        at = index(tag, " style=\"")
        if (at > 0) {
            text = before after
            at += tag_start - 1 + 7
            text = substr(text, 1, at) "paint-order:" value ";" substr(text, at + 1)
        } else {
            text = before " style=\"paint-order:" value "\"" after
        }
    }
    return text
}

function fix_ids(text,    out, whole, lead, quote, id) {
    out = ""
    while (match(text, /(^|[ \t])id=("[^"]*"|'[^']*')/)) {
        whole = substr(text, RSTART, RLENGTH)
        out = out substr(text, 1, RSTART - 1)
        text = substr(text, RSTART + RLENGTH)
        lead = substr(whole, 1, index(whole, "id=") - 1)
        quote = substr(whole, length(whole), 1)
        id = substr(whole, length(lead) + 5, length(whole) - length(lead) - 5)
        if (++uses[id] > 1) id = id "-" uses[id]
        out = out lead "id=" quote id quote
    }
    return out text
}

{ print fix_ids(fix_paint_order($0)) }
