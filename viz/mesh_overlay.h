// The source mesh drawn over the voxels in world coordinates, to check that voxels and triangles line up.
// Loaded with voxr's own loader (load_input: a mesh file, or a scene .json with its transforms), so the
// overlay holds exactly the triangles the voxelizer saw. Two parts:
//  - the whole mesh, as a wireframe or a translucent surface (or hidden);
//  - in the slice view, the mesh's cross-section with each slice plane, drawn as lines on the plane, so
//    every line must run through set voxels of that slice.
#pragma once

#include <vtkActor.h>
#include <vtkCutter.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPolyData.h>

#include <array>
#include <filesystem>

class vtkRenderer;

#include "view_options.h"

namespace voxr::view {

class MeshOverlay {
 public:
  // Throws voxr::Error naming the file when it cannot be loaded.
  MeshOverlay(vtkRenderer* renderer, const std::filesystem::path& file, MeshStyle style);
  void set_style(MeshStyle style);
  MeshStyle style() const { return style_; }
  size_t triangles() const { return triangles_; }

  // World-space plane of slice `axis` (a point on it and its normal).
  void set_cut_plane(int axis, const double origin[3], const double normal[3]);
  // In the slice view the overlay is the cross-sections alone (the whole mesh would hide the planes);
  // elsewhere it is the whole mesh. Either way MeshStyle::kHidden hides it.
  void set_slice_mode(bool slices);

 private:
  void update_visibility();

  vtkNew<vtkPolyData> mesh_;
  vtkNew<vtkActor> actor_;
  std::array<vtkNew<vtkPlane>, 3> planes_;
  std::array<vtkNew<vtkCutter>, 3> cutters_;
  std::array<vtkNew<vtkActor>, 3> cut_actors_;
  MeshStyle style_;
  bool slice_mode_ = false;
  size_t triangles_ = 0;
};

}  // namespace voxr::view
