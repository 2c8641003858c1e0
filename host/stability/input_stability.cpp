// The inputs family of the stability suite (stability_case.h): degenerate and non-finite meshes, each
// written as an OBJ file and taken through the paths the CLI takes (load_input, validate_soup, fit_grid,
// every voxelization method, one small frame of FrameRenderer). Each stage either throws a clear voxr::Error
// (one line, naming what is wrong) — then the input is rejected and the later stages are skipped — or gives a
// documented result with no NaN (finite voxel counts, finite pixels). A crash, an exception of another type
// or a NaN fails the row. Each input also says which outcome it must have: rejected (NaN, Inf, empty),
// accepted (zero-area triangles, extreme aspect ratio) or either (collinear, point-sized, 1e30).
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>

#include "core/scene.h"
#include "io/atomic_file.h"
#include "render/camera_frame.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "stability/stability_case.h"
#include "stability/stability_voxels.h"
#include "util/error.h"

namespace voxr {

namespace {

constexpr const char* kFamily = "inputs";

enum class Expect { kRejected, kAccepted, kEither };

struct InputCase {
  std::string name, description;
  std::string obj;  // the file's text
  Expect expect;
  size_t degenerate = 0;  // zero-area triangles validate_soup must count (accepted inputs)
  // Set: the triangles come from memory (a library caller, a generator) instead of the file, so the
  // readers' own checks are bypassed and validate_soup is the one that must catch the problem.
  float in_memory_vertex = 0.0f;
  bool in_memory = false;
};

std::string box_obj(glm::dvec3 lo, glm::dvec3 hi) {
  std::string obj;
  for (int c = 0; c < 8; ++c)
    obj += fmt::format("v {} {} {}\n", c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
  obj +=
      "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\n"
      "f 2 8 6\n";
  return obj;
}

std::vector<InputCase> input_cases() {
  std::vector<InputCase> cases;
  // A box plus three zero-area triangles: a repeated vertex, three collinear vertices, a point.
  std::string degenerate = box_obj(glm::dvec3(0.0), glm::dvec3(1.0));
  degenerate += "v 0.5 0.5 2\nv 0.5 1.5 2\nv 0.5 2.5 2\nf 1 1 8\nf 9 10 11\nf 9 9 9\n";
  cases.push_back(
      {"zero-area-triangles",
       "A box with three zero-area triangles (repeated vertex, collinear, a point): counted and kept "
       "(conservative voxelization treats them as the segment or point they are).",
       degenerate, Expect::kAccepted, 3});
  cases.push_back({"all-collinear",
                   "Every triangle on one line (zero area, bounds of zero extent on two axes).",
                   "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3\nf 2 3 4\n", Expect::kEither});
  cases.push_back({"nan-vertex", "A vertex with a NaN coordinate used by a triangle: must be rejected.",
                   box_obj(glm::dvec3(0.0), glm::dvec3(1.0)) + "v nan 0 0\nf 1 2 9\n", Expect::kRejected});
  cases.push_back({"inf-vertex",
                   "A vertex with an infinite coordinate (1e39 overflows float): must be rejected.",
                   box_obj(glm::dvec3(0.0), glm::dvec3(1.0)) + "v 1e39 0 0\nf 1 2 9\n", Expect::kRejected});
  for (const auto& [label, value] :
       {std::pair<std::string, float>{"nan", std::numeric_limits<float>::quiet_NaN()},
        std::pair<std::string, float>{"inf", std::numeric_limits<float>::infinity()}}) {
    InputCase c{label + "-vertex-in-memory",
                "A box built in memory with one vertex " + label +
                    " (no reader to catch it): validate_soup must reject it.",
                box_obj(glm::dvec3(0.0), glm::dvec3(1.0)), Expect::kRejected};
    c.in_memory = true;
    c.in_memory_vertex = value;
    cases.push_back(c);
  }
  cases.push_back({"point-sized", "Every vertex at the same point: a mesh of zero size.",
                   "v 0.25 0.5 0.75\nv 0.25 0.5 0.75\nv 0.25 0.5 0.75\nf 1 2 3\n", Expect::kEither});
  cases.push_back({"empty", "A file with vertices and no triangles: must be rejected.", "v 0 0 0\nv 1 0 0\n",
                   Expect::kRejected});
  cases.push_back({"huge-coordinates", "A box from -1e30 to 1e30, the largest coordinates the readers take.",
                   box_obj(glm::dvec3(-1e30), glm::dvec3(1e30)), Expect::kEither});
  cases.push_back({"beyond-coordinate-limit",
                   "A box at 2e30, past the readers' limit (1e30): must be rejected.",
                   box_obj(glm::dvec3(2e30), glm::dvec3(3e30)), Expect::kRejected});
  cases.push_back({"extreme-aspect", "A box 1000 x 0.001 x 1: one voxel thick at any resolution.",
                   box_obj(glm::dvec3(0.0), glm::dvec3(1000.0, 0.001, 1.0)), Expect::kAccepted});
  return cases;
}

const char* expect_name(Expect e) {
  return e == Expect::kRejected ? "rejected" : e == Expect::kAccepted ? "accepted" : "rejected or accepted";
}

// The outcome of one stage: ok (a result, checked finite by the stage), a clear voxr::Error, or anything
// else.
struct Outcome {
  bool ok = false, clear_error = false;
  std::string text;  // the result's summary or the exception's message
};

Outcome attempt(const std::function<std::string()>& stage) {
  Outcome o;
  try {
    o.text = stage();
    o.ok = true;
  } catch (const Error& e) {
    o.text = e.what();
    o.clear_error = !o.text.empty() && o.text.find('\n') == std::string::npos && o.text.size() < 400;
  } catch (const std::exception& e) {
    o.text = fmt::format("not a voxr::Error: {}", e.what());
  }
  return o;
}

std::vector<StabilityRow> run_input(StabilityContext& ctx, const InputCase& c) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("voxr-stability-{}", getpid());
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / (c.name + ".obj");
  write_file_atomically(file, c.obj);
  const std::string name = "input/" + c.name;
  std::vector<StabilityRow> rows;
  bool rejected = false;
  auto stage = [&](const std::string& method, const std::string& what,
                   const std::function<std::string()>& fn) {
    if (rejected) return;
    const Outcome o = attempt(fn);
    StabilityRow r;
    r.family = kFamily;
    r.name = name;
    r.method = method;
    r.measure = what + ": a result or a clear error (1 = yes)";
    r.value = o.ok || o.clear_error ? 1.0 : 0.0;
    r.bound = 1.0;
    r.at_least = true;
    r.note = o.ok ? o.text : "error: " + o.text;
    r.reason = "rule: every stage gives a result or a clear error, never a crash or NaN pixels";
    // The page is generated: the temporary folder (a process id) stays out of it.
    for (size_t at; (at = r.note.find(dir.string() + "/")) != std::string::npos;)
      r.note.erase(at, dir.string().size() + 1);
    rows.push_back(r);
    rejected = !o.ok;
  };
  Scene scene;
  TriangleSoup soup;
  GridSpec grid;
  size_t degenerate = 0;
  stage("load_input", "read the file", [&] {
    scene = load_input(file);
    soup = scene_triangles(scene);
    if (c.in_memory) {
      soup.positions[0].y = c.in_memory_vertex;
      return fmt::format("{} triangles; vertex 0's y set to {} in memory", soup.triangle_count(),
                         c.in_memory_vertex);
    }
    return fmt::format("{} triangles", soup.triangle_count());
  });
  stage("validate_soup", "validate", [&] {
    degenerate = validate_soup(soup, file.filename().string());
    return fmt::format("{} zero-area triangles", degenerate);
  });
  stage("fit_grid", "fit a grid", [&] {
    GridRequest request;
    request.resolution = ctx.full ? 64 : 16;
    grid = fit_grid(soup.bounds(), request, soup.anchor);
    if (!std::isfinite(grid.voxel_size) || !(grid.voxel_size > 0.0f))
      fail("fit_grid gave voxel size {}", grid.voxel_size);
    return fmt::format("{}x{}x{} voxels of {:.3g}", grid.dims.x, grid.dims.y, grid.dims.z, grid.voxel_size);
  });
  MethodRunner runner(ctx.cl);
  for (const std::string& method : stability_methods()) {
    if (rejected) break;
    stage(method, "voxelize", [&] {
      const VoxelGrid result = runner.run(method, soup, grid);
      return fmt::format("{} voxels", result.voxels_set);
    });
  }
  stage("render", "render 32x24 (voxel shadows)", [&] {
    FrameRenderer renderer(ctx.cl);
    renderer.set_scene(soup, scene.materials);
    const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 32, 24);
    const RenderLight light =
        render_light(scene.light, make_environment_map(scene.environment).mean(), soup.anchor);
    RenderOptions options;
    options.shadow_resolution = 32;
    renderer.prepare(options);
    const RenderedFrame frame = renderer.render(light, camera, options);
    size_t nan = 0;
    for (const glm::vec4& p : frame.image.pixels)
      nan += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w));
    if (nan) fail("{} of {} pixels are not finite", nan, frame.image.pixels.size());
    return fmt::format("{} pixels, all finite", frame.image.pixels.size());
  });
  std::filesystem::remove_all(dir);
  StabilityRow r;
  r.family = kFamily;
  r.name = name;
  r.method.assign(1, '-');  // not = "-": GCC 12 warns (-Wrestrict, a false positive, PR 105329)
  r.measure = fmt::format("outcome as expected: {} (1 = yes)", expect_name(c.expect));
  r.value = c.expect == Expect::kEither || (c.expect == Expect::kRejected) == rejected ? 1.0 : 0.0;
  r.bound = 1.0;
  r.at_least = true;
  r.note = rejected ? "rejected at " + rows.back().method : "accepted by every stage";
  r.reason = "rule: the outcome documented for this input (docs/mesh-files.md)";
  if (c.expect == Expect::kAccepted && !rejected && degenerate != c.degenerate) {
    r.value = 0.0;
    r.note =
        fmt::format("validate_soup counted {} zero-area triangles, {} planted", degenerate, c.degenerate);
  }
  rows.push_back(r);
  return rows;
}

}  // namespace

std::vector<StabilityCase> input_stability_cases() {
  std::vector<StabilityCase> cases;
  for (const InputCase& c : input_cases())
    cases.push_back({kFamily, "input/" + c.name, c.description,
                     [c](StabilityContext& ctx) { return run_input(ctx, c); }});
  return cases;
}

}  // namespace voxr
