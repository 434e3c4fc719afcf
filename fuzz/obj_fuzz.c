/* obj_fuzz.c: libFuzzer target for the OBJ reader of the latest chapter.
 *
 * Each input is parsed as an OBJ file. A mesh that parses gets smooth
 * normals and its bounding box, and a fan of rays through the box is
 * intersected with it: the vertices the parser let through reach the
 * watertight test and the normal interpolation, whose results must be
 * finite. */
#include <stdint.h>
#include <stdlib.h>

#include "obj.h"

/* Rays from in front of the box towards points spread over it. */
static void shoot_rays(const mesh *m)
{
    vec3 centre = vec3_scale(vec3_add(m->bounds.lo, m->bounds.hi), 0.5);
    vec3 size = vec3_sub(m->bounds.hi, m->bounds.lo);
    vec3 origin = vec3_sub(centre, (vec3){0.3 * size.x, 0.2 * size.y, 2 * size.z + 1});
    for (int k = 0; k < 16; k++) {
        vec3 target = vec3_add(m->bounds.lo, (vec3){size.x * (k % 4) / 3.0, size.y * (k / 4) / 3.0,
                                             size.z * 0.5});
        vec3 d = vec3_sub(target, origin);
        if (!(vec3_dot(d, d) > 0) || !isfinite(vec3_dot(d, d)))
            continue;
        hit h;
        long long tests = 0;
        ray r = {origin, vec3_normalize(d)};
        if (mesh_intersect(m, r, 0, INFINITY, &h, &tests) &&
            !(isfinite(h.t) && isfinite(h.normal.x) && isfinite(h.normal.y) &&
              isfinite(h.normal.z)))
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mesh m = {0};
    parse_error err;
    if (mesh_parse_obj(&m, (const char *)data, size, "fuzz.obj", &err) && m.vertex_count > 0) {
        if (m.normal_count == 0 && !mesh_smooth_normals(&m)) /* as `mesh ... smooth` does */
            abort();
        mesh_compute_bounds(&m);
        shoot_rays(&m);
    }
    mesh_free(&m);
    return 0;
}
