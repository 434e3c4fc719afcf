/* Sheet 1.4 as written: the camera at the origin, D = sqrt(|c|^2 - <c,d>^2) */
int SPHERE_FORM(robust)(vec3 center, double radius, ray r, double t[2])
{
    rvec c = rvec_from(center), d = rvec_from(r.dir);
    real a = rvec_dot(c, d);
    real D = real_sqrt(rvec_dot(c, c) - a * a);
    if (!(D <= (real)radius))
        return 0;
    real half_chord = real_sqrt((real)radius * (real)radius - D * D);
    t[0] = (double)(a - half_chord);
    t[1] = (double)(a + half_chord);
    return 2;
}
