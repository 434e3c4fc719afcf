/* ch07_refraction.c: Snell's law, the refracted direction, the Fresnel
 * reflectance, transparent materials and the checker pattern (chapter 07).
 *
 * Expected values come from closed forms (stated beside each) computed in
 * long double, or from a second scene that must give the same picture for
 * a reason stated beside it, never from the functions under test. Tolerances
 * are in units of DBL_EPSILON (2.2e-16, the spacing of doubles at 1) or
 * degrees, with the reason beside each. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "optics.h"
#include "render.h"
#include "scene.h"
#include "offset.h"
#include "search.h"
#include "trace.h"
#include "test_util.h"
#include "rng.h"

#define EPS DBL_EPSILON
#define DEG (M_PI / 180)

static const double MEDIA[] = {1.33, 1.5, 2.42}; /* water, glass, diamond */

/* The tests of a refracted direction run once a form, as Check's loop
 * tests: iteration 0 is exercise 7.1's standard form, 1 exercise 7.2's
 * construction of the sheet, each exercise naming its own. */
typedef refraction (*refract_fn)(vec3 i, vec3 n, double eta);
static const struct {
    const char *name;
    refract_fn refract;
} forms[] = {{"standard", refract_standard}, {"sheet", refract_sheet}};

/* ---------------------------------------------------------------- helpers */

/* fixed seed: reproducible */
static const rng_state RNG_START = {0x9E3779B97F4A7C15ULL};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

static double uniform01(void) { return rng_uniform01(&rng); }

/* A unit normal n and a unit vector u along the surface, turned at random. */
static void random_frame(vec3 *n, vec3 *u)
{
    double z = 2 * uniform01() - 1, phi = 2 * M_PI * uniform01(),
           s = sqrt(1 - z * z);
    *n = (vec3){s * cos(phi), s * sin(phi), z};
    vec3 helper = fabs(n->x) < 0.5 ? (vec3){1, 0, 0} : (vec3){0, 1, 0};
    *u = vec3_normalize(vec3_cross(*n, helper));
}

/* The unit direction that meets the surface at theta from the normal n. */
static vec3 incident(vec3 n, vec3 u, double theta)
{
    return vec3_normalize(
        vec3_sub(vec3_scale(u, sin(theta)), vec3_scale(n, cos(theta))));
}

typedef struct {
    long double x, y, z;
} lvec;

