#include "viewer.h"

#include "grid/channel_table.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "key_style.h"
#include "screenshot.h"
#include "util/error.h"

namespace voxr::view {

namespace fs = std::filesystem;

namespace {

std::string array_list(const Volume& volume) {
  std::string list;
  for (const std::string& a : volume.arrays) list += (list.empty() ? "" : ", ") + a;
  return list;
}

// World bounds of the voxels' outer faces (the image's points are voxel centres).
std::array<double, 6> world_bounds(const Volume& volume) {
  double b[6];
  volume.image->GetBounds(b);
  for (int a = 0; a < 3; ++a) {
    b[2 * a] -= 0.5 * volume.voxel_size(a);
    b[2 * a + 1] += 0.5 * volume.voxel_size(a);
  }
  std::array<double, 6> out{1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (int corner = 0; corner < 8; ++corner) {
    const double local[4] = {b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1.0};
    double world[4];
    volume.to_world->MultiplyPoint(local, world);
    for (int a = 0; a < 3; ++a) {
      out[2 * a] = std::min(out[2 * a], world[a]);
      out[2 * a + 1] = std::max(out[2 * a + 1], world[a]);
    }
  }
  return out;
}

std::string format_number(double v) {
  return fmt::format("{:.6g}", v);
}

}  // namespace

Viewer::Viewer(Volume volume, const ViewOptions& options) : volume_(std::move(volume)), options_(options) {
  // Everything that can be wrong with the input is checked here, before the display is touched.
  std::string array = options_.array;
  const std::string occupancy = channel_info(Channel::kOcc).array_name;
  if (array.empty()) array = volume_.has_array(occupancy) ? occupancy : volume_.arrays.front();
  if (!volume_.has_array(array))
    fail("--array '{}': {} has no such array (arrays: {})", array, volume_.source.filename().string(),
         array_list(volume_));
  array_ = size_t(std::find(volume_.arrays.begin(), volume_.arrays.end(), array) - volume_.arrays.begin());
  if (options_.component) {
    const int components = volume_.image->GetPointData()->GetArray(array.c_str())->GetNumberOfComponents();
    if (*options_.component >= components)
      fail("--component {}: array '{}' has {} component(s)", *options_.component, array, components);
  }
  field_ = make_display_field(volume_, array, options_.component.value_or(0));
  if (options_.slices) {
    for (int a = 0; a < 3; ++a)
      if ((*options_.slices)[a] < 0 || (*options_.slices)[a] >= volume_.dims(a))
        fail("--slices: index {} is outside 0..{} on axis {}", (*options_.slices)[a], volume_.dims(a) - 1,
             "xyz"[a]);
  }
  if (!options_.screenshot.empty()) check_screenshot_path(options_.screenshot);
  if (!options_.mesh.empty())
    mesh_ = std::make_unique<MeshOverlay>(renderer_, options_.mesh, options_.mesh_style);
  view_ =
      options_.view.value_or(field_.kind == ChannelKind::kOccupancy || field_.kind == ChannelKind::kInside ||
                                     field_.kind == ChannelKind::kColor
                                 ? ViewKind::kIso
                                 : ViewKind::kVolume);
  world_bounds_ = world_bounds(volume_);
  hud_visible_ = options_.overlay;

  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    fail(
        "no X display (DISPLAY is not set); VTK renders through X: run under a virtual one, "
        "e.g. xvfb-run -a voxr-view ...");

  renderer_->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  // Translucent isosurface and mesh overlap: sort them per pixel.
  renderer_->SetUseDepthPeeling(1);
  renderer_->SetMaximumNumberOfPeels(8);
  renderer_->SetOcclusionRatio(0.0);
  window_->SetMultiSamples(0);
  window_->AddRenderer(renderer_);
  window_->SetSize(options_.width, options_.height);
  window_->SetWindowName(fmt::format("voxr-view {}", volume_.source.filename().string()).c_str());
  if (!options_.screenshot.empty()) window_->SetOffScreenRendering(1);
  interactor_->SetRenderWindow(window_);

  volume_view_ = std::make_unique<VolumeView>(renderer_, volume_.to_world);
  slice_view_ = std::make_unique<SliceView>(renderer_, volume_.to_world, volume_.image->GetDimensions());
  if (options_.slices)
    for (int a = 0; a < 3; ++a) slice_view_->set_index(a, (*options_.slices)[a]);
  iso_view_ = std::make_unique<IsoView>(renderer_, volume_.to_world);
  iso_view_->set_opacity(options_.iso_opacity);
  hud_ = std::make_unique<Hud>(renderer_, interactor_);
  hud_->set_visible(hud_visible_);

  make_bindings();
  hud_->set_help(help_text());
  apply_field();
  set_view(view_);
  reset_camera();
}

Viewer::~Viewer() = default;

int Viewer::run() {
  if (!options_.screenshot.empty()) {
    for (char key : options_.keys) on_key(key);
    save_screenshot(window_, options_.screenshot);
    return 0;
  }
  vtkNew<KeyStyle> style;
  style->on_key = [this](char key) { on_key(key); };
  interactor_->SetInteractorStyle(style);
  interactor_->Initialize();
  window_->Render();
  std::printf("voxr-view: %s; press h in the window for the keys\n", volume_.source.string().c_str());
  std::fflush(stdout);
  interactor_->Start();
  return 0;
}

// ---- Keys ------------------------------------------------------------------------------------------------

void Viewer::make_bindings() {
  bindings_ = {
      {"h", "h", "show / hide this help", [this](char) { hud_->toggle_help(); }},
      {"aA", "a A", "next / previous array",
       [this](char k) {
         const size_t n = volume_.arrays.size();
         show_array((array_ + (k == 'a' ? 1 : n - 1)) % n, 0);
       }},
      {"c", "c", "next component of a vector array (normal x, y, z)",
       [this](char) {
         if (field_.components > 1) show_array(array_, (field_.component + 1) % field_.components);
       }},
      {"123", "1 2 3", "volume rendering / slice planes / isosurface",
       [this](char k) {
         set_view(k == '1' ? ViewKind::kVolume : k == '2' ? ViewKind::kSlices : ViewKind::kIso);
       }},
      {"xXyYzZ", "x y z", "move the x / y / z slice plane +1 voxel (shift: -1)",
       [this](char k) {
         const int axis = (k | 0x20) - 'x';
         slice_view_->move(axis, k >= 'a' ? 1 : -1);
         set_view(ViewKind::kSlices);
         sync_mesh_cuts();
       }},
      {"+=-", "+ -", "more / less opacity in the volume rendering",
       [this](char k) {
         opacity_scale_ = std::clamp(opacity_scale_ * (k == '-' ? 1.0 / 1.4 : 1.4), 0.02, 50.0);
         apply_field();
       }},
      {"t", "t", "opaque / translucent isosurface",
       [this](char) { iso_view_->set_opacity(iso_view_->opacity() < 1.0 ? 1.0 : 0.4); }},
      {"m", "m", "mesh overlay: wireframe / translucent / solid / hidden",
       [this](char) {
         if (mesh_) mesh_->set_style(MeshStyle((int(mesh_->style()) + 1) % 4));
       }},
      {"o", "o", "show / hide axes, scalar bar and text",
       [this](char) {
         hud_visible_ = !hud_visible_;
         hud_->set_visible(hud_visible_);
       }},
      {"r", "r", "reset the camera", [this](char) { reset_camera(); }},
      {"s", "s", "save a screenshot (voxr-view-N.png in the current folder)",
       [this](char) { save_numbered_screenshot(); }},
      {std::string("q\x1b"), "q Esc", "quit",
       [this](char) {
         if (options_.screenshot.empty()) interactor_->TerminateApp();  // no event loop runs for screenshots
       }},
  };
}

std::string Viewer::help_text() const {
  // The HUD centres each line; padding every line to one width keeps the columns aligned (monospace font).
  std::vector<std::string> lines{"voxr-view keys", ""};
  for (const Binding& b : bindings_) lines.push_back(fmt::format("{:<6} {}", b.label, b.help));
  lines.push_back("");
  lines.push_back("mouse: left rotate, middle pan, right/wheel zoom");
  size_t width = 0;
  for (const std::string& line : lines) width = std::max(width, line.size());
  std::string text;
  for (const std::string& line : lines)
    text += fmt::format("{} {:<{}} ", text.empty() ? "" : "\n", line, width);
  return text;
}

void Viewer::on_key(char key) {
  for (const Binding& b : bindings_) {
    if (b.keys.find(key) != std::string::npos) {
      b.run(key);
      update_info();
      window_->Render();
      return;
    }
  }
}

// ---- State -----------------------------------------------------------------------------------------------

void Viewer::show_array(size_t index, int component) {
  array_ = index;
  field_ = make_display_field(volume_, volume_.arrays[index], component);
  apply_field();
}

void Viewer::apply_field() {
  preset_ = make_preset(field_, opacity_scale_);
  volume_view_->set_field(field_, preset_);
  slice_view_->set_field(field_, preset_);
  iso_view_->set_field(field_, preset_);
  // Occupancy and inside need no legend; colours are their own.
  const bool binary = field_.kind == ChannelKind::kOccupancy || field_.kind == ChannelKind::kInside ||
                      field_.kind == ChannelKind::kColor;
  const bool categorical = preset_.categorical && field_.kind != ChannelKind::kNormal;
  vtkDataArray* scalars = field_.scalars->GetPointData()->GetScalars();
  const bool integer = scalars->GetDataType() != VTK_FLOAT && scalars->GetDataType() != VTK_DOUBLE;
  hud_->set_legend(binary ? nullptr : preset_.legend.Get(), field_.label(), categorical, integer);
  update_info();
}

void Viewer::set_view(ViewKind view) {
  view_ = view;
  volume_view_->set_visible(view == ViewKind::kVolume);
  slice_view_->set_visible(view == ViewKind::kSlices);
  iso_view_->set_visible(view == ViewKind::kIso);
  if (mesh_) mesh_->set_slice_mode(view == ViewKind::kSlices);
  sync_mesh_cuts();
  update_info();
}

void Viewer::sync_mesh_cuts() {
  if (!mesh_) return;
  const double* origin = volume_.image->GetOrigin();
  const double* spacing = volume_.image->GetSpacing();
  for (int axis = 0; axis < 3; ++axis) {
    double local[4] = {origin[0], origin[1], origin[2], 1.0};
    local[axis] += spacing[axis] * slice_view_->index(axis);
    double world[4];
    volume_.to_world->MultiplyPoint(local, world);
    double normal[3];
    for (int r = 0; r < 3; ++r) normal[r] = volume_.to_world->GetElement(r, axis);
    mesh_->set_cut_plane(axis, world, normal);
  }
}

void Viewer::reset_camera() {
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(0.0, 0.0, 1.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->Azimuth(options_.azimuth);
  camera->Elevation(options_.elevation);
  camera->OrthogonalizeViewUp();
  double bounds[6];
  std::copy(world_bounds_.begin(), world_bounds_.end(), bounds);
  renderer_->ResetCamera(bounds);
  // ResetCamera fits the bounding sphere; zoom in until the box's corners fill 90% of the view. Zoom narrows
  // the view angle, which scales projected coordinates exactly by the zoom factor.
  double extent = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    renderer_->SetWorldPoint(bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)],
                             bounds[4 + ((corner >> 2) & 1)], 1.0);
    renderer_->WorldToView();
    const double* v = renderer_->GetViewPoint();
    extent = std::max({extent, std::abs(v[0]), std::abs(v[1])});
  }
  camera->Zoom((extent > 0.0 ? 0.9 / extent : 1.0) * options_.zoom);
  renderer_->ResetCameraClippingRange();
}

