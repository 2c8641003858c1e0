// VTK reports problems through its global output window, as multi-line text on stderr. voxr-view installs
// a collector instead: errors are kept (the last line of each, which names the problem) so that callers
// turn them into one-line voxr::Error messages; warnings are dropped unless VOXR_VIEW_VTK_WARNINGS is set.
#pragma once

#include <string>

namespace voxr::view {

// Replaces VTK's output window with the collector. Call once, first thing in main.
void install_vtk_message_collector();

// Forgets the errors collected so far.
void clear_vtk_errors();

// The last error VTK reported since clear_vtk_errors(), or "" when none.
std::string last_vtk_error();

}  // namespace voxr::view
