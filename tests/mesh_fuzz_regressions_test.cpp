// Inputs the mesh fuzzers (fuzz/, scripts/fuzz.sh) found or pointed at, each read the way voxr reads files
// (load_mesh on a file in a temporary folder): each ends in the right mesh or a one-line voxr::Error that
// starts with the file path, promptly and without reserving memory a header merely claims.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/mesh_loader.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// load_mesh's error for `content` written to `name`, or "no error".
std::string load_error(const test::TempDir& dir, const std::string& name, const std::string& content) {
  const fs::path file = dir.write(name, content);
  try {
    load_mesh(file);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  return "no error";
}

const char* const kCubeAsciiPlyBody =
    "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
    "4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 0 2 3 1\n4 4 5 7 6\n";

// The seed corpus of the fuzzers is a valid file in every format (else the fuzzers would start from errors).
TEST(MeshFuzzRegressions, SeedCorpusLoads) {
  const fs::path corpus = fs::path(VOXR_SOURCE_DIR) / "fuzz" / "corpus";
  size_t files = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(corpus)) {
    // fuzz/corpus/scene and env_image hold the scene reader's and the image reader's seeds
    // (scene_inputs_test.cpp, image_file_test.cpp).
    const fs::path folder = e.path().parent_path().filename();
    if (!e.is_regular_file() || folder == "scene" || folder == "env_image") continue;
    SCOPED_TRACE(e.path().string());
    const TriangleSoup soup = load_mesh(e.path());
    EXPECT_EQ(soup.triangle_count(), e.path().stem() == "concave" ? 4u : 12u);
    ++files;
  }
  EXPECT_EQ(files, 11u);
}

// PLY: an element without properties holds no bytes, but the reader counted through its 2^64 - 1 instances
// (a hang).
TEST(MeshFuzzRegressions, PlyElementWithoutPropertiesIsSkipped) {
  test::TempDir dir;
  const std::string ply = std::string(
                              "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                              "property float z\nelement nothing 18446744073709551615\nelement face 6\n"
                              "property list uchar int vertex_indices\nend_header\n") +
                          kCubeAsciiPlyBody;
  const auto start = std::chrono::steady_clock::now();
  const TriangleSoup soup = load_mesh(dir.write("empty_element.ply", ply));
  EXPECT_EQ(soup.triangle_count(), 12u);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

// OFF and PLY reserved up to 2^24 vertices (and OFF 2^24 faces) on a header's word: a 23-byte file took
// 670 MB of address space (402 MB in one allocation, which libFuzzer's -malloc_limit_mb=100 reports). They
// now reserve only what the bytes after the header can hold, and fail on the truncation as before.
TEST(MeshFuzzRegressions, HugeHeaderCountsReserveNothing) {
  test::TempDir dir;
  EXPECT_NE(load_error(dir, "counts.off", "OFF\n99999999 99999999 0\n")
                .find("declares 99999999 vertices but ends after 0"),
            std::string::npos);
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 99999999\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(load_error(dir, "counts.ply", ply).find("vertex 0 of 99999999, property 'x': the file ends here"),
            std::string::npos);
}

// glTF whose embedded base64 buffer holds a byte that is not base64 (the seed cube with one byte changed):
// Assimp 5.2.5 leaked the decoded buffer on this input (fuzz/lsan.supp); voxr refuses it before Assimp reads
// it.
TEST(MeshFuzzRegressions, GltfBadBase64IsAnError) {
  std::ifstream in(fs::path(VOXR_SOURCE_DIR) / "fuzz" / "corpus" / "gltf" / "cube.gltf", std::ios::binary);
  std::string gltf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t data = gltf.find("base64,");
  ASSERT_NE(data, std::string::npos);
  test::TempDir dir;
  // The fuzzer's input exactly: a byte that is not UTF-8 in the base64 data is no JSON, refused before Assimp
  // (whose decoder leaked on it).
  gltf[data + 7 + 151] = '\x8e';
  EXPECT_NE(load_error(dir, "bad_base64.gltf", gltf).find(": not glTF 2.0 JSON"), std::string::npos);
}

// glTF (through Assimp) had no bound on coordinates: the fuzzers found positions that were infinite or NaN
// after the node transforms, which went on into the triangulation (CGAL) before anything checked them, and
// a cube 3e38 units away loaded. read_with_assimp now refuses them as voxr's own readers do.
TEST(MeshFuzzRegressions, GltfCoordinatesBeyondRangeAreAnError) {
  std::ifstream in(fs::path(VOXR_SOURCE_DIR) / "fuzz" / "corpus" / "gltf" / "cube.gltf", std::ios::binary);
  std::string gltf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = gltf.find("\"translation\":[1,0,0]");
  ASSERT_NE(at, std::string::npos);
  gltf.replace(at, 21, "\"translation\":[3e38,0,0]");
  test::TempDir dir;
  EXPECT_NE(load_error(dir, "far.gltf", gltf).find("vertex 0 is not finite or too large"), std::string::npos);
}

TEST(MeshFuzzRegressions, FilesThatAreNotTheirFormatNeverReachAssimpsSniffing) {
  // Found by fuzzing: Assimp hung on this 23-byte .gltf and took 2.3 GB on this 83-byte .glb (its header
  // claims 1.7 GB), after the importer for the extension declined them and it tried every other one.
  test::TempDir dir;
  const std::string gltf(
      "\x50\x4f\x53\x49\x54\x3a\x4f\x4e\x7b\x69\x6e\x64\x65\x78\x61\x72\x72\x61\x79\x43\x34\x22\x2b", 23),
      glb("\x67\x6c\x54\x46\x02\x00\x00\x00\xa4\x62\x6c\x65\x6e\x64\x65\x72\x4a\x53\x4f\x4e\x7b\x22\x61\x73"
          "\x73\x2e\x65\x74\x22\x3a\x7b\x22\x76\x65\x72\x73\x69\x6f\x6e\x22\x3a\x22\x32\x2e\x30\x22\x7d\x2c"
          "\x22\x73\x63\x65\x3a\x65\x22\x3a\x30\x2c\x22\x73\x63\x65\x6e\x65\x73\x22\x74\x65\x72\x72\x61\x67"
          "\x65\x6e\x73\x22\x3a\x5b\x30\x5d\x22\xa4\x5d",
          83);
  EXPECT_NE(load_error(dir, "hang.gltf", gltf).find("hang.gltf: not glTF 2.0 JSON"), std::string::npos);
  EXPECT_NE(load_error(dir, "huge.glb", glb).find("huge.glb: the binary glTF header gives a length of"),
            std::string::npos);
  EXPECT_NE(load_error(dir, "x.dae", "<xml/>").find("x.dae: not COLLADA"), std::string::npos);
  EXPECT_NE(load_error(dir, "x.3mf", "PK").find("x.3mf: not 3MF"), std::string::npos);
  EXPECT_NE(load_error(dir, "x.fbx", "hello").find("x.fbx: not FBX"), std::string::npos);
}

}  // namespace
}  // namespace voxr
