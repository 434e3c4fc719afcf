/* pixel.h: how many rays a pixel gets, and where: the settings of the
 * pixel statement (chapter 13). Data only: antialias.h places the rays,
 * render.c traces them. */
#ifndef PIXEL_H
#define PIXEL_H

#include <stdbool.h>

typedef enum {
    PIXEL_CENTER,   /* one ray through the centre: chapters 1 to 12 */
    PIXEL_GRID,     /* side x side rays at the centres of equal cells */
    PIXEL_JITTERED, /* one ray at a random point of each cell */
    PIXEL_ADAPTIVE, /* Whitted's: the corners, divided where they differ */
} pixel_pattern;

typedef enum { FILTER_BOX, FILTER_TENT } pixel_filter;

/* <<pixel limits>> ch13 */
#define PIXEL_MAX_SIDE 16 /* 256 rays: as many levels as an 8-bit code */
#define PIXEL_MAX_DEPTH 4 /* 16 x 16 cells: the same resolution */
/* The most rays one pixel may cost: the 17 x 17 points of its finest
 * division, or the grid's 256. */
#define PIXEL_MAX_RAYS ((PIXEL_MAX_SIDE + 1) * (PIXEL_MAX_SIDE + 1))
/* Primary rays of one image at the worst: two billion, hours of a render,
 * and room for the default adaptive pattern's 77 rays a pixel on the
 * largest image (2^24 pixels); a setting that asks for more is a mistake,
 * not a wish. */
#define PIXEL_RAY_BUDGET (1LL << 31)
/* Rays of one image, all kinds counted, at the worst: 2^36, hours of one
 * core; each primary ray's tree gets its share. */
#define IMAGE_RAY_BUDGET (1LL << 36)
/* Read off this chapter's chart: see "Speed against accuracy". */
#define PIXEL_DEFAULT_THRESHOLD 0.05

typedef struct {
    pixel_pattern pattern;
    int side;              /* grid, jittered: side x side rays */
    pixel_filter filter;   /* grid, jittered */
    double threshold;      /* adaptive: sRGB difference left undivided */
    int depth, min_depth;  /* adaptive: the deepest division, the least */
    bool linear;           /* adaptive: compare linear light instead */
    bool jittered_corners; /* adaptive: each point moved at random */
    int heatmap;           /* > 0: draw rays per pixel, white at this */
} pixel_sampling;

/* Chapter 1's one ray through the centre, and the other patterns'
 * defaults for when they are chosen. */
#define PIXEL_DEFAULTS                                                    \
    ((pixel_sampling){.pattern = PIXEL_CENTER, .side = 4,                 \
                      .threshold = PIXEL_DEFAULT_THRESHOLD, .depth = 3})

#endif
