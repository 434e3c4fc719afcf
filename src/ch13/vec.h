/* vec.h: 3-vectors and rays (chapter 1).
 *
 * A vec3 is a point, a direction or a linear RGB colour; the function's name
 * says which it expects. All functions take and return values, never
 * pointers, and never fail. */
#ifndef VEC_H
#define VEC_H

#include <math.h>

typedef struct {
    double x, y, z;
} vec3;

/* <<vector operations>> ch01 */
static inline vec3 vec3_add(vec3 a, vec3 b)
{
    return (vec3){a.x + b.x, a.y + b.y, a.z + b.z};
}

static inline vec3 vec3_sub(vec3 a, vec3 b)
{
    return (vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}

static inline vec3 vec3_scale(vec3 a, double s)
{
    return (vec3){a.x * s, a.y * s, a.z * s};
}

/* Component by component: how a surface colour filters a light colour. */
static inline vec3 vec3_mul(vec3 a, vec3 b)
{
    return (vec3){a.x * b.x, a.y * b.y, a.z * b.z};
}

static inline double vec3_dot(vec3 a, vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline double vec3_length(vec3 a) { return sqrt(vec3_dot(a, a)); }

/* a scaled to length 1; a must not be the zero vector. */
static inline vec3 vec3_normalize(vec3 a)
{
    return vec3_scale(a, 1.0 / vec3_length(a));
}

/* (1 - t) a + t b: a at t = 0, b at t = 1. */
static inline vec3 vec3_lerp(vec3 a, vec3 b, double t)
{
    return vec3_add(vec3_scale(a, 1.0 - t), vec3_scale(b, t));
}

/* <<math constants>> ch01 */
#ifndef M_PI
#define M_PI 3.14159265358979323846 /* POSIX has it; strict C11 does not */
#endif
/* <<vector operations>> += ch03 */

/* Is a finite and not zero: a direction that can be normalised? */
static inline int vec3_is_direction(vec3 a)
{
    int finite = isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
    return finite && (a.x != 0 || a.y != 0 || a.z != 0);
}

/* The unit vector along a, for any a that vec3_is_direction accepts. */
static inline vec3 vec3_normalize_scaled(vec3 a)
{
    double d = vec3_dot(a, a);
    if (d >= 0x1p-900 && d <= 0x1p900)
        return vec3_normalize(a); /* no square lost a bit that matters */
    double m = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    return vec3_normalize((vec3){a.x / m, a.y / m, a.z / m});
}
/* <<vector operations>> += ch04 */

static inline vec3 vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
}
/* <<vector operations>> += ch06 */

/* i mirrored about the plane with unit normal n: i - 2 n <n, i>. */
static inline vec3 vec3_reflect(vec3 i, vec3 n)
{
    return vec3_sub(i, vec3_scale(n, 2 * vec3_dot(n, i)));
}
/* <<vector operations>> += ch08 */

/* Component axis (0: x, 1: y, 2: z) of v. */
static inline double vec3_axis(vec3 v, int axis)
{
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

static inline void vec3_set_axis(vec3 *v, int axis, double value)
{
    *(axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z) = value;
}

/* Component by component: the corners of the box around a and b. */
static inline vec3 vec3_min(vec3 a, vec3 b)
{
    return (vec3){a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y,
                  a.z < b.z ? a.z : b.z};
}

static inline vec3 vec3_max(vec3 a, vec3 b)
{
    return (vec3){a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y,
                  a.z > b.z ? a.z : b.z};
}

/* <<ray type>> ch01 */
/* The half-line origin + t dir, t >= 0. Rays made by the renderer have
 * |dir| = 1, so that t is a distance. */
typedef struct {
    vec3 origin, dir;
} ray;

static inline vec3 ray_at(ray r, double t)
{
    return vec3_add(r.origin, vec3_scale(r.dir, t));
}

/* <<matrices>> ch05 */
#include <stdbool.h>

/* <<homogeneous coordinates>> ch05 */
/* A point (w = 1) or a vector (w = 0) in homogeneous coordinates
 * (chapter 5). A sum whose w is anything else is neither. */
typedef struct {
    double x, y, z, w;
} vec4;

static inline vec4 vec4_point(vec3 p) { return (vec4){p.x, p.y, p.z, 1}; }
static inline vec4 vec4_vector(vec3 v) { return (vec4){v.x, v.y, v.z, 0}; }

static inline vec4 vec4_add(vec4 a, vec4 b)
{
    return (vec4){a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
}

static inline vec4 vec4_scale(vec4 a, double s)
{
    return (vec4){a.x * s, a.y * s, a.z * s, a.w * s};
}

static inline bool vec4_is_point(vec4 a) { return a.w == 1; }
static inline bool vec4_is_vector(vec4 a) { return a.w == 0; }

/* <<4x4 matrices>> ch05 */
/* A 4x4 matrix m[row][column] acting on column vectors (chapter 5). The
 * program's matrices are affine: their last row is 0 0 0 1. */
typedef struct {
    double m[4][4];
} mat4;

static inline vec4 mat4_mul_vec4(mat4 a, vec4 v)
{
    double r[4];
    for (int i = 0; i < 4; i++)
        r[i] = a.m[i][0] * v.x + a.m[i][1] * v.y + a.m[i][2] * v.z +
               a.m[i][3] * v.w;
    return (vec4){r[0], r[1], r[2], r[3]};
}

/* M p for a point (w = 1) and an affine M: the translation applies. */
static inline vec3 mat4_mul_point(mat4 a, vec3 p)
{
    double(*m)[4] = a.m;
    return (vec3){m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                  m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                  m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}

/* M v for a vector (w = 0): the translation does not apply. */
static inline vec3 mat4_mul_dir(mat4 a, vec3 v)
{
    double(*m)[4] = a.m;
    return (vec3){m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                  m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                  m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

/* (M^-1)^T n, given inv = M^-1: how a normal moves with M (sheet 5.3).
 * Not normalised. */
static inline vec3 mat4_mul_normal(mat4 inv, vec3 n)
{
    double(*m)[4] = inv.m;
    return (vec3){m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z,
                  m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
                  m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z};
}

/* <<matrix declarations>> ch05 */
mat4 mat4_identity(void);
/* a b: the transform that applies b first, then a. */
mat4 mat4_mul(mat4 a, mat4 b);
mat4 mat4_transpose(mat4 a);

/* The sheet's standard matrices (section 5.2); angles in degrees, exact
 * at multiples of 90. A positive angle turns y towards z about x, z
 * towards x about y, and x towards y about z: counter-clockwise seen
 * from the origin looking along the axis, in this left-handed frame. */
mat4 mat4_translate(vec3 t);
mat4 mat4_scale(vec3 s);
mat4 mat4_rotate_x(double deg);
mat4 mat4_rotate_y(double deg);
mat4 mat4_rotate_z(double deg);
/* About the unit axis a through the origin (Rodrigues' formula). */
mat4 mat4_rotate(vec3 a, double deg);
/* S_yz: y += dy x, z += dz x. S_xz: x += dx y, z += dz y. S_xy: x += dx
 * z, y += dy z. */
mat4 mat4_shear_yz(double dy, double dz);
mat4 mat4_shear_xz(double dx, double dz);
mat4 mat4_shear_xy(double dx, double dy);

/* Of the 3x3 part A: its determinant; its cofactor matrix (entry ij is
 * (-1)^(i+j) times the minor without row i and column j), which is
 * det(A) (A^-1)^T; its largest absolute row sum, the infinity norm. */
double mat4_det3(mat4 a);
mat4 mat4_cofactor3(mat4 a);
double mat4_norm3(mat4 a);
/* Every entry is a finite number. */
bool mat4_is_finite(mat4 a);

/* The inverse of a by Gauss-Jordan elimination with partial pivoting, for
 * any 4x4; false when a is singular (a pivot is exactly zero). */
bool mat4_inverse(mat4 a, mat4 *out);
/* The inverse of an affine a: the 3x3 part A by its cofactors over
 * det(A), then -A^-1 t; false when det(A) is zero or not finite. */
bool mat4_inverse_affine(mat4 a, mat4 *out);

/* The camera-to-world matrix of an eye at eye looking at target, with up
 * pointing up in the picture: its columns are the camera's x (right), y
 * (up) and z (forward) in the world, and the eye. false when target is
 * eye, or up is zero or (nearly) along the view. */
bool mat4_look_at(vec3 eye, vec3 target, vec3 up, mat4 *out);

/* <<transforms and their inverses>> ch05 */
/* An affine transform m, from an object's space to the world, and its
 * inverse inv (chapter 5). Each standard step's inverse is known in
 * closed form, so a transform built from steps never inverts a matrix. */
typedef struct {
    mat4 m, inv;
} transform;

transform transform_identity(void);
/* first, then next: m = next.m first.m, inv = first.inv next.inv. */
transform transform_then(transform first, transform next);
transform transform_translate(vec3 t);
/* A zero factor is singular: its inverse has infinite entries. */
transform transform_scale(vec3 s);
/* About the unit axis a (Rodrigues' formula); exact for 90 degrees. */
transform transform_rotate(vec3 a, double deg);
/* One of the sheet's shears, S = I + N with N N = 0: inverse I - N. */
transform transform_shear(mat4 shear);
/* Any affine matrix, inverted by Gauss-Jordan (mat4_inverse); false when
 * it is singular. */
bool transform_of_matrix(mat4 m, transform *out);

#endif