static lvec lvec_of(vec3 a) { return (lvec){a.x, a.y, a.z}; }
static long double lvec_dot(lvec a, lvec b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static long double lvec_length(lvec a) { return sqrtl(lvec_dot(a, a)); }
static lvec lvec_cross(lvec a, lvec b)
{
    return (lvec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
}

/* sin of the angle between a and b, in long double. */
static long double sine_between(vec3 a, vec3 b)
{
    lvec la = lvec_of(a), lb = lvec_of(b);
    return lvec_length(lvec_cross(la, lb)) /
           (lvec_length(la) * lvec_length(lb));
}

/* How far a computed t may be from the true one: 8 eps times the size of
 * the terms it is made of. t = eta i + (eta c1 - c2) n adds terms of size
 * eta, and the radicand 1 - eta^2 (1 - c1^2) subtracts terms of size
 * eta^2, so for eta > 1 its rounding error is a few ulps of eta^2. (n and
 * i are unit only to an ulp, which the 8 covers.) */
static double t_tolerance(double eta)
{
    return 8 * EPS * (eta > 1 ? eta * eta : 1);
}

/* The reflectance at normal incidence between air and MEDIA[k], a table
 * worked out to 21 digits (it is ((eta - 1) / (eta + 1))^2). */
static const long double NORMAL_REFLECTANCE[] = {
    0.020059312199524765606L, 0.04L, 0.172394924934167778120L};

static void expect_relative(double got, long double want, double tolerance,
                            const char *what)
{
    ck_assert_msg(fabsl(got - want) <= tolerance * fabsl(want),
                  "%s: %.17g, expected %.17Lg", what, got, want);
}

/* ---------------------------------------------------------------- formulas */

START_TEST(test_normal_incidence_reflects_four_percent_of_glass)
{
    /* 4 eps: a subtraction, an addition, a division and a square, each
     * rounded once */
    expect_relative(fresnel_exact(1, 1, 1.5), 0.04L, 4 * EPS,
                    "glass from outside");
    expect_relative(fresnel_exact(1, 1.5, 1), 0.04L, 4 * EPS,
                    "glass from inside");
    for (int k = 0; k < 3; k++) {
        double eta = MEDIA[k];
        long double f0 = NORMAL_REFLECTANCE[k];
        expect_relative(fresnel_exact(1, 1, eta), f0, 4 * EPS,
                        "exact, outside");
        expect_relative(fresnel_exact(1, eta, 1), f0, 4 * EPS, "exact, inside");
        expect_relative(fresnel_schlick(1, 1, eta), f0, 4 * EPS, "Schlick");
        expect_relative(fresnel_schlick_tir(1, eta, 1), f0, 4 * EPS,
                        "Schlick with TIR");
    }
    /* the table's values, to the digits it prints */
    ck_assert(fabs(fresnel_exact(1, 1, 1.33) - 0.0201) < 0.00005);
    ck_assert(fabs(fresnel_exact(1, 1, 2.42) - 0.1724) < 0.00005);
}
END_TEST

START_TEST(test_brewster_angle_of_glass_is_56_31_degrees)
{
    ck_assert(fabs(fresnel_brewster_angle(1, 1.5) / DEG - 56.31) < 0.005);
    const double table[3] = {53.06, 56.31, 67.55}; /* from outside, degrees */
    const double at_brewster[3] = {0.0386, 0.0740, 0.2508}; /* F_R there */
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            long double eta1 = side ? MEDIA[k] : 1, eta2 = side ? 1 : MEDIA[k];
            double theta = fresnel_brewster_angle((double)eta1, (double)eta2);
            /* tan theta_B = eta2 / eta1; 2 eps: a division and atan2 */
            ck_assert(fabsl(theta - atanl(eta2 / eta1)) <= 2 * EPS);
            fresnel_pair f =
                fresnel_polarized(cos(theta), (double)eta1, (double)eta2);
            /* r_par's numerator cancels to a rounding error, about eps */
            ck_assert_msg(f.parallel < 1e-30, "r_par^2 = %g", f.parallel);
            long double q =
                (eta1 * eta1 - eta2 * eta2) / (eta1 * eta1 + eta2 * eta2);
            /* 16 eps: cos(theta) is rounded, and F changes by about F per
             * radian there */
            expect_relative(
                fresnel_exact(cos(theta), (double)eta1, (double)eta2),
                q * q / 2, 16 * EPS, "F_R at Brewster's angle");
            if (!side) {
                ck_assert(fabs(theta / DEG - table[k]) < 0.005);
                ck_assert(fabs((double)(q * q / 2) - at_brewster[k]) < 0.00005);
            }
        }
}
END_TEST

START_TEST(test_critical_angle_of_glass_is_41_81_degrees)
{
    ck_assert(fabs(refract_critical_angle(1.5, 1) / DEG - 41.81) < 0.005);
    const double table[3] = {48.75, 41.81, 24.41};
    for (int k = 0; k < 3; k++) {
        double eta = MEDIA[k], theta_c = refract_critical_angle(eta, 1);
        ck_assert(fabs(theta_c / DEG - table[k]) < 0.005);
        ck_assert(fabsl(theta_c - asinl(1 / (long double)eta)) <= 2 * EPS);
        /* none from outside: light going into the denser medium always enters
         */
        ck_assert(refract_critical_angle(1, eta) == M_PI / 2);
        vec3 n = {0, 1, 0};
        /* 1e-9 rad either side: far beyond rounding, well inside the
         * resolution of any scene */
        refraction before = forms[_i].refract(
            incident(n, (vec3){1, 0, 0}, theta_c - 1e-9), n, eta);
        refraction after = forms[_i].refract(
            incident(n, (vec3){1, 0, 0}, theta_c + 1e-9), n, eta);
        ck_assert_msg(!before.total && after.total, "%s at %g", forms[_i].name,
                      eta);
    }
}
END_TEST

/* Snell's law for both forms at many angles from both sides of each medium. */
START_TEST(test_snell_holds_for_the_refracted_direction)
{
    int checked = 0;
    int m = _i; /* the form of this iteration */
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            double eta1 = side ? MEDIA[k] : 1, eta2 = side ? 1 : MEDIA[k];
            for (int a = 1; a < 1000; a++) {
                double theta = a * (89.9 / 1000) * DEG;
                vec3 n, u;
                random_frame(&n, &u);
                vec3 i = incident(n, u, theta);
                refraction r = forms[m].refract(i, n, eta1 / eta2);
                long double s1 = sine_between(i, n);
                ck_assert_msg(r.total == (eta1 * s1 > eta2),
                              "%s: total reflection %s at %.3f deg from %g "
                              "into %g: Snell's "
                              "law is eta1 sin1 = eta2 sin2, so sin1 / "
                              "sin2 = eta2 / eta1, "
                              "not the sheet's eta1 / eta2 (sheet 6.3)",
                              forms[m].name, r.total ? "wrongly" : "missed",
                              theta / DEG, eta1, eta2);
                if (r.total)
                    continue;
                long double s2 = sine_between(r.dir, n);
                ck_assert_msg(fabsl(eta1 * s1 - eta2 * s2) <=
                                  eta2 * t_tolerance(eta1 / eta2),
                              "%s: eta1 sin1 - eta2 sin2 = %Lg at %.3f "
                              "deg: Snell's law is "
                              "eta1 sin1 = eta2 sin2, so sin1 / sin2 = "
                              "eta2 / eta1, not the "
                              "sheet's eta1 / eta2 (sheet 6.3)",
                              forms[m].name, eta1 * s1 - eta2 * s2,
                              theta / DEG);
                /* the sheet's ratio sin1 / sin2 = eta1 / eta2 is off by
                 * far more than rounding */
                ck_assert(fabsl(s1 / s2 - eta1 / eta2) > 0.1);
                checked++;
            }
        }
    ck_assert_int_gt(checked, 4000); /* most angles refract */
}
END_TEST

START_TEST(test_refracted_direction_is_a_unit_vector_beyond_the_surface)
{
    int m = _i; /* the form of this iteration */
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            double eta = side ? MEDIA[k] : 1 / MEDIA[k];
            for (int a = 1; a < 1000; a++) {
                vec3 n, u;
                random_frame(&n, &u);
                vec3 i = incident(n, u, a * (89.9 / 1000) * DEG);
                refraction r = forms[m].refract(i, n, eta);
                if (r.total)
                    continue;
                lvec t = lvec_of(r.dir);
                double tolerance = t_tolerance(eta);
                ck_assert_msg(fabsl(lvec_length(t) - 1) <= tolerance,
                              "%s: |t| - 1 = %Lg", forms[m].name,
                              lvec_length(t) - 1);
                ck_assert(lvec_dot(t, lvec_of(n)) < 0); /* on the far side */
                /* in the plane of i and n */
                lvec across = lvec_cross(lvec_of(i), lvec_of(n));
                long double out = lvec_dot(t, across) / lvec_length(across);
                ck_assert_msg(fabsl(out) <= tolerance,
                              "%s: out of plane by %Lg", forms[m].name, out);
                /* cos_t is -<n, t> */
                ck_assert(fabsl(r.cos_t + lvec_dot(t, lvec_of(n))) <=
                          tolerance);
            }
        }
}
END_TEST

