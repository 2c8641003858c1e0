#include "mesh_overlay.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include "core/scene.h"

namespace voxr::view {

namespace {

constexpr double kMeshColor[3] = {0.35, 0.85, 1.0};
constexpr double kCutColor[3] = {0.2, 1.0, 0.45};

}  // namespace

MeshOverlay::MeshOverlay(vtkRenderer* renderer, const std::filesystem::path& file, MeshStyle style) {
  const TriangleSoup soup = scene_triangles(load_input(file));
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(vtkIdType(soup.positions.size()));
  for (size_t i = 0; i < soup.positions.size(); ++i)
    points->SetPoint(vtkIdType(i), soup.positions[i].x, soup.positions[i].y, soup.positions[i].z);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(vtkIdType(soup.triangles.size()), vtkIdType(3 * soup.triangles.size()));
  for (const glm::uvec4& t : soup.triangles) {
    const vtkIdType ids[3] = {vtkIdType(t.x), vtkIdType(t.y), vtkIdType(t.z)};
    polys->InsertNextCell(3, ids);
  }
  mesh_->SetPoints(points);
  mesh_->SetPolys(polys);
  triangles_ = soup.triangles.size();

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh_);
  mapper->ScalarVisibilityOff();
  // The surface voxels enclose the mesh closely; keep its lines in front of the isosurface where they touch.
  mapper->SetResolveCoincidentTopologyToPolygonOffset();
  actor_->SetMapper(mapper);
  renderer->AddActor(actor_);
  set_style(style);

  for (int axis = 0; axis < 3; ++axis) {
    cutters_[axis]->SetInputData(mesh_);
    cutters_[axis]->SetCutFunction(planes_[axis]);
    cutters_[axis]->GenerateCutScalarsOff();
    vtkNew<vtkPolyDataMapper> cut_mapper;
    cut_mapper->SetInputConnection(cutters_[axis]->GetOutputPort());
    cut_mapper->ScalarVisibilityOff();
    // The lines lie in the slice plane: draw them over it.
    cut_mapper->SetResolveCoincidentTopologyToPolygonOffset();
    cut_mapper->SetRelativeCoincidentTopologyLineOffsetParameters(0.0, -8.0);
    cut_actors_[axis]->SetMapper(cut_mapper);
    vtkProperty* p = cut_actors_[axis]->GetProperty();
    p->SetColor(kCutColor[0], kCutColor[1], kCutColor[2]);
    p->SetLineWidth(2.0);
    p->LightingOff();
    renderer->AddActor(cut_actors_[axis]);
  }
  update_visibility();
}

void MeshOverlay::update_visibility() {
  const bool shown = style_ != MeshStyle::kHidden;
  actor_->SetVisibility(shown && !slice_mode_ ? 1 : 0);
  for (auto& a : cut_actors_) a->SetVisibility(shown && slice_mode_ ? 1 : 0);
}

void MeshOverlay::set_style(MeshStyle style) {
  style_ = style;
  vtkProperty* p = actor_->GetProperty();
  update_visibility();
  p->SetColor(kMeshColor[0], kMeshColor[1], kMeshColor[2]);
  if (style == MeshStyle::kWireframe) {
    p->SetRepresentationToWireframe();
    p->SetOpacity(1.0);
    p->SetLineWidth(1.0);
    p->LightingOff();
  } else {
    p->SetRepresentationToSurface();
    p->SetOpacity(style == MeshStyle::kTranslucent ? 0.35 : 1.0);
    p->LightingOn();
  }
}

void MeshOverlay::set_cut_plane(int axis, const double origin[3], const double normal[3]) {
  planes_[axis]->SetOrigin(origin[0], origin[1], origin[2]);
  planes_[axis]->SetNormal(normal[0], normal[1], normal[2]);
}

void MeshOverlay::set_slice_mode(bool slices) {
  slice_mode_ = slices;
  update_visibility();
}

}  // namespace voxr::view
