// The stability suite (issue 11): one scene per failure mode the sources name or that we found, every method
// run on it, each measure checked against a bound. `voxr bench stability` runs the full suite and writes
// docs/stability.md (tables and small pictures, generated, never edited by hand); the test suite runs the
// small version of every case (StabilityContext::full false) and fails when a bound is broken, so a
// regression in stability fails a test.
//
// Families, each in its own file (one concept per file):
//   voxelization  voxelization_stability.cpp: 24 random rotations of each test mesh (mean, max and spread of
//                 each method's error), steep triangles (centre-mode holes), sub-voxel features and thin
//                 shells, grid-aligned planes, non-watertight and duplicated geometry, meshes far from the
//                 origin;
//   rendering     rendering_stability.cpp: grazing light and view, floors under light 1-3 degrees above the
//                 horizon and a point light 1e5 units away (issue 20), receivers among casters, sheet
//                 self-shadowing (acne, leaks), total internal reflection (IOR 2.42), several boundary voxels
//                 along one ray, rays slipping through voxel corners, multi-material boundaries, and glass
//                 walls 0.5 to 8 voxels of the fitted refraction grid thick (thin-wall/*);
//   inputs        input_stability.cpp: degenerate and non-finite inputs (a clear error or a documented
//                 result, never a crash or NaN pixels);
//   temporal      temporal_stability.cpp: a slowly moving and deforming scene, each method's frame-to-frame
//                 change against the reference's (flicker).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"

namespace voxr {

// One measure of one method on one case, checked against a bound that states a requirement and says which
// (`reason`): physics ("physics: ..."), the method's documented rule ("rule: ..."), an issue's target
// ("issue 19 target: ..."), the method's purpose ("purpose: better than ..."), or a documented failure held
// in both directions ("documented failure: ...": low <= value <= bound, so a change either way is seen).
// `pass` is low <= value <= bound (or, for a measure that must be at least the bound, value >= bound:
// `at_least`). A row with no reason, or with an infinite bound (it could not fail), never passes.
struct StabilityRow {
  std::string family;   // "voxelization", "rendering", "inputs", "temporal"
  std::string name;     // the case, e.g. "random-rotations/bunny"
  std::string method;   // e.g. "slice-conservative", "voxel-multi", "reference"
  std::string measure;  // what `value` is, with its unit, e.g. "false-negative share (mean of 24)"
  double value = 0.0;
  double bound = 0.0;
  bool at_least = false;
  double low = -std::numeric_limits<double>::infinity();  // finite: a two-sided (documented) expectation
  std::string note;     // one short line: what the number means or what happened (an error's text)
  std::string reason;   // where the bound comes from (shown on the page); see above
  std::string picture;  // optional: a small PNG written under StabilityContext::picture_dir (relative path)
  bool pass() const {
    if (reason.empty() || std::isinf(bound)) return false;
    return at_least ? value >= bound : (value <= bound && value >= low);
  }
};

// A row built from its fields (the families' `row` helpers); `reason` as StabilityRow's.
inline StabilityRow stability_row(std::string family, std::string name, std::string method,
                                  std::string measure, double value, double bound, bool at_least,
                                  std::string note, std::string reason = {}) {
  StabilityRow r;
  r.family = std::move(family);
  r.name = std::move(name);
  r.method = std::move(method);
  r.measure = std::move(measure);
  r.value = value;
  r.bound = bound;
  r.at_least = at_least;
  r.note = std::move(note);
  r.reason = std::move(reason);
  return r;
}

// A documented failure held in both directions: `row` passes when low <= value <= high; `why` says what the
// failure is and where it is documented (the reason becomes "documented failure: " + why).
inline StabilityRow documented(StabilityRow row, double low, double high, const std::string& why) {
  row.at_least = false;
  row.low = low;
  row.bound = high;
  row.reason = "documented failure: " + why;
  return row;
}

struct StabilityContext {
  ClRuntime& cl;
  bool full = false;                  // false: the small version the test suite runs (seconds per case)
  std::filesystem::path picture_dir;  // empty: write no pictures
  std::function<void(const std::string&)> progress;  // one line per finished case; may be empty
};

struct StabilityCase {
  std::string family, name;
  std::string description;  // one sentence: the failure mode and the source that names it
  std::function<std::vector<StabilityRow>(StabilityContext&)> run;
};

std::vector<StabilityCase> voxelization_stability_cases();
std::vector<StabilityCase> rendering_stability_cases();
std::vector<StabilityCase> input_stability_cases();
std::vector<StabilityCase> temporal_stability_cases();

}  // namespace voxr
