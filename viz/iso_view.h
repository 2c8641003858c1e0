// The isosurface view: flying edges at 0.5 through the field's mask (occupancy, or the solid interior for
// the "inside" array), coloured by the field. On a 0/1 mask every surface vertex lies halfway between a set
// and an empty voxel, so each vertex takes the value of its set voxel exactly (no blending with empties).
#pragma once

#include <vtkActor.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageConstantPad.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

class vtkMatrix4x4;
class vtkRenderer;

#include "display_field.h"
#include "transfer_presets.h"

namespace voxr::view {

class IsoView {
 public:
  IsoView(vtkRenderer* renderer, vtkMatrix4x4* to_world);
  void set_field(const DisplayField& field, const TransferPreset& preset);
  void set_visible(bool visible);
  void set_opacity(double opacity);
  double opacity() const;
  vtkIdType triangles() const;

 private:
  vtkNew<vtkImageConstantPad> pad_;  // one empty voxel around the grid closes surfaces at its faces
  vtkNew<vtkFlyingEdges3D> contour_;
  vtkNew<vtkPolyDataMapper> mapper_;
  vtkNew<vtkActor> actor_;
};

}  // namespace voxr::view
