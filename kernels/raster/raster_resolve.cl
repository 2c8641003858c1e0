/* raster_resolve.cl — what the camera sees at each pixel (voxr_layout.h SurfaceSample), from the visibility
 * buffer (raster_depth.cl): the pixel-centre ray of the camera (CameraFrame::ray_direction) intersected with
 * the plane of the pixel's triangle gives the exact position and distance, the barycentrics (of vertices 1
 * and 2, clamped to the triangle: snapping lets a covered centre lie a hair outside it), and the geometric
 * and shading normals turned towards the eye (surface_normal.h: the crease and side rules). Pixels without a
 * triangle get VOXR_NO_TRIANGLE and zeros. in: camera, visibility words, positions (float4), triangles
 * (uint4), vertex normals (float4, xyz unit) out: samples[y * width + x] shape: one work item per pixel. */
#include "surface_normal.h"
#include "voxr_layout.h"

#pragma OPENCL FP_CONTRACT OFF

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_resolve(
    RenderCamera cam, __global const ulong* visibility, __global const float4* positions,
    __global const uint4* triangles, __global const float4* normals, uint triangle_count,
    __global SurfaceSample* samples) {
  const uint gid = get_global_id(0);
  const uint pixels = cam.width * cam.height;
  if (gid >= pixels) return;
  __global SurfaceSample* out = samples + gid;
  const uint t = (uint)visibility[gid];
  if (t >= triangle_count) {
    for (int a = 0; a < 3; ++a) {
      out->position[a] = 0.0f;
      out->normal[a] = 0.0f;
      out->geometric_normal[a] = 0.0f;
    }
    out->triangle = VOXR_NO_TRIANGLE;
    out->material = 0;
    out->distance = 0.0f;
    out->barycentric[0] = 0.0f;
    out->barycentric[1] = 0.0f;
    out->pad[0] = 0.0f;
    out->pad[1] = 0.0f;
    return;
  }
  const uint4 tri = triangles[t];
  const float3 p0 = positions[tri.x].xyz, p1 = positions[tri.y].xyz, p2 = positions[tri.z].xyz;
  const float3 eye = (float3)(cam.eye[0], cam.eye[1], cam.eye[2]);
  const float3 forward = (float3)(cam.forward[0], cam.forward[1], cam.forward[2]);
  const float3 right = (float3)(cam.right[0], cam.right[1], cam.right[2]);
  const float3 up = (float3)(cam.up[0], cam.up[1], cam.up[2]);
  const float px = (float)(gid % cam.width) + 0.5f, py = (float)(gid / cam.width) + 0.5f;
  const float sx = (2.0f * px / (float)cam.width - 1.0f) * cam.tan_half_fov_y * cam.aspect;
  const float sy = (1.0f - 2.0f * py / (float)cam.height) * cam.tan_half_fov_y;
  const float3 dir = normalize(forward + sx * right + sy * up);

  /* Moller-Trumbore against the triangle's plane. */
  const float3 e1 = p1 - p0, e2 = p2 - p0;
  const float3 pv = cross(dir, e2);
  const float det = dot(e1, pv);
  float u, v, dist;
  if (fabs(det) > 1e-7f * length(e1) * length(e2)) {
    const float inv = 1.0f / det;
    const float3 tv = eye - p0;
    const float3 qv = cross(tv, e1);
    u = dot(tv, pv) * inv;
    v = dot(dir, qv) * inv;
    dist = dot(e2, qv) * inv;
  } else { /* the ray runs in the plane (an edge-on triangle a snapped centre still hit): its centroid */
    u = v = 1.0f / 3.0f;
    dist = dot((p0 + p1 + p2) / 3.0f - eye, dir);
  }
  const float3 position = eye + dist * dir;
  u = max(u, 0.0f);
  v = max(v, 0.0f);
  if (u + v > 1.0f) {
    const float s = u + v;
    u /= s;
    v /= s;
  }
  float3 ns, ng;
  sn_normals(p0, p1, p2, normals[tri.x].xyz, normals[tri.y].xyz, normals[tri.z].xyz, u, v, dir, &ns, &ng);

  out->position[0] = position.x;
  out->position[1] = position.y;
  out->position[2] = position.z;
  out->triangle = t;
  out->normal[0] = ns.x;
  out->normal[1] = ns.y;
  out->normal[2] = ns.z;
  out->material = tri.w;
  out->geometric_normal[0] = ng.x;
  out->geometric_normal[1] = ng.y;
  out->geometric_normal[2] = ng.z;
  out->distance = dist;
  out->barycentric[0] = u;
  out->barycentric[1] = v;
  out->pad[0] = 0.0f;
  out->pad[1] = 0.0f;
}