START_TEST(test_sheet_construction_equals_the_standard_form)
{
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            double eta = side ? MEDIA[k] : 1 / MEDIA[k];
            for (int a = 0; a < 1000; a++) {
                vec3 n, u;
                random_frame(&n, &u);
                vec3 i = incident(n, u, a * (89.9 / 1000) * DEG);
                refraction std = refract_standard(i, n, eta),
                           sheet = refract_sheet(i, n, eta);
                ck_assert(std.total == sheet.total);
                if (std.total || std.cos_t < 0.1)
                    continue; /* near the critical angle, see below */
                /* Rounding only: each form rounds its radicand by about
                 * t_tolerance(eta), and the square root divides that by
                 * 2 cos_t; the two forms' errors add. */
                double d = vec3_length(vec3_sub(std.dir, sheet.dir));
                ck_assert_msg(d <= t_tolerance(eta) / std.cos_t,
                              "eta %g, cos_t %g: the forms differ by %g", eta,
                              std.cos_t, d);
                /* the sheet's form does not care which side n is on */
                refraction flipped = refract_sheet(i, vec3_scale(n, -1), eta);
                ck_assert(vec3_length(vec3_sub(flipped.dir, sheet.dir)) <=
                          2 * EPS);
            }
        }
}
END_TEST

START_TEST(test_reflectance_and_transmittance_sum_to_one)
{
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            long double eta1 = side ? MEDIA[k] : 1, eta2 = side ? 1 : MEDIA[k];
            for (int a = 0; a < 900; a++) {
                double c1d = cos(a * 0.1 * DEG); /* the very input F gets */
                long double c1 = c1d, s2 = eta1 / eta2 * sqrtl(1 - c1 * c1);
                double F = fresnel_exact(c1d, (double)eta1, (double)eta2);
                if (s2 >= 1) {
                    ck_assert(F == 1); /* nothing is transmitted */
                    continue;
                }
                /* The transmitted power from the transmitted amplitudes
                 * 2 eta1 c1 / (...), scaled by the beam's speed and width */
                long double c2 = sqrtl(1 - s2 * s2);
                long double tp = 2 * eta1 * c1 / (eta2 * c1 + eta1 * c2);
                long double ts = 2 * eta1 * c1 / (eta1 * c1 + eta2 * c2);
                long double T =
                    eta2 * c2 / (eta1 * c1) * (tp * tp + ts * ts) / 2;
                /* 8 eps / c2: F's cos theta2 = sqrt(1 - sin^2) carries an
                 * absolute error of about eps / c2, large near the critical
                 * angle */
                ck_assert_msg(fabsl(F + T - 1) <= 8 * EPS / c2,
                              "F + T - 1 = %Lg at c2 = %Lg", F + T - 1, c2);
            }
        }
}
END_TEST

START_TEST(test_light_crossing_either_way_is_reflected_alike)
{
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 900; a++) {
            double c1 = cos(a * 0.1 * DEG);
            long double s2 = sqrtl(1 - (long double)c1 * c1) / MEDIA[k];
            double c2 = (double)sqrtl(1 - s2 * s2);
            double outside = fresnel_exact(c1, 1, MEDIA[k]);
            double inside = fresnel_exact(c2, MEDIA[k], 1);
            /* Each side's cosine of the other side has an error of a few
             * ulps of eta^2 over that cosine (the smaller of the two), and
             * rounding c2 to double adds as much */
            double smaller = c1 < c2 ? c1 : c2, eta = MEDIA[k];
            ck_assert_msg(fabs(outside - inside) <=
                              8 * EPS * eta * eta / smaller,
                          "%.17g against %.17g", outside, inside);
        }
}
END_TEST

START_TEST(test_slab_returns_a_ray_parallel_to_the_original)
{
    /* Enter a slab through its top (normal +y), leave through its bottom:
     * from inside, the normal on the ray's side is +y again. No angle
     * reflects totally at the bottom: sin theta inside is below 1/eta. */
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 900; a++) {
                double theta = a * 0.1 * DEG, eta = MEDIA[k];
                vec3 n = {0, 1, 0}, i = incident(n, (vec3){0.6, 0, 0.8}, theta);
                refraction in = forms[m].refract(i, n, 1 / eta);
                ck_assert(!in.total);
                refraction out = forms[m].refract(in.dir, n, eta);
                ck_assert_msg(!out.total, "%s at %.1f deg", forms[m].name,
                              a * 0.1);
                /* The second refraction's own error, plus the first one's
                 * (8 eps) grown by d theta2 / d theta1 = eta c1 / c2, where
                 * c2 is the cosine of the way out: that of theta */
                double tolerance =
                    t_tolerance(eta) + eta * 8 * EPS / cos(theta);
                ck_assert_msg(vec3_length(vec3_sub(out.dir, i)) <= tolerance,
                              "%s: off by %g", forms[m].name,
                              vec3_length(vec3_sub(out.dir, i)));
            }
}
END_TEST

START_TEST(test_schlick_values)
{
    /* F0 + (1 - F0)(1 - cos)^5 at cos = 1, 0.5, 0: F0, F0 + (1 - F0)/32, 1 */
    ck_assert(fabs(fresnel_schlick(1, 1, 1.5) - 0.04) <= 4 * EPS);
    ck_assert(fabs(fresnel_schlick(0.5, 1, 1.5) - 0.07) <= 4 * EPS);
    ck_assert(fresnel_schlick(0, 1, 1.5) == 1);
    ck_assert(fresnel_schlick_tir(0.5, 1, 1.5) == fresnel_schlick(0.5, 1, 1.5));
}
END_TEST

/* ---------------------------------------------------------------- edge cases
 */

START_TEST(test_total_internal_reflection_past_the_critical_angle)
{
    vec3 n = {0, 1, 0};
    for (int k = 0; k < 3; k++) {
        double eta = MEDIA[k], theta_c = refract_critical_angle(eta, 1);
        for (int a = 1; a <= 100; a++) {
            double theta = theta_c + (M_PI / 2 - theta_c) * a / 100.0;
            vec3 i = incident(n, (vec3){0, 0, 1}, theta);
            ck_assert_msg(forms[_i].refract(i, n, eta).total, "%s",
                          forms[_i].name);
        }
    }
}
END_TEST

/* Fresnel's reflectance is 1, all of the light, past the critical angle,
 * and less than 1 just before it. */
