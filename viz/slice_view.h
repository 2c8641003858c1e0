// The slice view: three orthogonal planes through the volume (one per grid axis), each showing the
// channel's colours voxel by voxel (nearest sampling, planes reach the voxels' outer faces). The planes
// move one voxel at a time.
#pragma once

#include <vtkImageProperty.h>
#include <vtkImageSlice.h>
#include <vtkImageSliceMapper.h>
#include <vtkNew.h>

#include <array>

class vtkMatrix4x4;
class vtkRenderer;

#include "display_field.h"
#include "transfer_presets.h"

namespace voxr::view {

class SliceView {
 public:
  // `dims` of the volume; the planes start at the middle of each axis.
  SliceView(vtkRenderer* renderer, vtkMatrix4x4* to_world, const int dims[3]);
  void set_field(const DisplayField& field, const TransferPreset& preset);
  void set_visible(bool visible);
  // Clamps `index` to the axis.
  void set_index(int axis, long index);
  void move(int axis, int delta) { set_index(axis, index_[axis] + delta); }
  int index(int axis) const { return index_[axis]; }

 private:
  std::array<int, 3> dims_{};
  std::array<int, 3> index_{};
  vtkNew<vtkImageProperty> property_;
  std::array<vtkNew<vtkImageSliceMapper>, 3> mappers_;
  std::array<vtkNew<vtkImageSlice>, 3> slices_;
};

}  // namespace voxr::view
