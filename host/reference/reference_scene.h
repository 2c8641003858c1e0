// The exact reference for everything that renders (DESIGN.md, "Materials and the reference"): the scene's
// triangles in an Embree 3 BVH, intersected in single precision with Embree's watertight test, positions
// relative to the scene's anchor as everywhere else.
//
// Shadow rays are straight (not refracted): their transmittance is the product of every sheet's per-crossing
// transmittance and exp(-sigma_a * length) through every dielectric along the segment to the light; an
// opaque hit blocks. That is the quantity a transparent shadow map approximates.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/material.h"
#include "core/triangle_soup.h"
#include "shadow_tolerances.h"
#include "voxr_layout.h"

namespace voxr {

class ReferenceScene {
 public:
  // Builds the BVH over `soup` (material ids index `materials`). Throws voxr::Error when Embree fails or a
  // material id is out of range. The soup is copied.
  ReferenceScene(const TriangleSoup& soup, const std::vector<Material>& materials);
  ~ReferenceScene();
  ReferenceScene(const ReferenceScene&) = delete;
  ReferenceScene& operator=(const ReferenceScene&) = delete;

  // Wall time of the BVH build. Rays with a direction component of 0 (axis-parallel) are also traced in
  // mirrored copies of the BVH (an Embree node test loses boxes whose upper bound lies exactly on such a
  // ray); those copies are built on first need, inside intersect/transmittance, and not counted here.
  double build_ms() const;

  // Largest side of the soup's bounds (1 for an empty scene): the scale of the tolerances below.
  float scene_size() const;

  // The unit normal of triangle `triangle`'s winding, cross(p1 - p0, p2 - p0) normalized (outward for a
  // closed mesh wound counter-clockwise seen from outside; 0 for a zero-area triangle): what says whether a
  // ray enters or leaves a dielectric (media_stack.h). Throws voxr::Error for an id out of range.
  glm::vec3 winding_normal(uint32_t triangle) const;

  // The nearest hit of the ray origin + t * dir, t in (t_near, t_far), as a SurfaceSample (triangle =
  // VOXR_NO_TRIANGLE on a miss; normals unit and turned towards the origin; shading normal interpolated from
  // angle-weighted vertex normals, as the rasterizer's resolve does).
  // Coincident hits: of the hits less than kMergeDistance * scene_size() beyond the nearest (coplanar
  // surfaces, e.g. a glass face standing on a floor, which float rounding orders either way), an opaque one
  // wins over a sheet or a dielectric (an opaque nearest hit wins outright: of coincident opaque ones the
  // nearer, then the lower id); among sheets and dielectrics one the ray enters (its winding's normal faces
  // the ray) wins over one it leaves, so two solids sharing a face are one interface, then the lowest
  // triangle id: the result does not depend on BVH order, rounding's choice or the thread count.
  // Embree traces the normalized direction: position = origin + t * dir as Embree found it, distance =
  // t * |dir| (world units); barycentric = Embree's (u, v), the weights of vertices 1 and 2. Shading normal:
  // render/vertex_normals.h interpolated with (1 - u - v, u, v) and normalized; where it deviates from the
  // triangle's normal by more than 45 degrees (a sharp crease) the triangle's normal is used, per corner
  // first (voxr_layout.h VOXR_CREASE_COS), then for the interpolated normal. Both are then turned towards
  // the origin by the geometric normal's flip, and a shading normal that still faces away is replaced by the
  // geometric one (the resolve's rule). Throws voxr::Error for a zero or non-finite dir.
  SurfaceSample intersect(const glm::vec3& origin, const glm::vec3& dir, float t_near = 0.0f,
                          float t_far = 3.0e38f) const;

  // The nearest hit of a ray leaving the surface point `origin` (found by intersect on the triangles
  // `leaving`: the one it left, and any coincident ones it passed at the same point; 1 to 8 ids): the
  // triangles in `leaving` are skipped at any t (a ray leaving a plane does not meet it again), and so are,
  // within kMergeDistance * scene_size() of the origin, triangles that share a vertex index with one of them
  // (the same surface at a shared edge or vertex, which the rounded origin may lie a hair beyond). Nothing
  // else is skipped: every other surface counts from kMergeDistance * scene_size() behind the origin, so a
  // coplanar one (a floor under a glass face) is met at distance ~0 whichever side of it rounding put the
  // origin; the coincident-hit rule of intersect applies. distance is clamped to >= 0, position is
  // origin + t * normalize(dir) with the signed t. The tolerance is the shadow rays' merge distance: 100x
  // the rounding of a hit point (a few float ulps of the scene's size), far below any modelled thickness.
  // Throws voxr::Error for a zero or non-finite dir, an empty `leaving` or more than 8 ids.
  SurfaceSample intersect_leaving(const glm::vec3& origin, const glm::vec3& dir,
                                  std::span<const uint32_t> leaving) const;

  // Hits nearer than kStartEpsilon * scene_size() along a shadow ray are ignored (with those on `self`): a
  // surface point computed by a primary ray lies off its plane by rounding, and would otherwise see its own
  // or a neighbouring coplanar triangle. A surface closer than that to the receiver casts no shadow on it.
  static constexpr float kStartEpsilon = VOXR_SHADOW_START_EPSILON;
  // Hits less than kMergeDistance * scene_size() apart along a shadow ray, on triangles that share a vertex
  // index, are one meeting of the ray with one surface (at a shared edge or vertex). The same tolerance says
  // which hits are coincident (intersect) and how near its origin a leaving ray skips the surface it left
  // (intersect_leaving).
  static constexpr float kMergeDistance = VOXR_SHADOW_MERGE_DISTANCE;

  // RGB transmittance from `point` (on triangle `self`, VOXR_NO_TRIANGLE for none) to the light, along the
  // straight segment. Every crossing counts once: a ray through an edge shared by two triangles of one mesh
  // crosses one surface, two coincident triangles are two surfaces.
  // How: one Embree traversal from `point` towards the light (the light's position, or -direction to
  // infinity) with a filter that records every hit and rejects it; the hits are sorted by t and grouped as
  // kMergeDistance says. A group where the ray only touches the surface (through a shared edge whose two
  // faces lie on one side of the ray, or a vertex whose faces face the ray with both sides by winding: a
  // grazed fold or corner) is no crossing. Every other group is one crossing of each distinct material in it:
  // an opaque one before the light gives 0, a sheet multiplies by its transmittance, a dielectric toggles
  // in or out of its material id by the winding of the group's first face of it (media_stack.h
  // VoxrSolidLedger), and the lengths inside multiply by exp(-sigma_a * length).
  // Inside at the start: the ray is followed past a point light to infinity, where it is outside every
  // solid, so the depth at the receiver is minus the sum of the crossings (+1 entered, -1 left): a receiver
  // inside nested solids of one glass is inside all of them, and the space inside an inner solid of the same
  // glass absorbs too. A material whose depth would be negative somewhere (open or inside-out meshes) is
  // taken by parity as before: an odd number of crossings means the segment starts inside. A point light
  // inside a solid ends its last interval.
  glm::vec3 transmittance(const RenderLight& light, const glm::vec3& point, uint32_t self) const;
  // The same for every sample with a triangle (others get 1), on all cores (std::thread, blocks of samples;
  // the result does not depend on the thread count).
  std::vector<glm::vec3> transmittance(const RenderLight& light,
                                       std::span<const SurfaceSample> samples) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxr
