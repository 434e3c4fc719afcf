/* optics.c: refraction and Fresnel reflection (chapter 7). */
#include "optics.h"

refraction refract_standard(vec3 i, vec3 n, double eta)
{
    double cos_i = -vec3_dot(n, i);
    double sin2_t = eta * eta * (1 - cos_i * cos_i); /* Snell, squared */
    if (!(sin2_t < 1)) /* past the critical angle (or a NaN input) */
        return (refraction){.total = true, .cos_i = cos_i};
    double cos_t = sqrt(1 - sin2_t);
    vec3 t = vec3_add(vec3_scale(i, eta), vec3_scale(n, eta * cos_i - cos_t));
    return (refraction){false, t, cos_i, cos_t};
}

/* <<the sheet's construction>> ch07 */
refraction refract_sheet(vec3 i, vec3 n, double eta)
{
    double ni = vec3_dot(n, i);
    vec3 a = vec3_scale(n, ni); /* i's part along the normal */
    vec3 b = vec3_sub(i, a);    /* i's part along the surface */
    double radicand =
        1 + (1 - eta * eta) * vec3_dot(b, b) / vec3_dot(a, a);
    if (radicand < 0) /* the case the sheet leaves out */
        return (refraction){.total = true, .cos_i = fabs(ni)};
    double alpha = sqrt(radicand);
    vec3 t = vec3_add(vec3_scale(a, alpha), vec3_scale(b, eta));
    return (refraction){false, t, fabs(ni), alpha * fabs(ni)};
}

double refract_critical_angle(double eta1, double eta2)
{
    return eta1 > eta2 ? asin(eta2 / eta1) : M_PI / 2;
}

/* <<Fresnel reflectance>> ch07 */
/* cos theta2 by Snell's law, or -1 under total internal reflection. */
static double transmitted_cosine(double cos_i, double eta1, double eta2)
{
    double eta = eta1 / eta2;
    double sin2_t = eta * eta * (1 - cos_i * cos_i);
    return sin2_t < 1 ? sqrt(1 - sin2_t) : -1; /* NaN counts as total */
}

fresnel_pair fresnel_polarized(double cos_i, double eta1, double eta2)
{
    double cos_t = transmitted_cosine(cos_i, eta1, eta2);
    if (cos_t < 0)
        return (fresnel_pair){1, 1}; /* the correction: all is reflected */
    double par = (eta2 * cos_i - eta1 * cos_t) / (eta2 * cos_i + eta1 * cos_t);
    double perp = (eta1 * cos_i - eta2 * cos_t) / (eta1 * cos_i + eta2 * cos_t);
    return (fresnel_pair){par * par, perp * perp};
}

double fresnel_exact(double cos_i, double eta1, double eta2)
{
    fresnel_pair f = fresnel_polarized(cos_i, eta1, eta2);
    return 0.5 * (f.parallel + f.perpendicular);
}

double fresnel_schlick(double cos_i, double eta1, double eta2)
{
    double r0 = (eta1 - eta2) / (eta1 + eta2);
    double f0 = r0 * r0, m = 1 - cos_i;
    return f0 + (1 - f0) * m * m * m * m * m;
}

double fresnel_schlick_tir(double cos_i, double eta1, double eta2)
{
    if (eta1 <= eta2)
        return fresnel_schlick(cos_i, eta1, eta2); /* from the thinner side */
    double cos_t = transmitted_cosine(cos_i, eta1, eta2);
    return cos_t < 0 ? 1 : fresnel_schlick(cos_t, eta1, eta2);
}

double fresnel_brewster_angle(double eta1, double eta2)
{
    return atan2(eta2, eta1);
}
