#include "slice_view.h"

#include <vtkMatrix4x4.h>
#include <vtkRenderer.h>

#include <algorithm>

namespace voxr::view {

SliceView::SliceView(vtkRenderer* renderer, vtkMatrix4x4* to_world, const int dims[3]) {
  property_->SetInterpolationTypeToNearest();
  property_->UseLookupTableScalarRangeOn();
  property_->SetAmbient(1.0);
  property_->SetDiffuse(0.0);
  for (int axis = 0; axis < 3; ++axis) {
    dims_[axis] = dims[axis];
    index_[axis] = dims[axis] / 2;
    mappers_[axis]->SetOrientation(axis);
    mappers_[axis]->SetSliceNumber(index_[axis]);
    mappers_[axis]->BorderOn();
    slices_[axis]->SetMapper(mappers_[axis]);
    slices_[axis]->SetProperty(property_);
    slices_[axis]->SetUserMatrix(to_world);
    renderer->AddViewProp(slices_[axis]);
  }
}

void SliceView::set_field(const DisplayField& field, const TransferPreset& preset) {
  // A colour field is drawn as it is: RGBA unsigned char, no lookup table (window 255, level 127.5 keeps the
  // values).
  property_->SetLookupTable(field.kind == ChannelKind::kColor ? nullptr : preset.color.Get());
  property_->SetColorWindow(255.0);
  property_->SetColorLevel(127.5);
  for (auto& mapper : mappers_) mapper->SetInputData(field.scalars);
}

void SliceView::set_visible(bool visible) {
  for (auto& slice : slices_) slice->SetVisibility(visible ? 1 : 0);
}

void SliceView::set_index(int axis, long index) {
  index_[axis] = int(std::clamp<long>(index, 0, dims_[axis] - 1));
  mappers_[axis]->SetSliceNumber(index_[axis]);
}

}  // namespace voxr::view