START_TEST(test_fresnel_reflects_all_past_the_critical_angle)
{
    for (int k = 0; k < 3; k++) {
        double eta = MEDIA[k], theta_c = refract_critical_angle(eta, 1);
        ck_assert(fresnel_exact(cos(theta_c - 1e-9), eta, 1) < 1);
        ck_assert(fresnel_exact(cos(theta_c + 1e-9), eta, 1) == 1);
        for (int a = 1; a <= 100; a++) {
            double theta = theta_c + (M_PI / 2 - theta_c) * a / 100.0;
            double c = cos(theta);
            ck_assert(fresnel_exact(c, eta, 1) == 1);
            ck_assert(fresnel_schlick_tir(c, eta, 1) == 1);
            fresnel_pair f = fresnel_polarized(c, eta, 1);
            ck_assert(f.parallel == 1 && f.perpendicular == 1);
        }
    }
}
END_TEST

START_TEST(test_without_the_tir_test_the_direction_is_nan)
{
    /* From inside glass at 60 degrees, past the critical 41.81 */
    vec3 n = {0, 1, 0}, i = {sin(60 * DEG), -cos(60 * DEG), 0};
    double eta = 1.5, c1 = -vec3_dot(n, i);
    double radicand = 1 - eta * eta * (1 - c1 * c1); /* 1 - 2.25 * 0.75 */
    ck_assert(radicand < 0);
    double c2 = sqrt(radicand); /* the standard form, unguarded */
    vec3 t = vec3_add(vec3_scale(i, eta), vec3_scale(n, eta * c1 - c2));
    ck_assert(isnan(t.x) && isnan(t.y));
    /* the program's forms report total internal reflection instead */
    ck_assert(refract_standard(i, n, eta).total);
    ck_assert(refract_sheet(i, n, eta).total);
}
END_TEST

START_TEST(test_without_the_tir_test_the_weights_are_nan)
{
    /* The sheet's F_R with cos theta2 = sqrt(1 - sin^2 theta2), unguarded */
    double eta1 = 1.5, eta2 = 1, c1 = 0.5, s1 = sqrt(1 - c1 * c1);
    double s2 = eta1 / eta2 * s1, c2 = sqrt(1 - s2 * s2);
    double par = (eta2 * c1 - eta1 * c2) / (eta2 * c1 + eta1 * c2);
    double perp = (eta1 * c1 - eta2 * c2) / (eta1 * c1 + eta2 * c2);
    double F = 0.5 * (par * par + perp * perp);
    ck_assert(isnan(F) && isnan(1 - F));
    ck_assert(fresnel_exact(c1, eta1, eta2) == 1);
    ck_assert(fresnel_exact(NAN, eta1, eta2) == 1); /* a NaN never passes */
}
END_TEST

START_TEST(test_schlick_needs_the_angle_in_the_thinner_medium)
{
    /* Inside glass at 60 degrees: exact 1; plain Schlick 0.04 + 0.96/32 */
    ck_assert(fresnel_exact(0.5, 1.5, 1) == 1);
    ck_assert(fabs(fresnel_schlick(0.5, 1.5, 1) - 0.07) <= 4 * EPS);
    ck_assert(fresnel_schlick_tir(0.5, 1.5, 1) == 1);
    /* below the critical angle it is Schlick at the angle outside: that
     * of the refracted ray (refract_standard's cos_t) */
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 100; a++) {
            double theta = refract_critical_angle(MEDIA[k], 1) * a / 100.0;
            vec3 i = {sin(theta), 0, -cos(theta)}, n = {0, 0, 1};
            refraction out = refract_standard(i, n, MEDIA[k]);
            ck_assert(!out.total);
            double want = fresnel_schlick(out.cos_t, MEDIA[k], 1);
            /* 64 eps: the two cosines, each from a rounded cos(theta),
             * may differ by up to eta c1 / c2 of its error, at most
             * about 40 at a = 99 */
            ck_assert_msg(fabs(fresnel_schlick_tir(-vec3_dot(n, i), MEDIA[k],
                                                   1) -
                               want) <= 64 * EPS,
                          "at %d%% of the critical angle", a);
        }
}
END_TEST

START_TEST(test_sheet_construction_fails_at_grazing_incidence)
{
    vec3 n = {0, 1, 0}, i = {1, 0, 0}; /* along the surface: cos theta1 = 0 */
    refraction sheet = refract_sheet(i, n, 1 / 1.5);
    ck_assert(!sheet.total && isnan(sheet.dir.y)); /* alpha = inf, a = 0 */
    refraction std = refract_standard(i, n, 1 / 1.5);
    ck_assert(!std.total);
    /* the far side's critical angle: sin theta2 = 1/1.5 */
    ck_assert(fabsl(sine_between(std.dir, n) - 1 / 1.5L) <= 4 * EPS);
    ck_assert(fabs(vec3_length(std.dir) - 1) <= 4 * EPS);
    /* leaving, a grazing ray is totally reflected by both */
    ck_assert(refract_sheet(i, n, 1.5).total &&
              refract_standard(i, n, 1.5).total);
}
END_TEST

START_TEST(test_index_one_is_no_surface)
{
    for (int a = 0; a < 900; a++) {
        double theta = a * 0.1 * DEG, c = cos(theta);
        /* c2 = sqrt(1 - (1 - c^2)) differs from c by the rounding of the
         * subtractions, about eps / c, so r = (c - c2) / (c + c2) by about
         * eps / c^2, and F = r^2 */
        ck_assert(fresnel_exact(c, 1, 1) <= pow(4 * EPS / (c * c), 2));
        vec3 n, u;
        random_frame(&n, &u);
        vec3 i = incident(n, u, theta);
        refraction r = refract_standard(i, n, 1);
        /* t = i + (c1 - c2) n: off from i by c1 - c2, about eps / c */
        ck_assert(!r.total && vec3_length(vec3_sub(r.dir, i)) <= 8 * EPS / c);
    }
    ck_assert(fresnel_exact(1, 1, 1) == 0); /* head-on, exactly */
}
END_TEST

/* ---------------------------------------------------------------- scenes */

