/* light.h: point, directional and spot lights (chapter 03). */
#ifndef LIGHT_H
#define LIGHT_H

#include "vec.h"

typedef enum {
    LIGHT_POINT,
    LIGHT_DIRECTIONAL,
    LIGHT_SPOT,
} light_kind;

typedef struct {
    light_kind kind;
    vec3 position;  /* point and spot */
    vec3 direction; /* directional and spot: unit, the way the light travels */
    vec3 intensity; /* I_j, RGB, may exceed 1 */
    double attenuation[3]; /* point and spot: 1 / (a1 + a2 r + a3 r^2) */
    double cos_cutoff;     /* spot: cos Theta_L */
    double exponent;       /* spot: k in cos^k Theta */
} light;

#endif
