// The heads-up display over the 3D view: world axes (lower left), the scalar bar of the shown array
// (right), the volume's dimensions, voxel size and what is shown (upper left), a key hint (lower right) and
// the key help (h), drawn on top of everything.
#pragma once

#include <vtkAxesActor.h>
#include <vtkNew.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>

#include <string>

class vtkRenderer;
class vtkRenderWindowInteractor;
class vtkScalarsToColors;

namespace voxr::view {

class Hud {
 public:
  Hud(vtkRenderer* renderer, vtkRenderWindowInteractor* interactor);
  void set_info(const std::string& text);
  // A null legend hides the scalar bar (binary arrays need none). `integer`: label whole numbers only.
  void set_legend(vtkScalarsToColors* legend, const std::string& title, bool categorical, bool integer);
  void set_help(const std::string& text);
  void toggle_help();
  void set_visible(bool visible);

 private:
  vtkNew<vtkAxesActor> axes_;
  vtkNew<vtkOrientationMarkerWidget> marker_;
  vtkNew<vtkScalarBarActor> bar_;
  vtkNew<vtkTextActor> info_;
  vtkNew<vtkTextActor> hint_;
  vtkNew<vtkTextActor> help_;
  bool help_shown_ = false;
  bool visible_ = true;
  bool has_legend_ = false;
};

}  // namespace voxr::view