START_TEST(test_material_settings_and_their_defaults)
{
    material m = material_default();
    ck_assert(m.ior == 1.5 && m.transparency == 0 &&
              m.fresnel == FRESNEL_EXACT);
    scene s;
    scene_error err;
    const char *text =
        "material glass ior 1.33 transparency 0.9 fresnel schlick\n"
        "material plain\n"
        "sphere material glass checker 0.1 0.2 0.3 tile 0.5\n";
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    const material *glass = scene_material(&s, 1),
                   *plain = scene_material(&s, 2);
    ck_assert(glass->ior == 1.33 && glass->transparency == 0.9);
    ck_assert(glass->fresnel == FRESNEL_SCHLICK);
    ck_assert(plain->ior == 1.5 && plain->transparency == 0 &&
              plain->fresnel == FRESNEL_EXACT);
    const object *o = &s.objects[0];
    ck_assert(o->checkered && o->tile == 0.5 && o->checker.y == 0.2);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_rejects_bad_optical_settings)
{
    expect_parse_error("material m ior 0", 1, 16,
                       "refractive index from 0.001 to 1000");
    expect_parse_error("material m ior -1.5", 1, 16,
                       "from 0.001 to 1000, found '-1.5'");
    expect_parse_error("material m ior 0.0001", 1, 16, "from 0.001 to 1000");
    expect_parse_error("material m ior 1e4", 1, 16, "from 0.001 to 1000");
    expect_parse_error("material m ior nan", 1, 16, "finite");
    expect_parse_error("material m ior inf", 1, 16, "finite");
    expect_parse_error("material m ior", 1, 15, "refractive index");
    expect_parse_error("material m transparency -0.1", 1, 25,
                       "transparency from 0 to 1");
    expect_parse_error("material m transparency 1.01", 1, 25,
                       "transparency from 0 to 1");
    expect_parse_error("material m transparency nan", 1, 25, "finite");
    expect_parse_error("material m fresnel fast", 1, 20,
                       "'exact' or 'schlick'");
    expect_parse_error("material m fresnel", 1, 19, "'exact' or 'schlick'");
    expect_parse_error("material m opacity 1", 1, 12,
                       "ior, transparency, fresnel");
    expect_parse_error("sphere checker 1 1", 1, 19, "checker colour component");
    expect_parse_error("sphere checker 1 -1 1", 1, 18, "from 0 to 1e6");
    expect_parse_error("sphere tile 0", 1, 13, "tile size from 1e-50 to 1e50");
    expect_parse_error("sphere tile -1", 1, 13, "tile size from 1e-50");
    expect_parse_error("sphere tile inf", 1, 13, "finite");
    expect_parse_error("triangle tile 1e-60", 1, 15, "tile size from 1e-50");
    expect_parse_error("sphere stripes 1", 1, 8, "checker, tile");
}
END_TEST

/* The colour of what a ray straight down through (x, 5, z) hits. */
static vec3 color_below(const scene *s, double x, double z)
{
    hit h;
    render_stats stats = {0};
    ck_assert(scene_intersect(s, (ray){{x, 5, z}, {0, -1, 0}}, 0, INFINITY, &h,
                              &stats));
    return h.color;
}

START_TEST(test_checker_changes_colour_from_one_cube_to_the_next)
{
    scene s;
    scene_error err;
    /* a floor in the plane y = 0, in the middle of a layer of cubes */
    const char *text = "triangle a -100 0 -100 b 100 0 -100 c 0 0 100 color 1 "
                       "1 1 checker 0 0 0\n";
    ck_assert_msg(parse_text(&s, text, &err), "%s", err.message);
    /* cubes of side 1 centred on whole numbers: (0.2, 0, 0.2) is in cube
     * (0, 0, 0), even; (0.7, 0, 0.2) in (1, 0, 0), odd; (0.7, 0, 0.7) in
     * (1, 0, 1), even; (-0.7, 0, 0.2) in (-1, 0, 0), odd */
    ck_assert(color_below(&s, 0.2, 0.2).x == 1);
    ck_assert(color_below(&s, 0.7, 0.2).x == 0);
    ck_assert(color_below(&s, 0.7, 0.7).x == 1);
    ck_assert(color_below(&s, -0.7, 0.2).x == 0);
    ck_assert(color_below(&s, -1.7, -3.2).x == 0); /* (-2, 0, -3): odd */
    s.objects[0].tile = 2; /* cubes centred on even numbers */
    ck_assert(color_below(&s, 0.7, 0.2).x == 1);
    ck_assert(color_below(&s, 1.2, 0.2).x == 0);
    s.objects[0].checkered = false;
    ck_assert(color_below(&s, 1.2, 0.2).x == 1);
    scene_free(&s);
}
END_TEST

/* ---------------------------------------------------------------- the tree */

/* A scene parsed from text; fails the test on a parse error. */
static void scene_of(scene *s, const char *text)
{
    scene_error err;
    ck_assert_msg(parse_text(s, text, &err), "%s:%d:%d: %s", err.file, err.line,
                  err.col, err.message);
}

START_TEST(test_glass_of_index_one_is_invisible)
{
    /* A clear ball of index 1 in front of the eye: F_R = 0 at both
     * surfaces (so no reflected ray), t = i, and the eye sees exactly what
     * it sees without the ball. */
    const char *ball =
        "background gradient 1 1 1  0.1 0.3 0.9\n"
        "material clear ambient 0 diffuse 0 specular 0 transparency 1 ior 1\n"
        "sphere center 0 0 5 radius 1 material clear\n";
    scene with, without;
    scene_of(&with, ball);
    scene_of(&without, "background gradient 1 1 1  0.1 0.3 0.9\n");
    for (int k = 0; k < 50; k++) {
        /* through the ball at up to 30 degrees from its normals */
        vec3 d = vec3_normalize((vec3){0.01 * k - 0.25, 0.007 * k - 0.17, 5});
        render_stats st = {0};
        vec3 a = trace(&with, (ray){{0, 0, 0}, d}, 0, &st);
        vec3 b = trace(&without, (ray){{0, 0, 0}, d}, 0, &(render_stats){0});
        ck_assert_int_eq(st.refraction_rays, 2); /* in and out */
        ck_assert_int_eq(st.reflection_rays, 0);
        /* t differs from i by about eps / cos theta per surface (the
         * formulas tests), and the sky's colour changes by at most 0.45 per
         * unit of direction: 64 eps is far above that */
        ck_assert_msg(vec3_length(vec3_sub(a, b)) <= 64 * EPS, "off by %g",
                      vec3_length(vec3_sub(a, b)));
    }
    scene_free(&with), scene_free(&without);
}
END_TEST

