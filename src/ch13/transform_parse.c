/* transform_parse.c: the steps of a transform setting (chapter 5). */
#include "transform_parse.h"

#include <math.h>

/* <<reading a step>> ch05 */
static const char transform_step_names[] =
    "translate, scale, rotate, shear, matrix";

static bool read_rotation(parser *p, transform *step)
{
    vec3 axis;
    const char *rest = p->next;
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "x"))
        axis = (vec3){1, 0, 0};
    else if (named && parse_token_is(p, "y"))
        axis = (vec3){0, 1, 0};
    else if (named && parse_token_is(p, "z"))
        axis = (vec3){0, 0, 1};
    else {
        p->next = rest; /* not x, y or z: the axis as three numbers */
        if (!parse_direction(p, "a rotation axis (x, y, z or 3 numbers)",
                             &axis))
            return false;
    }
    double deg;
    if (!parse_number(p, "an angle in degrees", &deg))
        return false;
    *step = transform_rotate(axis, deg);
    return true;
}

static bool read_shear(parser *p, transform *step)
{
    bool named = parse_next_token(p);
    bool yz = named && parse_token_is(p, "yz"),
         xz = named && parse_token_is(p, "xz"),
         xy = named && parse_token_is(p, "xy");
    if (!yz && !xz && !xy)
        return parse_expected(p, "expected the plane of a shear: yz, xz or "
                                 "xy");
    double a, b;
    if (!parse_number(p, "a shear factor", &a) ||
        !parse_number(p, "a shear factor", &b))
        return false;
    *step = transform_shear(yz   ? mat4_shear_yz(a, b)
                            : xz ? mat4_shear_xz(a, b)
                                 : mat4_shear_xy(a, b));
    return true;
}

static bool read_matrix(parser *p, const char *at, transform *step)
{
    mat4 m = mat4_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (!parse_number(p, "a matrix entry (3 rows of 4 numbers)",
                              &m.m[i][j]))
                return false;
    if (!transform_of_matrix(m, step))
        return parse_fail_at(p, at, "the matrix is singular: its "
                                    "determinant is 0 or not finite");
    return true;
}

/* The step the token just read names, into *step; *known is false when it
 * names none. */
static bool read_step(parser *p, const char *at, transform *step,
                      bool *known)
{
    vec3 v;
    *known = true;
    if (parse_token_is(p, "translate") || parse_token_is(p, "scale")) {
        bool moves = parse_token_is(p, "translate");
        if (!parse_point(p, moves ? "a translation" : "a scale factor", &v))
            return false;
        *step = moves ? transform_translate(v) : transform_scale(v);
        return true;
    }
    if (parse_token_is(p, "rotate"))
        return read_rotation(p, step);
    if (parse_token_is(p, "shear"))
        return read_shear(p, step);
    if (parse_token_is(p, "matrix"))
        return read_matrix(p, at, step);
    *known = false;
    return true;
}

/* <<checking the transform so far>> ch05 */
/* Why the scene cannot use t, or NULL when it can. */
static const char *transform_problem(const transform *t)
{
    if (!mat4_is_finite(t->m) || !(mat4_norm3(t->m) <= TRANSFORM_MAX_STRETCH))
        return "this step makes the transform stretch some direction by "
               "more than 1e12";
    if (!mat4_is_finite(t->inv) ||
        !(mat4_norm3(t->inv) <= TRANSFORM_MAX_STRETCH))
        return "this step makes the transform singular or nearly so: it "
               "shrinks some direction by more than 1e12";
    for (int i = 0; i < 3; i++)
        if (!(fabs(t->m.m[i][3]) <= PARSE_MAX_COORDINATE))
            return "this step moves the object's origin beyond 1e50";
    return NULL;
}

/* <<reading the steps>> ch05 */
bool transform_parse_steps(parser *p, transform *t)
{
    int steps = 0;
    for (;; steps++) {
        const char *rest = p->next;
        if (!parse_next_token(p))
            break;
        const char *at = p->token;
        transform step;
        bool known;
        if (!read_step(p, at, &step, &known))
            return false;
        if (!known) {
            p->next = rest; /* not a step: the statement's next setting */
            break;
        }
        *t = transform_then(*t, step);
        const char *problem = transform_problem(t);
        if (problem != NULL)
            return parse_fail_at(p, at, "%s", problem);
    }
    return steps > 0 || parse_expected(p, "expected a transform step (%s)",
                                       transform_step_names);
}
