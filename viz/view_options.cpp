#include "view_options.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include "util/error.h"

namespace voxr::view {

const char* view_kind_name(ViewKind kind) {
  switch (kind) {
    case ViewKind::kVolume:
      return "volume";
    case ViewKind::kSlices:
      return "slices";
    case ViewKind::kIso:
      return "iso";
  }
  return "?";
}

const char* mesh_style_name(MeshStyle style) {
  switch (style) {
    case MeshStyle::kWireframe:
      return "wireframe";
    case MeshStyle::kTranslucent:
      return "translucent";
    case MeshStyle::kSolid:
      return "solid";
    case MeshStyle::kHidden:
      return "hidden";
  }
  return "?";
}

namespace {

// "A,B,..." -> integers; errors name the flag.
std::vector<long> parse_ints(const std::string& text, size_t count, const char* flag) {
  std::vector<long> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    long v = 0;
    try {
      v = std::stol(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size()) fail("{} '{}': '{}' is not an integer", flag, text, item);
    values.push_back(v);
  }
  if (values.size() != count) fail("{} '{}': expected {} comma-separated integers", flag, text, count);
  return values;
}

int parse_component(const std::string& text) {
  if (text == "x" || text == "0") return 0;
  if (text == "y" || text == "1") return 1;
  if (text == "z" || text == "2") return 2;
  if (text.size() == 1 && text[0] >= '3' && text[0] <= '9') return text[0] - '0';
  fail("--component '{}': expected x, y, z or a component index", text);
}

}  // namespace

std::optional<ViewOptions> parse_view_options(int argc, char** argv) {
  ViewOptions o;
  std::string size, view, component, mesh_style;
  std::string slices;

  CLI::App app{
      "voxr-view: look at a voxr volume (.vti, .nrrd or .vdb) as a volume rendering, three slice planes or "
      "an "
      "isosurface, optionally with the source mesh overlaid. Press h in the window for the keys.",
      "voxr-view"};
  app.set_version_flag("--version", "voxr-view 0.1.0");
  app.add_option("volume", o.volume,
                 "volume file: .vti, .nrrd (with its .count/.normal/... siblings) or .vdb")
      ->required();
  app.add_option("--array", o.array, "array to show (default: occupancy, else the first)");
  app.add_option("--component", component, "component of a vector array: x, y, z (default x)");
  app.add_option("--view", view, "volume | slices | iso (default: iso for occupancy/inside, else volume)");
  app.add_option("--mesh", o.mesh, "overlay a mesh (.obj .off .ply .stl) or scene (.json) in world space");
  app.add_option("--mesh-style", mesh_style, "wireframe | translucent | solid (default wireframe)");
  app.add_option("--screenshot", o.screenshot, "render offscreen to this PNG and exit");
  app.add_option("--size", size, "W,H: window or screenshot size in pixels (default 960,720)");
  app.add_option("--azimuth", o.azimuth, "camera degrees about +Y from the front (camera on +Z)")
      ->capture_default_str();
  app.add_option("--elevation", o.elevation, "camera degrees above the front view")->capture_default_str();
  app.add_option("--zoom", o.zoom, "zoom factor on top of framing the volume")->capture_default_str();
  app.add_option("--iso-opacity", o.iso_opacity,
                 "isosurface opacity in (0, 1]; below 1 shows the mesh inside")
      ->capture_default_str();
  app.add_option("--slices", slices, "I,J,K: slice plane indices (default: the middle of each axis)");
  app.add_option("--keys", o.keys, "with --screenshot: press these keys first (e.g. 2xxh, see h)");
  bool no_overlay = false;
  app.add_flag("--no-overlay", no_overlay, "hide axes, scalar bar and text (clean screenshots)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return std::nullopt;
  } catch (const CLI::CallForVersion&) {
    std::puts("voxr-view 0.1.0");
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    fail("{} (voxr-view --help lists the flags)", e.what());
  }

  o.overlay = !no_overlay;
  if (!o.keys.empty() && o.screenshot.empty()) fail("--keys needs --screenshot");
  if (!component.empty()) o.component = parse_component(component);
  if (!view.empty()) {
    static const std::map<std::string, ViewKind> kViews{
        {"volume", ViewKind::kVolume}, {"slices", ViewKind::kSlices}, {"iso", ViewKind::kIso}};
    const auto it = kViews.find(view);
    if (it == kViews.end()) fail("--view '{}': expected volume, slices or iso", view);
    o.view = it->second;
  }
  if (!mesh_style.empty()) {
    if (mesh_style == "wireframe")
      o.mesh_style = MeshStyle::kWireframe;
    else if (mesh_style == "translucent")
      o.mesh_style = MeshStyle::kTranslucent;
    else if (mesh_style == "solid")
      o.mesh_style = MeshStyle::kSolid;
    else
      fail("--mesh-style '{}': expected wireframe, translucent or solid", mesh_style);
    if (o.mesh.empty()) fail("--mesh-style needs --mesh FILE");
  }
  if (!size.empty()) {
    const std::vector<long> wh = parse_ints(size, 2, "--size");
    if (wh[0] < 16 || wh[1] < 16 || wh[0] > 8192 || wh[1] > 8192)
      fail("--size '{}': width and height must be in 16..8192", size);
    o.width = int(wh[0]);
    o.height = int(wh[1]);
  }
  if (!slices.empty()) {
    const std::vector<long> ijk = parse_ints(slices, 3, "--slices");  // checked against the dims later
    o.slices = std::array<long, 3>{ijk[0], ijk[1], ijk[2]};
  }
  if (!std::isfinite(o.azimuth) || !std::isfinite(o.elevation)) fail("--azimuth/--elevation must be finite");
  if (!(o.iso_opacity > 0.0 && o.iso_opacity <= 1.0))
    fail("--iso-opacity {}: must be in (0, 1]", o.iso_opacity);
  if (!(o.zoom > 0.0) || !std::isfinite(o.zoom)) fail("--zoom {}: must be a positive number", o.zoom);
  return o;
}

}  // namespace voxr::view
