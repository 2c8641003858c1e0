// voxr-view's command line: one options struct, one line per flag, then a validation pass
// (parse_view_options).
#pragma once

#include <array>
#include <optional>
#include <string>

namespace voxr::view {

enum class ViewKind { kVolume, kSlices, kIso };

const char* view_kind_name(ViewKind kind);

enum class MeshStyle { kWireframe, kTranslucent, kSolid, kHidden };

const char* mesh_style_name(MeshStyle style);

struct ViewOptions {
  std::string volume;            // .vti or .nrrd
  std::string array;             // empty: occupancy when the file has it, else its first array
  std::optional<int> component;  // of a multi-component array (normal: 0..2); default 0
  std::optional<ViewKind> view;  // empty: iso for occupancy/inside, volume for other arrays
  std::string mesh;              // overlay: a mesh (.obj .off .ply .stl) or scene (.json), world space
  MeshStyle mesh_style = MeshStyle::kWireframe;
  std::string screenshot;                     // render offscreen to this PNG and exit
  int width = 960, height = 720;              // window or screenshot size
  double azimuth = 30.0;                      // degrees about world +Y, from the front view (camera on +Z)
  double elevation = 20.0;                    // degrees up from the front view
  double zoom = 1.0;                          // on top of framing the volume
  double iso_opacity = 1.0;                   // below 1 the mesh shows inside the isosurface
  std::optional<std::array<long, 3>> slices;  // slice indices; default: the middle of each axis
  bool overlay = true;                        // axes, scalar bar, info text
  std::string keys;                           // pressed before the screenshot (scripted views, tests)
};

// Parses argv. Returns the options, or std::nullopt when --help or --version was printed (exit 0).
// Throws voxr::Error with a one-line message for a bad flag or value.
std::optional<ViewOptions> parse_view_options(int argc, char** argv);

}  // namespace voxr::view
