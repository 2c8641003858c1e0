// Render regression tests against stored reference images, in the manner of Mitsuba 3's test suite: a test
// renders a small image and asserts EXPECT_TRUE(matches_reference(image, "shadow_tree_point", tolerance)).
//
// References are linear float EXR files, tests/render_references/NAME.exr, kept small (e.g. 96x72). An image
// matches when the RMSE over all its R, G and B values (metrics/image_metrics.h) and the share of pixels
// whose largest channel difference exceeds pixel_threshold are both within the tolerance, and it has no NaN
// or infinite value. On a mismatch the harness writes NAME.actual.exr, NAME.reference.exr and
// NAME.difference.exr
// (|actual - reference| scaled so that the largest difference is 1), and a .png of each, into the scratch
// folder (build/render-regression/), and the failure message names them.
//
// VOXR_UPDATE_REFERENCES=1 in the environment turns every check into an update: the reference is (re)written
// from the image and the check passes with a printed note. Review the new references before committing them.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "util/image_rgba.h"

namespace voxr::test {

struct RegressionTolerance {
  double max_rmse = 0.01;         // over all R, G and B values, linear
  double pixel_threshold = 0.05;  // a pixel differs when its largest channel |difference| exceeds this
  double max_share_over = 0.01;   // share of the pixels that may differ
};

struct RegressionFolders {
  std::filesystem::path references = VOXR_SOURCE_DIR "/tests/render_references";
  std::filesystem::path scratch = VOXR_BINARY_DIR "/render-regression";  // created when first written to
};

// True when `actual` matches references/NAME.exr within `tolerance` (see above). `name` is a file stem of
// letters, digits, '_', '-' and '.'. Fails, explaining why, on a mismatch, a size difference, a NaN or
// infinite value in `actual`, a missing or unreadable reference (saying how to create it) or a bad name.
// With VOXR_UPDATE_REFERENCES=1, writes the reference instead and passes.
::testing::AssertionResult matches_reference(const ImageRgba& actual, const std::string& name,
                                             RegressionTolerance tolerance = {},
                                             const RegressionFolders& folders = {});

}  // namespace voxr::test