START_TEST(test_weights_multiply_along_the_path)
{
    /* Head-on through a clear glass ball: F_R = 0.04 at both surfaces. With
     * the cutoff at 0.05 both reflections (weights 0.04 and 0.96 x 0.04) are
     * cut, and the ball shows its own shading, black, in their place: the
     * eye sees (1 - 0.04)^2 = 0.9216 of the sky behind. */
    const char *text =
        "background 0.5 0.6 0.7\n"
        "material glass ambient 0 diffuse 0 specular 0 transparency 1 ior 1.5\n"
        "sphere center 0 0 5 radius 1 material glass\n"
        "recursion cutoff 0.05\n";
    scene s;
    scene_of(&s, text);
    render_stats st = {0};
    vec3 seen = trace(&s, (ray){{0, 0, 0}, {0, 0, 1}}, 0, &st);
    /* 16 eps: F is within 4 eps of 0.04 and three products round */
    ck_assert(fabs(seen.x - 0.9216 * 0.5) <= 16 * EPS);
    ck_assert(fabs(seen.z - 0.9216 * 0.7) <= 16 * EPS);
    ck_assert_int_eq(st.refraction_rays, 2);
    ck_assert_int_eq(st.reflection_rays, 0);
    ck_assert_int_eq(st.reflection_skipped_weight, 2); /* cut in each branch */
    scene_free(&s);
    /* Half transparent, glowing 0.2: each surface shows 0.5 of its own
     * light E and 0.5 of F E + (1 - F) (what is beyond), the reflections
     * still cut: c2 = E/2 + (F E + (1 - F) B)/2 at the back, and
     * c1 = E/2 + (F E + (1 - F) c2)/2 at the front */
    scene_of(
        &s,
        "background 0.5 0.6 0.7\n"
        "material half ambient 0 diffuse 0 specular 0 emission 0.2 0.2 0.2 "
        "transparency 0.5 ior 1.5\n"
        "sphere center 0 0 5 radius 1 material half\nrecursion cutoff 0.05\n");
    st = (render_stats){0};
    seen = trace(&s, (ray){{0, 0, 0}, {0, 0, 1}}, 0, &st);
    long double E = 0.2, F = 0.04, B = 0.5;
    long double c2 = E / 2 + (F * E + (1 - F) * B) / 2,
                c1 = E / 2 + (F * E + (1 - F) * c2) / 2;
    ck_assert_msg(fabsl(seen.x - c1) <= 16 * EPS, "%.17g against %.17Lg",
                  seen.x, c1);
    ck_assert_int_eq(st.refraction_rays, 2);
    scene_free(&s);
    /* at the depth limit 0 neither branch is traced */
    scene_of(&s, "material glass transparency 1\nsphere material "
                 "glass\nrecursion depth 0\n");
    st = (render_stats){0};
    trace(&s, (ray){{0, 0, 0}, {0, 0, 1}}, 0, &st);
    ck_assert(st.refraction_rays == 0 && st.reflection_rays == 0);
    ck_assert(st.refraction_skipped_depth == 1 &&
              st.reflection_skipped_depth == 1);
    scene_free(&s);
}
END_TEST

START_TEST(test_opaque_material_spawns_no_refracted_ray)
{
    /* ior is set but the material is opaque: not one ray for glass */
    const char *text = "material m ior 1.5 fresnel schlick\n"
                       "sphere center 0 0 5 radius 1 material m\n"
                       "sphere center 0 -101 5 radius 100\n"
                       "image 32 24\n";
    scene s;
    scene_of(&s, text);
    image img;
    ck_assert(image_init(&img, 32, 24));
    render_stats st = {0};
    render(&s, &img, &st);
    ck_assert(st.refraction_rays == 0 && st.reflection_rays == 0);
    ck_assert(st.refraction_skipped_depth == 0 &&
              st.refraction_skipped_weight == 0);
    ck_assert(st.total_reflections == 0);
    image_free(&img);
    scene_free(&s);
}
END_TEST

/* A box of 12 triangles from lo to hi, each wound so that its normal points
 * out of the box, with the given settings. */
static void add_box(char *text, size_t size, vec3 lo, vec3 hi,
                    const char *settings)
{
    const double x[2] = {lo.x, hi.x}, y[2] = {lo.y, hi.y}, z[2] = {lo.z, hi.z};
    /* each face: its axis, its side, and two corners' orders that make
     * (b - a) x (c - a) point outwards in this frame */
    static const int faces[6][2] = {{1, 1}, {1, 0}, {2, 0},
                                    {2, 1}, {0, 0}, {0, 1}};
    for (int f = 0; f < 6; f++) {
        int axis = faces[f][0], side = faces[f][1];
        int u = (axis + 1) % 3, v = (axis + 2) % 3; /* u x v = +axis */
        double c[4][3];
        const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; k++) {
            int kk = side ? k : 3 - k; /* reversed on the low side */
            c[k][axis] = side ? (axis == 0   ? x[1]
                                 : axis == 1 ? y[1]
                                             : z[1])
                              : (axis == 0   ? x[0]
                                 : axis == 1 ? y[0]
                                             : z[0]);
            c[k][u] = (u == 0 ? x : u == 1 ? y : z)[du[kk]];
            c[k][v] = (v == 0 ? x : v == 1 ? y : z)[dv[kk]];
        }
        const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (int t = 0; t < 2; t++) {
            size_t used = strlen(text);
            snprintf(text + used, size - used,
                     "triangle a %.17g %.17g %.17g b %.17g %.17g %.17g c %.17g "
                     "%.17g %.17g %s\n",
                     c[tri[t][0]][0], c[tri[t][0]][1], c[tri[t][0]][2],
                     c[tri[t][1]][0], c[tri[t][1]][1], c[tri[t][1]][2],
                     c[tri[t][2]][0], c[tri[t][2]][1], c[tri[t][2]][2],
                     settings);
        }
    }
}

