/* surface_normal.h — the normals of a point on a triangle, as every exact surface in voxr reports them
 * (SurfaceSample.normal and geometric_normal): raster_resolve.cl for the camera's samples, refract_exact.cl
 * for the surfaces its paths meet; host/reference/reference_scene.cpp ReferenceScene::intersect mirrors it.
 *   geometric: the unit normal of (p0, p1, p2)'s winding (-dir for a degenerate triangle);
 *   shading:   the vertex normals interpolated with weights (1 - u - v, u, v), each vertex normal more than
 *              45 degrees (VOXR_CREASE_COS) off the geometric one replaced by it (the crease rule), and the
 *              result replaced by the geometric normal if it still turns more than 45 degrees from it.
 * Both are turned towards the ray's origin (the geometric normal's flip turns both); a shading normal that
 * still faces away is replaced by the geometric one (the side rule). */
#ifndef VOXR_SURFACE_NORMAL_H
#define VOXR_SURFACE_NORMAL_H

#include "voxr_layout.h"

#pragma OPENCL FP_CONTRACT OFF

inline void sn_normals(float3 p0, float3 p1, float3 p2, float3 n0, float3 n1, float3 n2, float u, float v,
                       float3 dir, float3* shading, float3* geometric) {
  const float w = 1.0f - u - v;
  float3 ng = cross(p1 - p0, p2 - p0);
  const float ng_length = length(ng);
  ng = ng_length > 0.0f ? ng / ng_length : -dir;
  if (dot(n0, ng) < VOXR_CREASE_COS) n0 = ng;
  if (dot(n1, ng) < VOXR_CREASE_COS) n1 = ng;
  if (dot(n2, ng) < VOXR_CREASE_COS) n2 = ng;
  float3 ns = w * n0 + u * n1 + v * n2;
  const float ns_length = length(ns);
  ns = ns_length > 0.0f ? ns / ns_length : ng;
  if (dot(ns, ng) < VOXR_CREASE_COS) ns = ng;
  if (dot(ng, dir) > 0.0f) {
    ng = -ng;
    ns = -ns;
  }
  if (dot(ns, dir) > 0.0f) ns = ng;
  *shading = ns;
  *geometric = ng;
}

#endif
