#include "render_regression.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <vector>

#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "util/error.h"

namespace voxr::test {

namespace fs = std::filesystem;

namespace {

bool update_mode() {
  const char* env = std::getenv("VOXR_UPDATE_REFERENCES");
  return env && std::strcmp(env, "1") == 0;
}

bool valid_name(const std::string& name) {
  if (name.empty() || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

size_t non_finite_values(const ImageRgba& image) {
  size_t n = 0;
  for (const glm::vec4& p : image.pixels)
    for (int c = 0; c < 4; ++c) n += !std::isfinite(p[c]);
  return n;
}

// |actual - reference| per RGB value, scaled so the largest is 1 (unscaled when all are 0); alpha 1. Sets
// `scale` to the factor used.
ImageRgba difference_image(const ImageRgba& actual, const ImageRgba& reference, double& scale) {
  ImageRgba out(actual.width, actual.height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  float largest = 0.0f;
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    const glm::vec3 d = glm::abs(glm::vec3(actual.pixels[i]) - glm::vec3(reference.pixels[i]));
    out.pixels[i] = glm::vec4(d, 1.0f);
    largest = std::max({largest, d.x, d.y, d.z});
  }
  scale = largest > 0.0f ? 1.0 / double(largest) : 1.0;
  for (glm::vec4& p : out.pixels) p = glm::vec4(glm::vec3(p) * float(scale), 1.0f);
  return out;
}

// Writes NAME.KIND.exr and NAME.KIND.png into the scratch folder; returns a line for the failure message.
std::string write_scratch(const ImageRgba& image, const fs::path& scratch, const std::string& name,
                          const char* kind) {
  try {
    fs::create_directories(scratch);
    for (const char* ext : {".exr", ".png"}) write_image(image, scratch / (name + "." + kind + ext));
    return fmt::format("\n  wrote {}", (scratch / (name + "." + kind + ".{exr,png}")).string());
  } catch (const std::exception& e) {
    return fmt::format("\n  could not write the {} image: {}", kind, e.what());
  }
}

// Removes what an earlier failing run of NAME left in the scratch folder.
void remove_scratch(const fs::path& scratch, const std::string& name) {
  std::error_code ec;
  for (const char* kind : {"actual", "reference", "difference"})
    for (const char* ext : {".exr", ".png"}) fs::remove(scratch / (name + "." + kind + ext), ec);
}

std::string update_hint(const fs::path& reference) {
  return fmt::format(
      "\n  to accept the actual image as the new reference, rerun with VOXR_UPDATE_REFERENCES=1 (it writes "
      "{}), "
      "look at it and commit it",
      reference.string());
}

}  // namespace

::testing::AssertionResult matches_reference(const ImageRgba& actual, const std::string& name,
                                             RegressionTolerance tolerance,
                                             const RegressionFolders& folders) {
  if (!valid_name(name))
    return ::testing::AssertionFailure() << "render regression: bad reference name '" << name
                                         << "' (letters, digits, '_', '-' and '.', not starting with '.')";
  const fs::path reference_path = folders.references / (name + ".exr");
  const std::string title = fmt::format("render regression '{}'", name);
  if (actual.width == 0 || actual.height == 0 || actual.pixels.size() != size_t(actual.width) * actual.height)
    return ::testing::AssertionFailure()
           << title << ": the image is empty or its pixels do not match its size";
  if (const size_t bad = non_finite_values(actual))
    return ::testing::AssertionFailure() << title << ": the image has " << bad << " NaN or infinite values"
                                         << write_scratch(actual, folders.scratch, name, "actual");

  if (update_mode()) {
    try {
      fs::create_directories(folders.references);
      write_image(actual, reference_path);
    } catch (const std::exception& e) {
      return ::testing::AssertionFailure() << title << ": could not write the reference: " << e.what();
    }
    std::printf("[ UPDATED  ] %s: wrote reference %s (%ux%u) because VOXR_UPDATE_REFERENCES=1\n",
                title.c_str(), reference_path.string().c_str(), actual.width, actual.height);
    std::fflush(stdout);
    return ::testing::AssertionSuccess() << "reference written";
  }

  std::error_code ec;
  if (!fs::exists(reference_path, ec))
    return ::testing::AssertionFailure() << title << ": no reference image " << reference_path.string()
                                         << write_scratch(actual, folders.scratch, name, "actual")
                                         << "\n  to create it from this image, rerun with "
                                            "VOXR_UPDATE_REFERENCES=1, look at the new file and "
                                            "commit it";
  ImageRgba reference;
  try {
    reference = read_image(reference_path);
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure()
           << title << ": cannot read the reference: " << e.what()
           << write_scratch(actual, folders.scratch, name, "actual") << update_hint(reference_path);
  }
  if (reference.width != actual.width || reference.height != actual.height)
    return ::testing::AssertionFailure()
           << title << ": the image is " << actual.width << "x" << actual.height << ", the reference "
           << reference_path.string() << " is " << reference.width << "x" << reference.height
           << write_scratch(actual, folders.scratch, name, "actual") << update_hint(reference_path);

  const double error = rmse(actual, reference);
  size_t over = 0, worst = 0;
  float worst_difference = -1.0f;
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    const glm::vec3 d = glm::abs(glm::vec3(actual.pixels[i]) - glm::vec3(reference.pixels[i]));
    // A NaN in the reference counts as a difference.
    const float m = std::isnan(d.x + d.y + d.z) ? INFINITY : std::max({d.x, d.y, d.z});
    over += !(m <= tolerance.pixel_threshold);
    if (m > worst_difference) {
      worst_difference = m;
      worst = i;
    }
  }
  const double share = double(over) / double(actual.pixels.size());
  const std::string summary = fmt::format(
      "RMSE {:.6g} (allowed {:.6g}); {} of {} pixels ({:.4g}%) differ by more than {:.6g} (allowed {:.4g}%); "
      "largest difference {:.6g} at pixel ({}, {})",
      error, tolerance.max_rmse, over, actual.pixels.size(), 100.0 * share, tolerance.pixel_threshold,
      100.0 * tolerance.max_share_over, worst_difference, worst % actual.width, worst / actual.width);
  if (error <= tolerance.max_rmse && share <= tolerance.max_share_over) {
    remove_scratch(folders.scratch, name);
    return ::testing::AssertionSuccess() << title << ": " << summary;
  }

  double scale = 1.0;
  const ImageRgba difference = difference_image(actual, reference, scale);
  return ::testing::AssertionFailure()
         << title << " does not match " << reference_path.string() << ": " << summary
         << write_scratch(actual, folders.scratch, name, "actual")
         << write_scratch(reference, folders.scratch, name, "reference")
         << write_scratch(difference, folders.scratch, name, "difference")
         << fmt::format(" (|actual - reference| x {:.4g})", scale) << update_hint(reference_path);
}

}  // namespace voxr::test
