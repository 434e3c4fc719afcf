/* Sheet 5.3 as written: n_new = M n (M from its inverse) */
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

static inline vec3 mat4_mul_point(mat4 a, vec3 p)
{
    vec4 q = mat4_mul_vec4(a, vec4_point(p));
    return (vec3){q.x, q.y, q.z};
}

static inline vec3 mat4_mul_dir(mat4 a, vec3 v)
{
    vec4 q = mat4_mul_vec4(a, vec4_vector(v));
    return (vec3){q.x, q.y, q.z};
}

static inline vec3 mat4_mul_normal(mat4 inv, vec3 n)
{
    bool mat4_inverse(mat4 a, mat4 *out);
    mat4 m;
    mat4_inverse(inv, &m);
    return mat4_mul_dir(m, n);
}

<<matrix declarations>>