START_TEST(test_box_triangles_face_outwards)
{
    /* add_box's winding, checked against the box itself: a ray from the
     * centre meets every face from inside */
    static char text[8192];
    add_box(text, sizeof text, (vec3){-1, -2, -3}, (vec3){1, 2, 3}, "");
    scene s;
    scene_of(&s, text);
    const vec3 dirs[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                          {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (int k = 0; k < 6; k++) {
        hit h;
        ray r = {{0.1, 0.2, 0.3}, dirs[k]};
        ck_assert(scene_intersect(&s, r, 0, INFINITY, &h, &(render_stats){0}));
        ck_assert_msg(h.inside, "face %d faces inwards", k);
    }
    scene_free(&s);
}
END_TEST

/* Rays into a glass slab from above, through it and out below; counts the
 * rays lost: not meeting the bottom from inside, or meeting the slab again
 * after leaving it. With offset, each secondary ray starts at chapter 6's
 * ray_leaving; without, at the hit point itself. */
static int lost_in_slab(const scene *s, double top, double bottom, vec3 centre,
                        bool offset)
{
    int lost = 0;
    rng_state g = {2024};
    for (int k = 0; k < 2000; k++) {
        double theta = rng_uniform(&g, 0, 80) * DEG,
               phi = rng_uniform(&g, 0, 2 * M_PI);
        vec3 d = {sin(theta) * cos(phi), -cos(theta), sin(theta) * sin(phi)};
        vec3 aim =
            vec3_add(centre, (vec3){rng_uniform(&g, -0.5, 0.5), top - centre.y,
                                    rng_uniform(&g, -0.5, 0.5)});
        ray r = {vec3_sub(aim, vec3_scale(d, 3)), d};
        hit h1, h2, h3;
        render_stats st = {0};
        ck_assert(scene_intersect(s, r, 0, INFINITY, &h1, &st) && !h1.inside);
        refraction in = refract_standard(d, h1.normal, 1 / 1.5);
        ray r2 = offset ? ray_leaving(&h1, in.dir) : (ray){h1.point, in.dir};
        if (!scene_intersect(s, r2, 0, INFINITY, &h2, &st) || !h2.inside ||
            fabs(h2.point.y - bottom) > 1e-6) {
            lost++;
            continue;
        }
        /* from inside the normal on the ray's side is the outward one turned */
        refraction out =
            refract_standard(in.dir, vec3_scale(h2.normal, -1), 1.5);
        ck_assert(
            !out.total); /* parallel faces: never past the critical angle */
        ray r3 = offset ? ray_leaving(&h2, out.dir) : (ray){h2.point, out.dir};
        lost += scene_intersect(s, r3, 0, INFINITY, &h3, &st);
    }
    return lost;
}

START_TEST(test_thin_slab_at_1e4_loses_no_ray)
{
    /* A slab a thousandth of a unit thick, 2 wide, 1e4 from the origin on
     * every axis: the offset of chapter 6 starts each refracted ray on the
     * far side of the surface it crosses, so every ray goes in through the
     * top, out through the bottom, and never meets the slab again. From
     * the hit point itself, some rays meet the surface they start on. */
    const vec3 centre = {1e4, 1e4, 1e4};
    const double top = 1e4 + 0.0005, bottom = 1e4 - 0.0005;
    static char text[8192];
    add_box(text, sizeof text, (vec3){centre.x - 1, bottom, centre.z - 1},
            (vec3){centre.x + 1, top, centre.z + 1}, "");
    scene s;
    scene_of(&s, text);
    ck_assert_int_eq(lost_in_slab(&s, top, bottom, centre, true), 0);
    ck_assert_int_gt(lost_in_slab(&s, top, bottom, centre, false), 0);
    scene_free(&s);
}
END_TEST

START_TEST(test_total_internal_reflection_is_a_perfect_mirror)
{
    /* The eye inside a box of glass looks at its floor 60 degrees from the
     * vertical, past the critical angle: F_R = 1, and the glass shows
     * exactly what a perfect mirror (reflect 1) in its place shows: the
     * same reflected ray, from the same origin, of the same weight. */
    static char glass[8192], mirror[8192];
    const char *head =
        "ambient 0.3 0.3 0.3\nrecursion depth 5\n"
        "material glass ambient 0 diffuse 0 specular 0 transparency 1 ior 1.5\n"
        "material mirror ambient 0 diffuse 0 specular 0 reflect 1\n"
        "sphere center 0 -0.5 9 radius 0.4 color 1 0.2 0.1\n";
    snprintf(glass, sizeof glass, "%s", head);
    snprintf(mirror, sizeof mirror, "%s", head);
    add_box(glass, sizeof glass, (vec3){-5, -1, -5}, (vec3){5, 1, 50},
            "material glass");
    add_box(mirror, sizeof mirror, (vec3){-5, -1, -5}, (vec3){5, 1, 50},
            "material mirror");
    scene g, m;
    scene_of(&g, glass);
    scene_of(&m, mirror);
    for (int k = 0; k < 20; k++) {
        double theta = (50 + k) * DEG; /* from the vertical; critical: 41.81 */
        ray r = {{0, 0, 0}, {0.01 * k, -cos(theta), sin(theta)}};
        r.dir = vec3_normalize(r.dir);
        render_stats sg = {0}, sm = {0};
        vec3 a = trace(&g, r, 0, &sg), b = trace(&m, r, 0, &sm);
        ck_assert_msg(a.x == b.x && a.y == b.y && a.z == b.z, "at %d", k);
        ck_assert_int_eq(sg.refraction_rays, 0);
        ck_assert_int_eq(sg.total_reflections,
                         sg.reflection_rays + sg.reflection_skipped_depth);
        ck_assert_int_eq(sg.reflection_rays, sm.reflection_rays);
    }
    scene_free(&g), scene_free(&m);
}
END_TEST

START_TEST(test_cli_renders_total_reflection_without_nan)
{
    /* Under water looking up: most rays meet the surface past the critical
     * angle. image_set refuses a pixel that is not finite, so a NaN would
     * stop the binary; it renders, and --stats counts the work. */
    make_tmpdir();
    static char text[8192];
    snprintf(text, sizeof text,
             "camera fov 110\nimage 48 64\n"
             "material water ambient 0 diffuse 0 specular 0.2 transparency 1 "
             "ior 1.33\n"
             "material schlick ambient 0 diffuse 0 transparency 1 ior 1.5 "
             "fresnel schlick\n"
             "triangle a -30 -2.5 -5 b 30 -2.5 -5 c 0 -2.5 40 checker 0 0 0\n"
             "sphere center 0 -1.5 6 radius 0.7 material schlick\n"
             "light point position 0 0.5 3\n");
    add_box(text, sizeof text, (vec3){-30, -3, -5}, (vec3){30, 1, 40},
            "material water");
    const char *path = write_file("pool.scene", text);
    char scene_path[256], out_path[256], errors[4096];
    snprintf(scene_path, sizeof scene_path, "%s", path);
    snprintf(out_path, sizeof out_path, "%s", tmp_path("out.png"));
    const char *args[] = {scene_path, "-o", out_path, "--stats", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert(file_exists(out_path));
    long long refracted = -1, cut_deep = -1, cut_light = -1, total = -1;
    const char *line = strstr(errors, "refraction rays");
    ck_assert_msg(line != NULL, "%s", errors);
    ck_assert(sscanf(line,
                     "refraction rays %lld not traced %lld at the depth limit, "
                     "%lld below "
                     "the cutoff, %lld totally reflected",
                     &refracted, &cut_deep, &cut_light, &total) == 4);
    ck_assert(refracted > 0 && total > 0);
    remove_tmpdir();
}
END_TEST

START_TEST(test_cli_rejects_a_bad_index_and_writes_nothing)
{
    make_tmpdir();
    const char *path =
        write_file("bad.scene", "material glass transparency 1 ior -1.5\n");
    char scene_path[256], out_path[256], errors[1024];
    snprintf(scene_path, sizeof scene_path, "%s", path);
    snprintf(out_path, sizeof out_path, "%s", tmp_path("out.png"));
    const char *args[] = {scene_path, "-o", out_path, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "bad.scene:1:35: error:") != NULL, "%s",
                  errors);
    ck_assert(!file_exists(out_path));
    remove_tmpdir();
}
END_TEST

Suite *ch07_refraction_suite(void)
{
    Suite *s = suite_create("ch07 refraction");
    TCase *formulas = tcase_create("formulas");
    tcase_add_checked_fixture(formulas, reseed, NULL);
    tcase_add_test(formulas,
                   test_normal_incidence_reflects_four_percent_of_glass);
    tcase_add_test(formulas, test_brewster_angle_of_glass_is_56_31_degrees);
    tcase_add_loop_test(formulas, test_critical_angle_of_glass_is_41_81_degrees,
                        0, 2);
    tcase_add_loop_test(formulas, test_snell_holds_for_the_refracted_direction,
                        0, 2);
    tcase_add_loop_test(
        formulas, test_refracted_direction_is_a_unit_vector_beyond_the_surface,
        0, 2);
    tcase_add_test(formulas, test_sheet_construction_equals_the_standard_form);
    tcase_add_test(formulas, test_reflectance_and_transmittance_sum_to_one);
    tcase_add_test(formulas, test_light_crossing_either_way_is_reflected_alike);
    tcase_add_test(formulas, test_slab_returns_a_ray_parallel_to_the_original);
    tcase_add_test(formulas, test_schlick_values);
    suite_add_tcase(s, formulas);

    TCase *edges = tcase_create("edge cases");
    tcase_add_checked_fixture(edges, reseed, NULL);
    tcase_add_loop_test(
        edges, test_total_internal_reflection_past_the_critical_angle, 0, 2);
    tcase_add_test(edges, test_fresnel_reflects_all_past_the_critical_angle);
    tcase_add_test(edges, test_without_the_tir_test_the_direction_is_nan);
    tcase_add_test(edges, test_without_the_tir_test_the_weights_are_nan);
    tcase_add_test(edges, test_schlick_needs_the_angle_in_the_thinner_medium);
    tcase_add_test(edges, test_sheet_construction_fails_at_grazing_incidence);
    tcase_add_test(edges, test_index_one_is_no_surface);
    suite_add_tcase(s, edges);

    TCase *tree = tcase_create("the ray tree");
    tcase_add_checked_fixture(tree, reseed, NULL);
    tcase_add_test(tree, test_glass_of_index_one_is_invisible);
    tcase_add_test(tree, test_weights_multiply_along_the_path);
    tcase_add_test(tree, test_opaque_material_spawns_no_refracted_ray);
    tcase_add_test(tree, test_box_triangles_face_outwards);
    tcase_add_test(tree, test_thin_slab_at_1e4_loses_no_ray);
    tcase_add_test(tree, test_total_internal_reflection_is_a_perfect_mirror);
    tcase_add_test(tree, test_cli_renders_total_reflection_without_nan);
    suite_add_tcase(s, tree);

    TCase *scenes = tcase_create("bad input");
    tcase_add_checked_fixture(scenes, reseed, NULL);
    tcase_add_test(scenes, test_material_settings_and_their_defaults);
    tcase_add_test(scenes, test_scene_rejects_bad_optical_settings);
    tcase_add_test(scenes,
                   test_checker_changes_colour_from_one_cube_to_the_next);
    tcase_add_test(scenes, test_cli_rejects_a_bad_index_and_writes_nothing);
    suite_add_tcase(s, scenes);
    return s;
}
