/* mat4.c: 4x4 matrices, transforms and their inverses (chapter 5). See
 * vec.h. */
#include "vec.h"

/* <<sine and cosine in degrees>> ch05 */
/* sin and cos of deg degrees, exact at every multiple of 90 degrees: the
 * angle is split into quarter turns q and a rest within 45 degrees. */
static void sin_cos_deg(double deg, double *s, double *c)
{
    double q = round(deg / 90);
    double rest = (deg - 90 * q) * (M_PI / 180);
    double sr = sin(rest), cr = cos(rest);
    switch ((int)fmod(fmod(q, 4) + 4, 4)) { /* q mod 4, from 0 to 3 */
    case 0: *s = sr, *c = cr; break;
    case 1: *s = cr, *c = -sr; break;
    case 2: *s = -sr, *c = -cr; break;
    default: *s = -cr, *c = sr; break;
    }
}

/* <<products of matrices>> ch05 */
mat4 mat4_identity(void)
{
    return (mat4){{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
}

mat4 mat4_mul(mat4 a, mat4 b)
{
    mat4 c;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            c.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] +
                        a.m[i][2] * b.m[2][j] + a.m[i][3] * b.m[3][j];
    return c;
}

mat4 mat4_transpose(mat4 a)
{
    mat4 t;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            t.m[i][j] = a.m[j][i];
    return t;
}

/* <<the sheet's matrices>> ch05 */
mat4 mat4_translate(vec3 t)
{
    mat4 a = mat4_identity();
    a.m[0][3] = t.x, a.m[1][3] = t.y, a.m[2][3] = t.z;
    return a;
}

mat4 mat4_scale(vec3 s)
{
    mat4 a = mat4_identity();
    a.m[0][0] = s.x, a.m[1][1] = s.y, a.m[2][2] = s.z;
    return a;
}

/* The rotation by (s, c) = (sin, cos) in the plane of axes i and j,
 * turning axis i towards axis j. */
static mat4 rotation_in_plane(int i, int j, double s, double c)
{
    mat4 a = mat4_identity();
    a.m[i][i] = c, a.m[i][j] = -s;
    a.m[j][i] = s, a.m[j][j] = c;
    return a;
}

mat4 mat4_rotate_x(double deg)
{
    double s, c;
    sin_cos_deg(deg, &s, &c);
    return rotation_in_plane(1, 2, s, c); /* y towards z */
}

mat4 mat4_rotate_y(double deg)
{
    double s, c;
    sin_cos_deg(deg, &s, &c);
    return rotation_in_plane(2, 0, s, c); /* z towards x */
}

mat4 mat4_rotate_z(double deg)
{
    double s, c;
    sin_cos_deg(deg, &s, &c);
    return rotation_in_plane(0, 1, s, c); /* x towards y */
}

mat4 mat4_rotate(vec3 a, double deg)
{
    if (a.y == 0 && a.z == 0 && a.x == 1)
        return mat4_rotate_x(deg); /* exactly the sheet's matrices */
    if (a.x == 0 && a.z == 0 && a.y == 1)
        return mat4_rotate_y(deg);
    if (a.x == 0 && a.y == 0 && a.z == 1)
        return mat4_rotate_z(deg);
    double s, c;
    sin_cos_deg(deg, &s, &c);
    double u[3] = {a.x, a.y, a.z}, k = 1 - c;
    double cross[3][3] = {{0, -a.z, a.y}, {a.z, 0, -a.x}, {-a.y, a.x, 0}};
    mat4 r = mat4_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.m[i][j] = (i == j ? c : 0) + k * u[i] * u[j] + s * cross[i][j];
    return r;
}

mat4 mat4_shear_yz(double dy, double dz)
{
    mat4 a = mat4_identity();
    a.m[1][0] = dy, a.m[2][0] = dz; /* y += dy x, z += dz x */
    return a;
}

mat4 mat4_shear_xz(double dx, double dz)
{
    mat4 a = mat4_identity();
    a.m[0][1] = dx, a.m[2][1] = dz; /* x += dx y, z += dz y */
    return a;
}

mat4 mat4_shear_xy(double dx, double dy)
{
    mat4 a = mat4_identity();
    a.m[0][2] = dx, a.m[1][2] = dy; /* x += dx z, y += dy z */
    return a;
}

/* <<inverses>> ch05 */
double mat4_det3(mat4 a)
{
    mat4 c = mat4_cofactor3(a);
    return a.m[0][0] * c.m[0][0] + a.m[0][1] * c.m[0][1] +
           a.m[0][2] * c.m[0][2];
}

mat4 mat4_cofactor3(mat4 a)
{
    double(*m)[4] = a.m;
    mat4 c = mat4_identity(); /* the translation and w parts stay 0 0 0 1 */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3; /* cyclic: the signs */
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3; /* come out right */
            c.m[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
        }
    return c;
}

bool mat4_inverse_affine(mat4 a, mat4 *out)
{
    mat4 c = mat4_cofactor3(a);
    double det = a.m[0][0] * c.m[0][0] + a.m[0][1] * c.m[0][1] +
                 a.m[0][2] * c.m[0][2];
    if (det == 0 || !isfinite(det))
        return false;
    mat4 inv = mat4_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            inv.m[i][j] = c.m[j][i] / det; /* the adjugate over det */
    for (int i = 0; i < 3; i++)
        inv.m[i][3] = -(inv.m[i][0] * a.m[0][3] + inv.m[i][1] * a.m[1][3] +
                        inv.m[i][2] * a.m[2][3]); /* -A^-1 t */
    *out = inv;
    return true;
}

static void swap_rows(mat4 *a, int i, int j)
{
    for (int k = 0; k < 4; k++) {
        double t = a->m[i][k];
        a->m[i][k] = a->m[j][k], a->m[j][k] = t;
    }
}

/* Row i -= f row j, in a and in its companion b. */
static void subtract_row(mat4 *a, mat4 *b, int i, int j, double f)
{
    for (int k = 0; k < 4; k++) {
        a->m[i][k] -= f * a->m[j][k];
        b->m[i][k] -= f * b->m[j][k];
    }
}

bool mat4_inverse(mat4 a, mat4 *out)
{
    mat4 inv = mat4_identity();
    for (int col = 0; col < 4; col++) {
        int pivot = col;
        for (int r = col + 1; r < 4; r++)
            if (fabs(a.m[r][col]) > fabs(a.m[pivot][col]))
                pivot = r; /* the largest: multipliers below it within 1 */
        if (a.m[pivot][col] == 0)
            return false; /* the column is zero from here down: singular */
        swap_rows(&a, col, pivot), swap_rows(&inv, col, pivot);
        double scale = 1 / a.m[col][col];
        for (int k = 0; k < 4; k++)
            a.m[col][k] *= scale, inv.m[col][k] *= scale;
        for (int r = 0; r < 4; r++)
            if (r != col)
                subtract_row(&a, &inv, r, col, a.m[r][col]);
    }
    *out = inv;
    return true;
}

double mat4_norm3(mat4 a)
{
    double largest = 0;
    for (int i = 0; i < 3; i++) {
        double row = fabs(a.m[i][0]) + fabs(a.m[i][1]) + fabs(a.m[i][2]);
        largest = row > largest || row != row ? row : largest; /* NaN wins */
    }
    return largest;
}

bool mat4_is_finite(mat4 a)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(a.m[i][j]))
                return false;
    return true;
}

