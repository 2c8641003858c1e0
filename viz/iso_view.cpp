#include "iso_view.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

namespace voxr::view {

namespace {

// The field's value at each surface vertex: the set voxel among the (up to two) voxels the vertex lies
// between, per axis.
void color_by_set_voxel(vtkPolyData* surface, const DisplayField& field) {
  vtkImageData* mask = field.mask;
  const int* dims = mask->GetDimensions();
  const double* origin = mask->GetOrigin();
  const double* spacing = mask->GetSpacing();
  auto* mask_values = mask->GetPointData()->GetScalars();
  auto* values = field.scalars->GetPointData()->GetScalars();
  const bool direct = field.kind == ChannelKind::kColor;
  vtkSmartPointer<vtkDataArray> colors;
  if (direct)
    colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  else
    colors = vtkSmartPointer<vtkFloatArray>::New();
  colors->SetName("value");
  const vtkIdType n = surface->GetNumberOfPoints();
  colors->SetNumberOfComponents(direct ? 3 : 1);
  colors->SetNumberOfTuples(n);
  auto linear = [&](const int* ijk) {
    return vtkIdType((int64_t(ijk[2]) * dims[1] + ijk[1]) * dims[0] + ijk[0]);
  };
  for (vtkIdType p = 0; p < n; ++p) {
    double x[3];
    surface->GetPoint(p, x);
    int ijk[3];
    int between = -1;  // the axis along which the vertex sits between two voxel centres
    for (int a = 0; a < 3; ++a) {
      const double u = (x[a] - origin[a]) / spacing[a];
      const double f = u - std::floor(u);
      if (between < 0 && f > 0.25 && f < 0.75) {
        between = a;
        ijk[a] = int(std::floor(u));
      } else {
        ijk[a] = int(std::lround(u));
      }
      ijk[a] = std::clamp(ijk[a], 0, dims[a] - 1);
    }
    if (between >= 0 && mask_values->GetComponent(linear(ijk), 0) == 0.0 && ijk[between] + 1 < dims[between])
      ++ijk[between];
    for (int c = 0; c < colors->GetNumberOfComponents(); ++c)
      colors->SetComponent(p, c, values->GetComponent(linear(ijk), c));
  }
  surface->GetPointData()->SetScalars(colors);
}

}  // namespace

IsoView::IsoView(vtkRenderer* renderer, vtkMatrix4x4* to_world) {
  pad_->SetConstant(0.0);
  contour_->SetInputConnection(pad_->GetOutputPort());
  contour_->SetValue(0, 0.5);
  contour_->ComputeNormalsOn();
  contour_->ComputeGradientsOff();
  contour_->ComputeScalarsOff();
  mapper_->ScalarVisibilityOn();
  mapper_->SetScalarModeToUsePointData();
  mapper_->UseLookupTableScalarRangeOn();
  mapper_->SetColorModeToMapScalars();
  actor_->SetMapper(mapper_);
  actor_->GetProperty()->SetAmbient(0.15);
  actor_->GetProperty()->SetDiffuse(0.85);
  actor_->GetProperty()->SetSpecular(0.2);
  actor_->GetProperty()->SetSpecularPower(30.0);
  actor_->SetUserMatrix(to_world);
  renderer->AddActor(actor_);
}

void IsoView::set_field(const DisplayField& field, const TransferPreset& preset) {
  const int* e = field.mask->GetExtent();
  pad_->SetInputData(field.mask);
  pad_->SetOutputWholeExtent(e[0] - 1, e[1] + 1, e[2] - 1, e[3] + 1, e[4] - 1, e[5] + 1);
  contour_->Update();
  vtkNew<vtkPolyData> surface;
  surface->ShallowCopy(contour_->GetOutput());
  color_by_set_voxel(surface, field);
  mapper_->SetInputData(surface);
  mapper_->SetLookupTable(preset.color);
  if (field.kind == ChannelKind::kColor)
    mapper_->SetColorModeToDirectScalars();
  else
    mapper_->SetColorModeToMapScalars();
}

void IsoView::set_visible(bool visible) {
  actor_->SetVisibility(visible ? 1 : 0);
}

void IsoView::set_opacity(double opacity) {
  actor_->GetProperty()->SetOpacity(opacity);
}

double IsoView::opacity() const {
  return actor_->GetProperty()->GetOpacity();
}

vtkIdType IsoView::triangles() const {
  auto* input = mapper_->GetInput();
  return input ? input->GetNumberOfPolys() : 0;
}

}  // namespace voxr::view