void Viewer::update_info() {
  if (!hud_) return;
  const int* d = volume_.image->GetDimensions();
  const double* s = volume_.image->GetSpacing();
  const std::string voxel =
      s[0] == s[1] && s[1] == s[2]
          ? format_number(s[0])
          : fmt::format("{} x {} x {}", format_number(s[0]), format_number(s[1]), format_number(s[2]));
  std::string text = fmt::format("{}\n{} x {} x {} voxels, voxel {}\n", volume_.source.filename().string(),
                                 d[0], d[1], d[2], voxel);
  text += fmt::format("{}: {} set", field_.label(), field_.set_voxels);
  if (field_.kind != ChannelKind::kOccupancy && field_.kind != ChannelKind::kInside && field_.set_voxels)
    text += fmt::format(", {} .. {}", format_number(field_.low), format_number(field_.high));
  text += fmt::format("\nview: {}", view_kind_name(view_));
  if (view_ == ViewKind::kSlices)
    text += fmt::format("  x {}  y {}  z {}", slice_view_->index(0), slice_view_->index(1),
                        slice_view_->index(2));
  if (view_ == ViewKind::kVolume && opacity_scale_ != 1.0)
    text += fmt::format("  opacity x{:.2g}", opacity_scale_);
  if (mesh_)
    text += fmt::format("\nmesh: {} ({} triangles, {})", fs::path(options_.mesh).filename().string(),
                        mesh_->triangles(), mesh_style_name(mesh_->style()));
  hud_->set_info(text);
}

void Viewer::save_numbered_screenshot() {
  for (int i = 1; i < 10000; ++i) {
    const fs::path out = fmt::format("voxr-view-{}.png", i);
    std::error_code ec;
    if (fs::exists(out, ec)) continue;
    try {
      save_screenshot(window_, out);
      std::printf("voxr-view: wrote %s\n", out.c_str());
    } catch (const Error& e) {
      std::fprintf(stderr, "voxr-view: error: %s\n", e.what());
    }
    std::fflush(stdout);
    return;
  }
}

}  // namespace voxr::view
