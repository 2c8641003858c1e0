#include "key_style.h"

#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

#include <cstring>

namespace voxr::view {

vtkStandardNewMacro(KeyStyle);

void KeyStyle::OnKeyPress() {
  vtkRenderWindowInteractor* rwi = this->Interactor;
  if (!rwi || !on_key) return;
  const char* sym = rwi->GetKeySym();
  char key = rwi->GetKeyCode();
  if (sym && std::strcmp(sym, "Escape") == 0) key = 27;
  if (key > 0) on_key(key);
}

}  // namespace voxr::view
