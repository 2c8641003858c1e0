// The volume-rendering view: vtkSmartVolumeMapper (GPU ray casting where OpenGL allows, CPU ray casting
// otherwise, e.g. some software GL setups) with the channel's colour and opacity preset.
#pragma once

#include <vtkNew.h>
#include <vtkSmartVolumeMapper.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

class vtkMatrix4x4;
class vtkRenderer;

#include "display_field.h"
#include "transfer_presets.h"

namespace voxr::view {

class VolumeView {
 public:
  VolumeView(vtkRenderer* renderer, vtkMatrix4x4* to_world);
  void set_field(const DisplayField& field, const TransferPreset& preset);
  void set_visible(bool visible);

 private:
  vtkNew<vtkSmartVolumeMapper> mapper_;
  vtkNew<vtkVolumeProperty> property_;
  vtkNew<vtkVolume> volume_;
};

}  // namespace voxr::view
