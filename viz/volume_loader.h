// Reading the volumes voxr writes into one vtkImageData with one point-data array per channel.
//  .vti   VTK XML ImageData: every point-data array ("occupancy", "count", "normal", "material", ...).
//  .nrrd  voxr's NRRD set: OUT.nrrd holds occupancy and OUT.<channel>.nrrd the other channels; opening any
//         file of the set loads them all. A lone NRRD file from elsewhere loads as one array named by its
//         "content" field.
//  .vdb   OpenVDB (when voxr-view is built with it): every bool, mask, int32, float and vec3s grid as a dense
//         array over [0, voxr_dims) for voxr's files, else over the active voxels' bounding box. Refused, one
//         line, when the dense arrays would pass kMaxDenseVdbBytes (4 GiB): no downsampling.
// Samples sit at voxel centres: the image origin is the world centre of voxel (0,0,0) and the spacing is
// the voxel size. A rotated grid frame (the .vti Direction, or NRRD space directions that are not axis
// aligned) is kept out of the image and returned as a local-to-world matrix for every prop to use, so all
// of VTK's mappers see an axis-aligned image.
#pragma once

#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace voxr::view {

// The most bytes of dense arrays a .vdb is expanded to (e.g. 2048^3 occupancy alone is 8 GiB: refused).
constexpr uint64_t kMaxDenseVdbBytes = uint64_t(4) << 30;

struct Volume {
  std::filesystem::path source;              // the file named on the command line
  std::vector<std::filesystem::path> files;  // every file read (the NRRD set)
  vtkSmartPointer<vtkImageData> image;       // point data; identity direction
  vtkSmartPointer<vtkMatrix4x4> to_world;    // image coordinates -> world (identity when axis aligned)
  std::vector<std::string> arrays;           // point-data array names, in display order

  int dims(int axis) const { return image->GetDimensions()[axis]; }
  double voxel_size(int axis) const { return image->GetSpacing()[axis]; }
  bool has_array(const std::string& name) const;
};

// Reads `file` (.vti, .nrrd or .vdb). Throws voxr::Error with a one-line message naming the file for a
// missing file, an unknown extension, a file that is not in the format its extension says, a set whose files
// disagree in dimensions, or a volume without arrays.
Volume load_volume(const std::filesystem::path& file);

}  // namespace voxr::view
