#include "vtk_messages.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace voxr::view {

namespace {

std::string g_last_error;

// The last non-empty line of VTK's message ("ERROR: In file, line N\nvtkClass (0x...): what went wrong").
std::string last_line(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
    text.remove_suffix(1);
  const size_t nl = text.rfind('\n');
  std::string_view line = nl == std::string_view::npos ? text : text.substr(nl + 1);
  // Drop the object address VTK prints: "vtkXMLImageDataReader (0x55d...): " -> "vtkXMLImageDataReader: ".
  if (const size_t open = line.find(" (0x"); open != std::string_view::npos) {
    if (const size_t close = line.find("): ", open); close != std::string_view::npos)
      return std::string(line.substr(0, open)) + std::string(line.substr(close + 1));
  }
  return std::string(line);
}

class MessageCollector : public vtkOutputWindow {
 public:
  static MessageCollector* New();
  vtkTypeMacro(MessageCollector, vtkOutputWindow);

  void DisplayText(const char* text) override {
    if (show_warnings_) std::fprintf(stderr, "%s\n", text);
  }
  void DisplayErrorText(const char* text) override {
    g_last_error = last_line(text);
    if (show_warnings_) std::fprintf(stderr, "%s\n", text);
  }
  void DisplayWarningText(const char* text) override { DisplayText(text); }
  void DisplayGenericWarningText(const char* text) override { DisplayText(text); }
  void DisplayDebugText(const char* text) override { DisplayText(text); }

 private:
  bool show_warnings_ = std::getenv("VOXR_VIEW_VTK_WARNINGS") != nullptr;
};

vtkStandardNewMacro(MessageCollector);

}  // namespace

void install_vtk_message_collector() {
  // VTK also logs every warning and error to stderr through vtkLogger; the collector reports them instead.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkSmartPointer<MessageCollector> collector = vtkSmartPointer<MessageCollector>::New();
  vtkOutputWindow::SetInstance(collector);
}

void clear_vtk_errors() {
  g_last_error.clear();
}

std::string last_vtk_error() {
  return g_last_error;
}

}  // namespace voxr::view
