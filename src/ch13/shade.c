/* shade.c: the Phong model, lights and tone mapping (chapter 3). */
#include "shade.h"
/* <<shade.c includes>> ch06 */
#include "search.h"
#include "offset.h"
#include "sample.h"

/* <<highlights>> ch03 */
double phong_cosine(vec3 n, vec3 l, vec3 v)
{
    /* l mirrored about n */
    vec3 r = vec3_sub(vec3_scale(n, 2.0 * vec3_dot(n, l)), l);
    double rv = vec3_dot(r, v);
    return rv > 0 ? rv : 0;
}

double blinn_cosine(vec3 n, vec3 l, vec3 v)
{
    vec3 sum = vec3_add(l, v);
    double length = vec3_length(sum);
    if (length == 0)
        return 0; /* v = -l: no direction lies halfway */
    double nh = vec3_dot(n, sum) / length;
    return nh > 0 ? nh : 0;
}

double specular_phong(vec3 n, vec3 l, vec3 v, double k)
{
    return pow(phong_cosine(n, l, v), k);
}

double specular_blinn(vec3 n, vec3 l, vec3 v, double k)
{
    return pow(blinn_cosine(n, l, v), 4.0 * k);
}

/* <<lights>> ch03 */
double light_attenuation(const light *L, double r)
{
    const double *a = L->attenuation;
    /* the parser keeps this denominator > 0 */
    return 1.0 / (a[0] + a[1] * r + a[2] * r * r);
}

double spot_falloff(const light *L, vec3 l)
{
    /* the light travels along -l */
    double cos_theta = -vec3_dot(l, L->direction);
    if (cos_theta < L->cos_cutoff)
        return 0; /* outside the cone: the edge is hard */
    return pow(cos_theta > 0 ? cos_theta : 0, L->exponent);
}

light_sample light_toward(const light *L, vec3 point)
{
    if (L->kind == LIGHT_DIRECTIONAL)
        return (light_sample){vec3_scale(L->direction, -1), INFINITY,
                              L->intensity};
    vec3 to_light = vec3_sub(L->position, point);
    double r = vec3_length(to_light);
    vec3 l = r > 0 ? vec3_scale(to_light, 1 / r) : (vec3){0, 0, 0};
    double factor = light_attenuation(L, r);
    if (L->kind == LIGHT_SPOT)
        factor *= spot_falloff(L, l);
    return (light_sample){l, r, vec3_scale(L->intensity, factor)};
}

/* <<tone mapping>> ch03 */
double tone_map(double I, double alpha, double beta)
{
    if (!(I > 0))
        return 0;
    double mapped = alpha * pow(I, beta);
    return mapped < 1 ? mapped : 1;
}

/* <<shading a hit>> ch03 */
/* <<light visibility>> ch03 */
/* Can the light of ls reach the hit point h->point? */
static bool light_reaches(const scene *s, const hit *h,
                          const light_sample *ls, render_stats *stats)
{
    (void)s, (void)h, (void)ls, (void)stats; /* used from chapter 6 on */
    /* <<is the light blocked>> ch06 */
    vec3 I = ls->intensity;
    if (I.x == 0 && I.y == 0 && I.z == 0) {
        stats->shadow_skipped_dark++;
        return false; /* nothing arrives that a shadow could take away */
    }
    if (!scene_can_shadow(s, h)) {
        stats->shadow_skipped_alone++;
        return true;
    }
    stats->shadow_rays++;
    /* ls->distance is from the hit point; the offset origin is closer to
     * the light by far less than any object could be thick */
    bool blocked = scene_occluded(s, ray_leaving(h, ls->l), 0.0, ls->distance,
                                  stats);
    stats->shadow_rays_blocked += blocked;
    return !blocked;
    return true;
}

/* The highlight term rho_s <r, v>^k or rho_s <n, h>^(4k). */
static double highlight(const material *m, vec3 n, vec3 l, vec3 v)
{
    if (m->specular == 0)
        return 0; /* a matte finish pays no pow */
    double k = m->shininess;
    return m->specular * (m->highlight == HIGHLIGHT_BLINN
                              ? specular_blinn(n, l, v, k)
                              : specular_phong(n, l, v, k));
}

/* One light's diffuse and specular terms at the hit, or nothing. */
static vec3 direct_light(const scene *s, const material *m, const hit *h,
                         vec3 n, vec3 v, const light *L, render_stats *stats)
{
    /* <<lights made of many points>> ch06 */
    if (L->kind == LIGHT_AREA) { /* the sum of its point lights */
        vec3 sum = {0, 0, 0};
        sample_stream g = sample_stream_at(h->point, L->position);
        for (int k = 0; k < L->samples; k++) {
            light point = area_light_point(L, k, &g);
            sum = vec3_add(sum, direct_light(s, m, h, n, v, &point, stats));
        }
        stats->light_samples_cut += L->samples_cut;
        return sum;
    }
    stats->light_tests++;
    light_sample ls = light_toward(L, h->point);
    double nl = vec3_dot(n, ls.l);
    if (nl <= 0)
        return (vec3){0, 0, 0}; /* behind the surface: none, not negative */
    if (!light_reaches(s, h, &ls, stats))
        return (vec3){0, 0, 0};
    double spec = highlight(m, n, ls.l, v);
    vec3 diffuse = vec3_scale(h->color, m->diffuse * nl);
    return vec3_mul(vec3_add(diffuse, (vec3){spec, spec, spec}), ls.intensity);
}

vec3 shade(const scene *s, const hit *h, vec3 v, render_stats *stats)
{
    const material *m = scene_material(s, h->material);
    vec3 n = vec3_dot(h->normal, v) < 0 ? vec3_scale(h->normal, -1)
                                        : h->normal;
    vec3 ambient = vec3_scale(vec3_mul(h->color, s->ambient), m->ambient);
    vec3 color = vec3_add(m->emission, ambient);
    int count = s->light_count > 0 ? s->light_count : 1;
    const light *lights = s->light_count > 0 ? s->lights : &s->default_light;
    for (int j = 0; j < count; j++)
        color = vec3_add(color,
                         direct_light(s, m, h, n, v, &lights[j], stats));
    return color;
}
