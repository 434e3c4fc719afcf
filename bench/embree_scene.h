/* embree_scene.h: a mesh given to Intel Embree 3 as a scene of one
 * triangle geometry, its vertices in float, built at the given quality
 * (the benchmarks of chapter 10). The caller commits the scene. */
#ifndef EMBREE_SCENE_H
#define EMBREE_SCENE_H

#include <embree3/rtcore.h>

#include "mesh.h"

static inline RTCScene embree_scene(RTCDevice device, const mesh *m,
                                    enum RTCBuildQuality quality)
{
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), (size_t)m->vertex_count);
    for (int k = 0; k < m->vertex_count; k++) {
        v[3 * k] = (float)m->vertices[k].x;
        v[3 * k + 1] = (float)m->vertices[k].y;
        v[3 * k + 2] = (float)m->vertices[k].z;
    }
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)m->triangle_count);
    for (int k = 0; k < m->triangle_count; k++)
        for (int c = 0; c < 3; c++)
            ix[3 * k + c] = (unsigned)m->triangles[k].v[c];
    rtcSetGeometryBuildQuality(g, quality);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return scene;
}

#endif
