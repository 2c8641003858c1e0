#include "display_field.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "grid/channel_table.h"
#include "util/error.h"

namespace voxr::view {

ChannelKind channel_kind(const std::string& name) {
  if (name.rfind("absorption", 0) == 0) return ChannelKind::kCount;  // shown like a count: a heat ramp
  const ChannelInfo* info = find_channel_array(name);
  if (!info) return ChannelKind::kGeneric;
  switch (info->channel) {
    case Channel::kOcc:
      return ChannelKind::kOccupancy;
    case Channel::kCount:
      return ChannelKind::kCount;
    case Channel::kNormal:
      return ChannelKind::kNormal;
    case Channel::kMaterial:
      return ChannelKind::kMaterial;
    case Channel::kInside:
      return ChannelKind::kInside;
    case Channel::kColor:
      return ChannelKind::kColor;
  }
  return ChannelKind::kGeneric;
}

std::string DisplayField::label() const {
  if (components <= 1) return array;
  if (components == 3) return fmt::format("{}.{}", array, "xyz"[component]);
  return fmt::format("{}[{}]", array, component);
}

namespace {

vtkSmartPointer<vtkImageData> image_like(vtkImageData* volume, vtkDataArray* scalars) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(volume);
  image->GetPointData()->SetScalars(scalars);
  return image;
}

std::string array_list(const Volume& volume) {
  std::string list;
  for (const std::string& a : volume.arrays) list += (list.empty() ? "" : ", ") + a;
  return list;
}

}  // namespace

DisplayField make_display_field(const Volume& volume, const std::string& array, int component) {
  vtkPointData* pd = volume.image->GetPointData();
  vtkDataArray* values = pd->GetArray(array.c_str());
  if (!values) fail("{}: no array '{}' (arrays: {})", volume.source.string(), array, array_list(volume));
  DisplayField f;
  f.array = array;
  f.components = values->GetNumberOfComponents();
  if (component < 0 || component >= f.components)
    fail("{}: array '{}' has {} component(s); component {} does not exist", volume.source.string(), array,
         f.components, component);
  f.component = component;
  f.kind = channel_kind(array);
  if (f.kind == ChannelKind::kNormal && f.components != 3) f.kind = ChannelKind::kGeneric;
  if (f.kind == ChannelKind::kColor && (f.components != 4 || values->GetDataType() != VTK_UNSIGNED_CHAR))
    f.kind = ChannelKind::kGeneric;
  if ((f.kind != ChannelKind::kNormal && f.kind != ChannelKind::kColor && f.kind != ChannelKind::kGeneric) &&
      f.components != 1)
    f.kind = ChannelKind::kGeneric;

  // The mask of set voxels.
  const vtkIdType n = values->GetNumberOfTuples();
  vtkDataArray* mask_source = nullptr;
  if (f.kind == ChannelKind::kInside)
    mask_source = values;
  else if (vtkDataArray* occ = pd->GetArray(channel_info(Channel::kOcc).array_name);
           occ && occ->GetNumberOfComponents() == 1)
    mask_source = occ;
  auto mask = vtkSmartPointer<vtkUnsignedCharArray>::New();
  mask->SetName("mask");
  mask->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i) {
    bool set = false;
    if (mask_source) {
      set = mask_source->GetComponent(i, 0) != 0.0;
    } else {
      for (int c = 0; c < f.components && !set; ++c) set = values->GetComponent(i, c) != 0.0;
    }
    mask->SetValue(i, set ? 1 : 0);
  }
  f.mask = image_like(volume.image, mask);

  if (f.kind == ChannelKind::kColor) {
    // The colours as they are, transparent where no voxel is set.
    auto rgba = vtkSmartPointer<vtkUnsignedCharArray>::New();
    rgba->SetName(f.array.c_str());
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i) {
      const bool set = mask->GetValue(i) != 0;
      for (int c = 0; c < 3; ++c)
        rgba->SetValue(4 * i + c, set ? (unsigned char)values->GetComponent(i, c) : 0);
      rgba->SetValue(4 * i + 3, set ? 255 : 0);
      f.set_voxels += set ? 1 : 0;
    }
    f.scalars = image_like(volume.image, rgba);
    f.low = f.robust_high = 0.0;
    f.high = 255.0;
    return f;
  }

  // The scalars: the array itself where 0 already means empty, else a float copy with a distinct empty value.
  const bool copy = f.kind == ChannelKind::kNormal || f.kind == ChannelKind::kMaterial || f.components > 1;
  f.empty_value = f.kind == ChannelKind::kNormal ? -2.0 : f.kind == ChannelKind::kMaterial ? -1.0 : 0.0;
  std::vector<double> set_values;
  set_values.reserve(size_t(n / 8));
  vtkSmartPointer<vtkDataArray> scalars = values;
  vtkSmartPointer<vtkFloatArray> copied;
  if (copy) {
    copied = vtkSmartPointer<vtkFloatArray>::New();
    copied->SetName(f.label().c_str());
    copied->SetNumberOfValues(n);
    scalars = copied;
  }
  double lowest = 0.0;
  for (vtkIdType i = 0; i < n; ++i) {
    const double v = values->GetComponent(i, component);
    if (i == 0 || v < lowest) lowest = v;
    if (mask->GetValue(i)) set_values.push_back(v);
    if (copied) copied->SetValue(i, mask->GetValue(i) ? float(v) : float(f.empty_value));
  }
  f.scalars = image_like(volume.image, scalars);
  f.set_voxels = set_values.size();
  if (f.kind == ChannelKind::kGeneric) f.empty_value = lowest;

  if (!set_values.empty()) {
    const auto [lo, hi] = std::minmax_element(set_values.begin(), set_values.end());
    f.low = *lo;
    f.high = *hi;
    const size_t k = std::min(set_values.size() - 1, size_t(double(set_values.size()) * 0.995));
    std::nth_element(set_values.begin(), set_values.begin() + ptrdiff_t(k), set_values.end());
    f.robust_high = set_values[k];
  }
  if (f.kind == ChannelKind::kMaterial) {
    std::set<long> ids;
    for (double v : set_values) {
      ids.insert(long(v));
      if (ids.size() > DisplayField::kMaxCategories) break;
    }
    if (ids.size() <= DisplayField::kMaxCategories) f.categories.assign(ids.begin(), ids.end());
  }
  return f;
}

}  // namespace voxr::view
