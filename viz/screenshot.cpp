#include "screenshot.h"

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <cctype>

#include "util/error.h"
#include "vtk_messages.h"

namespace voxr::view {

namespace fs = std::filesystem;

void check_screenshot_path(const fs::path& out) {
  std::string ext = out.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png") fail("--screenshot {}: the file must end in .png", out.string());
  std::error_code ec;
  const fs::path folder = out.parent_path();
  if (!folder.empty() && !fs::is_directory(folder, ec))
    fail("--screenshot {}: folder '{}' does not exist", out.string(), folder.string());
  if (fs::is_directory(out, ec)) fail("--screenshot {}: is a folder", out.string());
}

void save_screenshot(vtkRenderWindow* window, const fs::path& out) {
  check_screenshot_path(out);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  clear_vtk_errors();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(out.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != vtkErrorCode::NoError || !last_vtk_error().empty())
    fail("{}: cannot write the screenshot: {}", out.string(),
         last_vtk_error().empty() ? vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode())
                                  : last_vtk_error());
}

}  // namespace voxr::view
