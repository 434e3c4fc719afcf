/* optics.h: refraction and Fresnel reflection at a smooth surface between
 * two transparent media (chapter 7).
 *
 * eta1 is the refractive index on the side the light comes from, eta2 on
 * the far side, eta = eta1 / eta2. i is the unit incident direction
 * (travelling towards the surface), n the unit normal on i's side, so that
 * cos_i = -<n, i> is in [0, 1]. Total internal reflection is an answer,
 * not an error: no function here returns a NaN for such inputs, except
 * refract_sheet, kept to be measured, at exactly grazing incidence. */
#ifndef OPTICS_H
#define OPTICS_H

#include <stdbool.h>
#include "vec.h"

/* A ray's fate at the surface. */
typedef struct {
    bool total;   /* total internal reflection: no refracted ray */
    vec3 dir;     /* the refracted unit direction t, unless total */
    double cos_i; /* cos theta1 */
    double cos_t; /* cos theta2, unless total */
} refraction;

/* <<refraction functions>> ch07 */
/* The standard form t = eta i + (eta cos_i - cos_t) n. */
refraction refract_standard(vec3 i, vec3 n, double eta);
/* The sheet's construction, corrected (6.4): t = alpha a + eta b. The
 * same t where cos_i > 0, for n on either side of the surface; at
 * cos_i = 0 it divides by zero and its direction is NaN. */
refraction refract_sheet(vec3 i, vec3 n, double eta);
/* The angle of incidence beyond which light going from eta1 into eta2 is
 * totally reflected, asin(eta2 / eta1); pi/2 (none) when eta1 <= eta2. */
double refract_critical_angle(double eta1, double eta2);

/* <<Fresnel functions>> ch07 */
/* r_par^2 and r_perp^2: the reflectances of light polarized parallel and
 * perpendicular to the plane of incidence; both 1 under total internal
 * reflection. cos_i in [0, 1]. */
typedef struct {
    double parallel, perpendicular;
} fresnel_pair;
fresnel_pair fresnel_polarized(double cos_i, double eta1, double eta2);

/* The sheet's F_R (6.5) for unpolarized light, the mean of the two, and 1
 * under total internal reflection. F_T = 1 - F_R is the refracted share. */
double fresnel_exact(double cos_i, double eta1, double eta2);
/* Schlick's F0 + (1 - F0)(1 - cos_i)^5 with the angle of incidence,
 * whichever side the light comes from: wrong from the denser side. */
double fresnel_schlick(double cos_i, double eta1, double eta2);
/* Schlick with the angle in the less dense medium, and 1 past the
 * critical angle. */
double fresnel_schlick_tir(double cos_i, double eta1, double eta2);
/* The angle of incidence at which r_par = 0: atan(eta2 / eta1). */
double fresnel_brewster_angle(double eta1, double eta2);

/* Which reflectance a material uses. */
typedef enum { FRESNEL_EXACT, FRESNEL_SCHLICK } fresnel_model;

#endif
