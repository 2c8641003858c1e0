// Colour and opacity per channel kind, shared by the three views and the scalar bar:
//   occupancy  ivory; in the volume rendering unshaded and translucent (an X-ray of the surface shell)
//   inside     light blue solid interior, opaque and lit
//   count      write count (or absorption): a heat ramp (purple-red-yellow) from 1 to the 99.5th percentile,
//              opacity rising with the value, so dense regions stand out in the volume rendering
//   normal     one component in [-1, 1]: blue-white-red
//   material   categorical colours per id (Tableau 10)
//   color      the voxels' own RGB (no lookup table), empty voxels transparent
//   generic    any other array: the heat ramp over its range
// Empty voxels (DisplayField::empty_value) are dark grey in slices and fully transparent in volume
// renderings. Only the interior is lit: the other channels are mostly one-voxel surface shells, across
// which central differences are zero, so gradient shading would paint them black in patches.
#pragma once

#include <vtkColorTransferFunction.h>
#include <vtkPiecewiseFunction.h>
#include <vtkScalarsToColors.h>
#include <vtkSmartPointer.h>

#include "display_field.h"

namespace voxr::view {

struct TransferPreset {
  vtkSmartPointer<vtkColorTransferFunction> color;  // display value -> colour (slices, volume, iso)
  vtkSmartPointer<vtkPiecewiseFunction> opacity;    // display value -> opacity (volume)
  vtkSmartPointer<vtkScalarsToColors> legend;       // for the scalar bar: the set voxels' values only
  bool categorical = false;                         // nearest-neighbour sampling, labelled legend
  bool shade = false;                               // volume rendering with gradient lighting
  double unit_distance = 1.0;                       // volume opacity unit distance, in voxels
};

// `opacity_scale` multiplies the volume opacity (the +/- keys); 1 is the preset.
TransferPreset make_preset(const DisplayField& field, double opacity_scale = 1.0);

// Background, and the colour of empty voxels in slices.
inline constexpr double kBackground[3] = {0.11, 0.12, 0.15};
inline constexpr double kEmptyVoxel[3] = {0.22, 0.22, 0.24};

}  // namespace voxr::view
