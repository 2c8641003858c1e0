// What the views draw for one array of a volume: a one-component scalar image on the volume's geometry in
// which voxels the array has no value for ("empty") hold a value below every set voxel's, and the mask of
// set voxels. voxr's sparse channels store 0 for empty voxels, but 0 is also a material id and a normal
// component, so material and normal components are moved to distinct empty values here; occupancy, inside
// and count are used as they are (0 = empty already). voxr's color channel (RGBA8) is shown as the colours
// themselves: its scalars are four unsigned char components, RGB as stored and alpha 255 where a voxel is set
// and 0 where it is empty, which the views draw directly (no lookup table).
#pragma once

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

#include "volume_loader.h"

namespace voxr::view {

// How an array is presented, from its name (voxr's channel names; anything else is kGeneric).
enum class ChannelKind { kOccupancy, kInside, kCount, kNormal, kMaterial, kColor, kGeneric };

ChannelKind channel_kind(const std::string& array_name);

struct DisplayField {
  std::string array;
  int component = 0;   // of a multi-component array
  int components = 1;  // of the array
  ChannelKind kind = ChannelKind::kGeneric;
  vtkSmartPointer<vtkImageData> scalars;  // one component (kColor: RGBA unsigned char); active scalars
  vtkSmartPointer<vtkImageData> mask;     // unsigned char 0/1; active scalars
  double empty_value = 0.0;               // the scalar of empty voxels
  double low = 0.0, high = 1.0;           // range of set voxels
  double robust_high = 1.0;               // 99.5th percentile of set voxels (ramps saturate there)
  uint64_t set_voxels = 0;
  std::vector<long> categories;  // distinct values of a material array (at most kMaxCategories)

  static constexpr size_t kMaxCategories = 64;

  // "normal.y", "count".
  std::string label() const;
};

// Builds the field of `array` (component `component`). The mask is the "inside" array for kInside, else
// "occupancy" when the volume has it, else the voxels where the array is non-zero. Throws voxr::Error
// naming the available arrays when `array` is not one of them, or the component count when `component`
// is out of range.
DisplayField make_display_field(const Volume& volume, const std::string& array, int component);

}  // namespace voxr::view
