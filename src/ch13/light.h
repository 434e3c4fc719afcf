/* light.h: point, directional and spot lights (chapter 3). */
#ifndef LIGHT_H
#define LIGHT_H

#include "vec.h"

typedef enum {
    LIGHT_POINT,
    LIGHT_DIRECTIONAL,
    LIGHT_SPOT,
    /* <<light kinds>> ch06 */
    LIGHT_AREA, /* a disc, shining like many point lights spread over it */
} light_kind;

typedef struct {
    light_kind kind;
    vec3 position;  /* point and spot */
    vec3 direction; /* directional and spot: unit, the way the light travels */
    vec3 intensity; /* I_j, RGB, may exceed 1 */
    double attenuation[3]; /* point and spot: 1 / (a1 + a2 r + a3 r^2) */
    double cos_cutoff;     /* spot: cos Theta_L */
    double exponent;       /* spot: k in cos^k Theta */
    /* <<light members>> ch06 */
    double radius; /* area: the disc's radius, > 0 */
    int samples;   /* area: how many point lights stand for it */
    enum sample_pattern {
        SAMPLE_UNIFORM,    /* independent random points */
        SAMPLE_STRATIFIED, /* one random point in each of N equal cells */
        SAMPLE_GRID,       /* the centre of each cell */
    } pattern;             /* area: where the point lights go */
    int samples_cut;       /* area: samples the shadow-ray budget took away */
} light;

#endif
