#include "volume_view.h"

#include <vtkMatrix4x4.h>
#include <vtkRenderer.h>

#include <algorithm>

namespace voxr::view {

VolumeView::VolumeView(vtkRenderer* renderer, vtkMatrix4x4* to_world) {
  mapper_->SetRequestedRenderModeToDefault();
  mapper_->SetBlendModeToComposite();
  property_->SetAmbient(0.35);
  property_->SetDiffuse(0.75);
  property_->SetSpecular(0.15);
  property_->SetSpecularPower(20.0);
  volume_->SetMapper(mapper_);
  volume_->SetProperty(property_);
  volume_->SetUserMatrix(to_world);
  renderer->AddVolume(volume_);
}

void VolumeView::set_field(const DisplayField& field, const TransferPreset& preset) {
  mapper_->SetInputData(field.scalars);
  property_->SetColor(preset.color);
  // A colour field's RGBA is one dependent tuple: RGB drawn directly, opacity from alpha.
  property_->SetIndependentComponents(field.kind == ChannelKind::kColor ? 0 : 1);
  property_->SetScalarOpacity(preset.opacity);
  if (preset.categorical)
    property_->SetInterpolationTypeToNearest();
  else
    property_->SetInterpolationTypeToLinear();
  property_->SetShade(preset.shade ? 1 : 0);
  const double* spacing = field.scalars->GetSpacing();
  const double voxel = std::min({spacing[0], spacing[1], spacing[2]});
  property_->SetScalarOpacityUnitDistance(preset.unit_distance * voxel);
  mapper_->SetSampleDistance(float(0.25 * voxel));  // fine steps: less banding where opacity steps sharply
}

void VolumeView::set_visible(bool visible) {
  volume_->SetVisibility(visible ? 1 : 0);
}

}  // namespace voxr::view