/* <<the look-at frame>> ch05 */
/* Below this sine of the angle between up and the view, the picture's
 * roll would be decided by rounding: 1e-6 rad is 0.00006 degrees. */
#define MIN_UP_SINE 1e-6

bool mat4_look_at(vec3 eye, vec3 target, vec3 up, mat4 *out)
{
    vec3 view = vec3_sub(target, eye);
    double up_length = vec3_length(up); /* the scene's is a unit vector */
    if (!vec3_is_direction(view) || !(up_length > 0))
        return false;
    vec3 z = vec3_normalize_scaled(view); /* however near the target is */
    vec3 side = vec3_cross(up, z); /* up x forward: right, left-handed */
    double side_length = vec3_length(side);
    if (!(side_length / up_length >= MIN_UP_SINE))
        return false;
    vec3 x = vec3_scale(side, 1 / side_length), y = vec3_cross(z, x);
    vec3 column[4] = {x, y, z, eye};
    mat4 m = mat4_identity();
    for (int j = 0; j < 4; j++)
        m.m[0][j] = column[j].x, m.m[1][j] = column[j].y,
        m.m[2][j] = column[j].z;
    *out = m;
    return true;
}

/* <<transforms built with their inverses>> ch05 */
transform transform_identity(void)
{
    return (transform){mat4_identity(), mat4_identity()};
}

transform transform_then(transform first, transform next)
{
    return (transform){mat4_mul(next.m, first.m),
                       mat4_mul(first.inv, next.inv)};
}

transform transform_translate(vec3 t)
{
    return (transform){mat4_translate(t),
                       mat4_translate(vec3_scale(t, -1))};
}

transform transform_scale(vec3 s)
{
    return (transform){mat4_scale(s),
                       mat4_scale((vec3){1 / s.x, 1 / s.y, 1 / s.z})};
}

transform transform_rotate(vec3 a, double deg)
{
    mat4 r = mat4_rotate(a, deg);
    return (transform){r, mat4_transpose(r)}; /* orthogonal: R^-1 = R^T */
}

transform transform_shear(mat4 shear)
{
    mat4 inv = shear;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (i != j)
                inv.m[i][j] = -shear.m[i][j]; /* I + N -> I - N */
    return (transform){shear, inv};
}

bool transform_of_matrix(mat4 m, transform *out)
{
    out->m = m;
    return mat4_inverse(m, &out->inv); /* Gauss-Jordan: see the chart */
}
