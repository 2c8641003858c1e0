// Mouse: VTK's trackball camera (left rotate, middle pan, right/wheel zoom). Keys: every key press goes to
// one handler (the viewer's key table); VTK's own single-letter bindings (wireframe, stereo, fly-to, exit
// on e, ...) are switched off so that they cannot fight the viewer's.
#pragma once

#include <vtkInteractorStyleTrackballCamera.h>

#include <functional>

namespace voxr::view {

class KeyStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static KeyStyle* New();
  vtkTypeMacro(KeyStyle, vtkInteractorStyleTrackballCamera);

  // Called with the typed character ('a', 'A', '+'), or 27 for Escape.
  std::function<void(char)> on_key;

  void OnKeyPress() override;
  void OnChar() override {}
};

}  // namespace voxr::view
