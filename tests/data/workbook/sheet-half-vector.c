/* Sheet 2.4 as written: h = (l + v) / 2 */
double phong_cosine(vec3 n, vec3 l, vec3 v)
{
    vec3 r = vec3_sub(vec3_scale(n, 2.0 * vec3_dot(n, l)), l);
    double rv = vec3_dot(r, v);
    return rv > 0 ? rv : 0;
}

double blinn_cosine(vec3 n, vec3 l, vec3 v)
{
    double nh = vec3_dot(n, vec3_scale(vec3_add(l, v), 0.5));
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
