// The viewer: one volume, the array shown (a DisplayField and its TransferPreset), the three views of it
// (volume rendering, slice planes, isosurface; one visible at a time), the optional mesh overlay, the HUD,
// the camera, and the key table that drives them. run() either saves a screenshot offscreen and returns, or
// opens the window and returns when it is closed.
#pragma once

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "display_field.h"
#include "hud.h"
#include "iso_view.h"
#include "mesh_overlay.h"
#include "slice_view.h"
#include "transfer_presets.h"
#include "view_options.h"
#include "volume_loader.h"
#include "volume_view.h"

namespace voxr::view {

class Viewer {
 public:
  // Checks the options against the volume (array, component, slice indices) and loads the mesh before
  // anything touches the display, so bad input fails with a message even without X. Throws voxr::Error.
  Viewer(Volume volume, const ViewOptions& options);
  ~Viewer();

  // Returns the process exit code.
  int run();

 private:
  struct Binding {
    std::string keys;   // characters that trigger it
    std::string label;  // as shown in the help
    std::string help;
    std::function<void(char)> run;
  };

  void make_bindings();
  std::string help_text() const;
  void on_key(char key);

  void show_array(size_t index, int component);  // computes field_, then apply_field()
  void apply_field();                            // preset, views and legend for field_
  void set_view(ViewKind view);
  void sync_mesh_cuts();  // the mesh's cross-sections follow the slice planes
  void reset_camera();
  void update_info();
  void save_numbered_screenshot();

  Volume volume_;
  ViewOptions options_;
  std::array<double, 6> world_bounds_{};

  size_t array_ = 0;
  DisplayField field_;
  TransferPreset preset_;
  ViewKind view_ = ViewKind::kIso;
  double opacity_scale_ = 1.0;

  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderWindowInteractor> interactor_;
  std::unique_ptr<VolumeView> volume_view_;
  std::unique_ptr<SliceView> slice_view_;
  std::unique_ptr<IsoView> iso_view_;
  std::unique_ptr<MeshOverlay> mesh_;
  std::unique_ptr<Hud> hud_;
  bool hud_visible_ = true;
  std::vector<Binding> bindings_;
};

}  // namespace voxr::view
