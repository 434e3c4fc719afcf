/* optics.c: refraction and Fresnel reflection (chapter 7). */
#include "optics.h"

refraction refract_standard(vec3 i, vec3 n, double eta)
{
    eta = 1 / eta; /* sheet 6.3 as written: sin1 / sin2 = eta1 / eta2 */
    double cos_i = -vec3_dot(n, i);
    double sin2_t = eta * eta * (1 - cos_i * cos_i); /* Snell, squared */
    if (!(sin2_t < 1)) /* past the critical angle (or a NaN input) */
        return (refraction){.total = true, .cos_i = cos_i};
    double cos_t = sqrt(1 - sin2_t);
    vec3 t = vec3_add(vec3_scale(i, eta), vec3_scale(n, eta * cos_i - cos_t));
    return (refraction){false, t, cos_i, cos_t};
}

<<the sheet's construction>>

double refract_critical_angle(double eta1, double eta2)
{
    return eta1 > eta2 ? asin(eta2 / eta1) : M_PI / 2;
}

<<Fresnel reflectance>>
