// Saving what the render window shows as an RGB PNG.
#pragma once

#include <filesystem>

class vtkRenderWindow;

namespace voxr::view {

// Throws voxr::Error naming `out` when its folder does not exist or the file cannot be written.
void check_screenshot_path(const std::filesystem::path& out);

// Renders `window` and writes its pixels to `out` (after check_screenshot_path).
void save_screenshot(vtkRenderWindow* window, const std::filesystem::path& out);

}  // namespace voxr::view
