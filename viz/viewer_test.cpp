// voxr-view end to end: the test writes a small volume with voxr's own writers, runs the viewer as a process
// under a virtual X server (xvfb-run -a) and checks the PNG it saves: its size, that it is not one colour,
// and that the objects' pixels are where the objects are, seen from a known camera. Bad input must fail
// with one line on stderr and a non-zero exit, without needing a display. Small and thin grids are also
// loaded in-process through the viewer's loader and compared with what was written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "grid/voxel_grid.h"
#include "io/volume_writer.h"
#include "volume_loader.h"
#include "vtk_messages.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// ---- Test volume -----------------------------------------------------------------------------------------
//
// A 32^3 grid over the unit cube with two solid boxes, seen from the front (camera on +Z, +X right, +Y up):
//   A  x 18..29, y  4..27, z 6..25   right half, full height        count 1, material 0
//   B  x  3..13, y 18..27, z 6..25   upper left                      count 5, material 3
// so the lower left quarter of the picture is empty.
constexpr uint32_t kN = 32;

struct Box {
  glm::uvec3 lo, hi;  // inclusive
  uint32_t count, material;
  uint32_t color;  // RGBA8, R in the low byte
};
constexpr Box kBoxes[] = {{{18, 4, 6}, {29, 27, 25}, 1, 0, 0xff1e28dcu},   // (220, 40, 30): red
                          {{3, 18, 6}, {13, 27, 25}, 5, 3, 0xffdc3c1eu}};  // (30, 60, 220): blue

// `axes` columns are the grid axes in the world; `origin` the world position of the grid's corner.
VoxelGrid make_test_grid(const glm::mat3& axes = glm::mat3(1.0f), const glm::vec3& origin = glm::vec3(0.0f)) {
  VoxelGrid g;
  g.spec.axes = axes;
  g.spec.origin = origin;
  g.spec.voxel_size = 1.0f / kN;
  g.spec.dims = glm::uvec3(kN);
  g.channels = ChannelSet::parse("occ,count,material,color");
  g.occ.assign(size_t((g.spec.voxel_count() + 31) / 32), 0u);
  for (uint32_t k = 0; k < kN; ++k)
    for (uint32_t j = 0; j < kN; ++j)
      for (uint32_t i = 0; i < kN; ++i)
        for (const Box& b : kBoxes)
          if (i >= b.lo.x && i <= b.hi.x && j >= b.lo.y && j <= b.hi.y && k >= b.lo.z && k <= b.hi.z) {
            const uint64_t l = g.spec.linear_index(i, j, k);
            g.occ[l >> 5] |= 1u << (l & 31);
            ++g.voxels_set;
            g.count.push_back(b.count);
            g.material.push_back(b.material);
            g.color.push_back(b.color);
          }
  return g;
}

// A closed box mesh over box A, for --mesh.
void write_box_obj(const fs::path& path) {
  const Box& b = kBoxes[0];
  const float h = 1.0f / kN;
  const glm::vec3 lo = glm::vec3(b.lo) * h + 0.25f * h, hi = glm::vec3(b.hi + 1u) * h - 0.25f * h;
  std::ofstream out(path);
  for (int c = 0; c < 8; ++c)
    out << fmt::format("v {} {} {}\n", (c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
  for (const char* f : {"1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"})
    out << "f " << f << "\n";
}

// ---- Running the viewer ----------------------------------------------------------------------------------

struct Result {
  int code = -1;
  std::string output;  // stdout and stderr
};

Result run(const std::string& command) {
  Result r;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

std::string viewer() {
  return quoted(VOXR_VIEW_PATH);
}

// Under a virtual X server with a 24-bit screen, as the README shows.
std::string under_xvfb(const std::string& args) {
  return fmt::format("{} -a -s '-screen 0 1280x1024x24' {} {}", quoted(VOXR_XVFB_RUN), viewer(), args);
}

// Removes a suite's folder, kept after a failure or with VOXR_VIEW_TEST_KEEP set, to look at the pictures.
void remove_unless_failed(const fs::path& dir) {
  std::error_code ec;
  if (::testing::UnitTest::GetInstance()->current_test_suite()->failed_test_count() == 0 &&
      !std::getenv("VOXR_VIEW_TEST_KEEP"))
    fs::remove_all(dir, ec);
  else
    std::printf("voxr-view test files kept in %s\n", dir.c_str());
}

class ViewerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / fmt::format("voxr_view_test_{}", ::getpid());
    fs::create_directories(dir_);
    const VoxelGrid grid = make_test_grid();
    write_volume(grid, dir_ / "boxes.vti");
    write_volume(grid, dir_ / "boxes.nrrd");
    // The same grid turned 90 degrees about +Z (grid x -> world +Y, grid y -> world -X), still over the unit
    // cube: box A becomes a band across the top, box B sits lower left, the lower right is empty.
    const glm::mat3 turn(glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1));
    const VoxelGrid turned = make_test_grid(turn, glm::vec3(1, 0, 0));
    write_volume(turned, dir_ / "turned.vti");
    write_volume(turned, dir_ / "turned.nrrd");
    write_box_obj(dir_ / "box.obj");
  }
  static void TearDownTestSuite() { remove_unless_failed(dir_); }
  static fs::path dir_;
};

fs::path ViewerTest::dir_;

// ---- Reading the PNG -------------------------------------------------------------------------------------

struct Picture {
  int width = 0, height = 0;
  vtkSmartPointer<vtkImageData> image;

  // Mean colour of the 5x5 block at (x, y), y counted from the top, as fractions of the size.
  std::array<double, 3> at(double fx, double fy) const {
    const int cx = int(fx * width), cy = height - 1 - int(fy * height);
    std::array<double, 3> sum{};
    int n = 0;
    for (int y = cy - 2; y <= cy + 2; ++y)
      for (int x = cx - 2; x <= cx + 2; ++x) {
        if (x < 0 || y < 0 || x >= width || y >= height) continue;
        for (int c = 0; c < 3; ++c) sum[c] += image->GetScalarComponentAsDouble(x, y, 0, c);
        ++n;
      }
    for (double& s : sum) s /= std::max(n, 1);
    return sum;
  }
  bool single_color() const {
    auto* s = image->GetPointData()->GetScalars();
    const int comps = s->GetNumberOfComponents();
    for (vtkIdType i = 1; i < s->GetNumberOfTuples(); ++i)
      for (int c = 0; c < comps; ++c)
        if (s->GetComponent(i, c) != s->GetComponent(0, c)) return false;
    return true;
  }
};

Picture read_png(const fs::path& path) {
  Picture p;
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str())) return p;
  reader->SetFileName(path.c_str());
  reader->Update();
  p.image = reader->GetOutput();
  p.width = p.image->GetDimensions()[0];
  p.height = p.image->GetDimensions()[1];
  return p;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

std::string text(const std::array<double, 3>& c) {
  return fmt::format("({:.0f}, {:.0f}, {:.0f})", c[0], c[1], c[2]);
}

// transfer_presets.h: kBackground (0.11, 0.12, 0.15) and kEmptyVoxel (0.22, 0.22, 0.24), in 8 bits.
constexpr std::array<double, 3> kBackground{28.05, 30.6, 38.25};
constexpr std::array<double, 3> kEmptyVoxel{56.1, 56.1, 61.2};

// Where the boxes are in a front view of the test volume (fractions of the picture, y from the top).
constexpr std::array<double, 2> kInBoxA{0.65, 0.5}, kInBoxB{0.36, 0.32};
constexpr std::array<double, 2> kEmptyQuarter{0.35, 0.72}, kCorner{0.03, 0.03}, kFarCorner{0.97, 0.97};

Picture screenshot(const fs::path& dir, const std::string& name, const std::string& args) {
  const fs::path png = dir / (name + ".png");
  const Result r =
      run(under_xvfb(fmt::format("{} --screenshot {} {}", quoted(dir / "boxes.vti"), quoted(png), args)));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(png)) << r.output;
  return read_png(png);
}

// ---- Screenshots -----------------------------------------------------------------------------------------

// Pixel values that differ between two pictures of one size (-1 when the sizes differ).
vtkIdType differing_values(const Picture& first, const Picture& second) {
  vtkDataArray* a = first.image->GetPointData()->GetScalars();
  vtkDataArray* b = second.image->GetPointData()->GetScalars();
  if (a->GetNumberOfValues() != b->GetNumberOfValues()) return -1;
  vtkIdType differ = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    differ += a->GetVariantValue(i) != b->GetVariantValue(i);
  return differ;
}

TEST_F(ViewerTest, IsoFrontViewShowsTheBoxesWhereTheyAre) {
  const Picture p =
      screenshot(dir_, "iso", "--view iso --size 320,240 --azimuth 0 --elevation 0 --no-overlay");
  ASSERT_EQ(p.width, 320);
  ASSERT_EQ(p.height, 240);
  EXPECT_FALSE(p.single_color());
  EXPECT_LT(distance(p.at(kCorner[0], kCorner[1]), kBackground), 6.0) << text(p.at(kCorner[0], kCorner[1]));
  EXPECT_LT(distance(p.at(kFarCorner[0], kFarCorner[1]), kBackground), 6.0);
  EXPECT_LT(distance(p.at(kEmptyQuarter[0], kEmptyQuarter[1]), kBackground), 6.0)
      << "lower left is empty: " << text(p.at(kEmptyQuarter[0], kEmptyQuarter[1]));
  EXPECT_GT(distance(p.at(kInBoxA[0], kInBoxA[1]), kBackground), 150.0) << text(p.at(kInBoxA[0], kInBoxA[1]));
  EXPECT_GT(distance(p.at(kInBoxB[0], kInBoxB[1]), kBackground), 150.0) << text(p.at(kInBoxB[0], kInBoxB[1]));
}

TEST_F(ViewerTest, VolumeFrontViewShowsTheBoxesWhereTheyAre) {
  const Picture p =
      screenshot(dir_, "volume", "--view volume --size 320,240 --azimuth 0 --elevation 0 --no-overlay");
  ASSERT_EQ(p.width, 320);
  ASSERT_EQ(p.height, 240);
  EXPECT_LT(distance(p.at(kCorner[0], kCorner[1]), kBackground), 6.0);
  EXPECT_LT(distance(p.at(kEmptyQuarter[0], kEmptyQuarter[1]), kBackground), 6.0);
  EXPECT_GT(distance(p.at(kInBoxA[0], kInBoxA[1]), kBackground), 150.0) << text(p.at(kInBoxA[0], kInBoxA[1]));
  EXPECT_GT(distance(p.at(kInBoxB[0], kInBoxB[1]), kBackground), 150.0) << text(p.at(kInBoxB[0], kInBoxB[1]));
}

TEST_F(ViewerTest, SliceFrontViewShowsEmptyAndSetVoxels) {
  // The z plane (k = 16) faces the camera; the x and y planes are edge-on.
  const Picture p =
      screenshot(dir_, "slices", "--view slices --size 320,240 --azimuth 0 --elevation 0 --no-overlay");
  ASSERT_EQ(p.width, 320);
  EXPECT_LT(distance(p.at(kCorner[0], kCorner[1]), kBackground), 6.0);
  EXPECT_LT(distance(p.at(kEmptyQuarter[0], kEmptyQuarter[1]), kEmptyVoxel), 6.0)
      << text(p.at(kEmptyQuarter[0], kEmptyQuarter[1]));
  EXPECT_GT(distance(p.at(kInBoxA[0], kInBoxA[1]), kEmptyVoxel), 150.0);
  EXPECT_GT(distance(p.at(kInBoxB[0], kInBoxB[1]), kEmptyVoxel), 150.0);
}

TEST_F(ViewerTest, MaterialSlicesHaveOneColourPerMaterial) {
  const Picture p =
      screenshot(dir_, "material",
                 "--view slices --array material --size 320,240 --azimuth 0 --elevation 0 --no-overlay");
  ASSERT_EQ(p.width, 320);
  const auto a = p.at(kInBoxA[0], kInBoxA[1]), b = p.at(kInBoxB[0], kInBoxB[1]);
  EXPECT_GT(distance(a, b), 100.0) << text(a) << " vs " << text(b);
  EXPECT_GT(distance(a, kEmptyVoxel), 100.0);
}

TEST_F(ViewerTest, EveryArrayAndViewRendersWithOverlayAndMesh) {
  for (const char* array : {"occupancy", "count", "material", "color"})
    for (const char* view : {"volume", "slices", "iso"}) {
      SCOPED_TRACE(fmt::format("{} {}", array, view));
      const Picture p = screenshot(dir_, fmt::format("{}_{}", array, view),
                                   fmt::format("--array {} --view {} --size 400,300 --mesh {}", array, view,
                                               quoted(dir_ / "box.obj")));
      ASSERT_EQ(p.width, 400);
      ASSERT_EQ(p.height, 300);
      EXPECT_FALSE(p.single_color());
    }
}

TEST_F(ViewerTest, ColorArrayIsShownAsTheVoxelsColours) {
  // Slices draw the colours as stored (ambient 1, no lookup table) and leave empty voxels transparent.
  const std::string front = "--array color --size 320,240 --azimuth 0 --elevation 0 --no-overlay";
  const std::array<double, 3> red{220, 40, 30}, blue{30, 60, 220};
  const Picture slices = screenshot(dir_, "color_slices", front + " --view slices");
  EXPECT_LT(distance(slices.at(kInBoxA[0], kInBoxA[1]), red), 6.0) << text(slices.at(kInBoxA[0], kInBoxA[1]));
  EXPECT_LT(distance(slices.at(kInBoxB[0], kInBoxB[1]), blue), 6.0)
      << text(slices.at(kInBoxB[0], kInBoxB[1]));
  EXPECT_LT(distance(slices.at(kEmptyQuarter[0], kEmptyQuarter[1]), kBackground), 6.0)
      << text(slices.at(kEmptyQuarter[0], kEmptyQuarter[1]));
  // Lit (iso) and composited (volume): the hue survives.
  for (const char* view : {"iso", "volume"}) {
    SCOPED_TRACE(view);
    const Picture p = screenshot(dir_, fmt::format("color_{}", view), front + " --view " + view);
    const auto a = p.at(kInBoxA[0], kInBoxA[1]), b = p.at(kInBoxB[0], kInBoxB[1]);
    EXPECT_GT(a[0], a[1] + 60.0) << text(a);
    EXPECT_GT(a[0], a[2] + 60.0) << text(a);
    EXPECT_GT(b[2], b[0] + 60.0) << text(b);
    EXPECT_GT(b[2], b[1] + 60.0) << text(b);
    EXPECT_LT(distance(p.at(kEmptyQuarter[0], kEmptyQuarter[1]), kBackground), 6.0);
  }
}

TEST_F(ViewerTest, KeysSwitchViewsArraysAndHelp) {
  const std::string front = "--size 320,240 --azimuth 0 --elevation 0 --no-overlay --view iso";
  // 2: the slice view (the z plane shows empty voxels in the empty quarter).
  const Picture slices = screenshot(dir_, "keys_slices", front + " --keys 2");
  EXPECT_LT(distance(slices.at(kEmptyQuarter[0], kEmptyQuarter[1]), kEmptyVoxel), 6.0);
  // a a: occupancy -> count -> material; material 0 and 3 differ in colour.
  const Picture material = screenshot(dir_, "keys_material", front + " --keys 2aa");
  EXPECT_GT(distance(material.at(kInBoxA[0], kInBoxA[1]), material.at(kInBoxB[0], kInBoxB[1])), 100.0);
  // z z z ... moves the z plane out of the boxes (k = 16 + 12 = 28 > 25): no set voxels left on it.
  const Picture moved = screenshot(dir_, "keys_moved", front + " --keys 2zzzzzzzzzzzz");
  EXPECT_LT(distance(moved.at(kInBoxA[0], kInBoxA[1]), kEmptyVoxel), 6.0)
      << text(moved.at(kInBoxA[0], kInBoxA[1]));
  // h: the help box darkens the middle of the picture.
  const Picture help = screenshot(dir_, "keys_help", front + " --keys h");
  EXPECT_LT(help.at(0.5, 0.5)[0], 0.6 * slices.at(0.5, 0.5)[0] + 1.0);
}

TEST_F(ViewerTest, NrrdSetLooksLikeTheVti) {
  // Opening a sibling file loads the whole set; placed in the world as the .vti is, it renders the same.
  const std::string args = "--array count --view slices --size 240,180 --elevation 40 --no-overlay";
  std::vector<Picture> pictures;
  for (const char* file : {"boxes.vti", "boxes.count.nrrd"}) {
    const fs::path png = dir_ / (std::string(file) + ".png");
    const Result r =
        run(under_xvfb(fmt::format("{} {} --screenshot {}", quoted(dir_ / file), args, quoted(png))));
    ASSERT_EQ(r.code, 0) << r.output;
    pictures.push_back(read_png(png));
    ASSERT_EQ(pictures.back().width, 240);
    EXPECT_FALSE(pictures.back().single_color());
  }
  EXPECT_EQ(differing_values(pictures[0], pictures[1]), 0)
      << "pixel values differ between the .vti and the .nrrd picture";
}

TEST_F(ViewerTest, TurnedGridIsPlacedByItsAxes) {
  const std::string args = "--view iso --size 320,240 --azimuth 0 --elevation 0 --no-overlay";
  for (const char* file : {"turned.vti", "turned.nrrd"}) {
    SCOPED_TRACE(file);
    const fs::path png = dir_ / (std::string(file) + ".png");
    const Result r =
        run(under_xvfb(fmt::format("{} {} --screenshot {}", quoted(dir_ / file), args, quoted(png))));
    ASSERT_EQ(r.code, 0) << r.output;
    const Picture p = read_png(png);
    ASSERT_EQ(p.width, 320);
    EXPECT_GT(distance(p.at(0.5, 0.3), kBackground), 150.0)
        << "band across the top: " << text(p.at(0.5, 0.3));
    EXPECT_GT(distance(p.at(0.38, 0.7), kBackground), 150.0) << "lower left: " << text(p.at(0.38, 0.7));
    EXPECT_LT(distance(p.at(0.65, 0.7), kBackground), 6.0)
        << "lower right is empty: " << text(p.at(0.65, 0.7));
  }
}

// ---- Small and thin grids -------------------------------------------------------------------------------
//
// vtkNrrdReader takes a first axis of 9 or fewer samples for vector components; the loader must instead
// open every shape voxr writes as written, the same from .nrrd and .vti, with normal as 3 components.

// Every channel, with values that differ from voxel to voxel so a misread layout cannot match.
VoxelGrid make_pattern_grid(const glm::uvec3& dims) {
  VoxelGrid g;
  g.spec.voxel_size = 0.25f;
  g.spec.origin = glm::vec3(-1.0f, 0.5f, 2.0f);
  g.spec.dims = dims;
  g.channels = ChannelSet::parse("occ,count,normal,material,inside");
  g.occ.assign(size_t((g.spec.voxel_count() + 31) / 32), 0u);
  g.inside.assign(g.occ.size(), 0u);
  for (uint32_t k = 0; k < dims.z; ++k)
    for (uint32_t j = 0; j < dims.y; ++j)
      for (uint32_t i = 0; i < dims.x; ++i) {
        const uint64_t l = g.spec.linear_index(i, j, k);
        if ((i + 2 * j + 3 * k) % 3 != 1) {
          g.occ[l >> 5] |= 1u << (l & 31);
          ++g.voxels_set;
          g.count.push_back(uint32_t(1 + l % 7));
          g.normal.push_back(glm::normalize(glm::vec3(float(i) + 1.0f, float(j) - 0.5f, float(k) + 2.0f)));
          g.material.push_back(uint32_t(l % 5));
        } else if ((i + j + k) % 2 == 0) {
          g.inside[l >> 5] |= 1u << (l & 31);
          ++g.inside_voxels;
        }
      }
  return g;
}

// The values written for `array` (component `c`) at every voxel, in linear order: zero where empty.
std::vector<double> written_values(const VoxelGrid& g, const std::string& array, int c) {
  std::vector<double> values(size_t(g.spec.voxel_count()), 0.0);
  for (uint64_t l = 0; l < values.size(); ++l)
    if (array == "inside") values[l] = g.is_inside(l);
  g.for_each_set([&](uint64_t l, uint64_t rank) {
    if (array == "occupancy") values[l] = 1.0;
    if (array == "count") values[l] = g.count[rank];
    if (array == "normal") values[l] = g.normal[rank][c];
    if (array == "material") values[l] = g.material[rank];
  });
  return values;
}

class SmallGridTest : public ::testing::TestWithParam<glm::uvec3> {
 protected:
  static void SetUpTestSuite() {
    view::install_vtk_message_collector();
    dir_ = fs::temp_directory_path() / fmt::format("voxr_view_small_{}", ::getpid());
    fs::create_directories(dir_);
  }
  static void TearDownTestSuite() { remove_unless_failed(dir_); }
  static fs::path dir_;
};

fs::path SmallGridTest::dir_;

TEST_P(SmallGridTest, LoadsAsWrittenFromNrrdAndVtiAndRenders) {
  const glm::uvec3 dims = GetParam();
  const VoxelGrid grid = make_pattern_grid(dims);
  const std::string stem = fmt::format("grid_{}x{}x{}", dims.x, dims.y, dims.z);
  const std::vector<std::string> arrays = {"occupancy", "count", "normal", "material", "inside"};
  const std::vector<int> components = {1, 1, 3, 1, 1};

  std::vector<view::Volume> volumes;
  for (const char* ext : {".nrrd", ".vti"}) {
    SCOPED_TRACE(stem + ext);
    write_volume(grid, dir_ / (stem + ext));
    volumes.push_back(view::load_volume(dir_ / (stem + ext)));
    const view::Volume& v = volumes.back();
    EXPECT_EQ(fmt::format("{}x{}x{}", v.dims(0), v.dims(1), v.dims(2)), stem.substr(5));
    for (int a = 0; a < 3; ++a) EXPECT_FLOAT_EQ(v.voxel_size(a), grid.spec.voxel_size) << "axis " << a;
    ASSERT_EQ(v.arrays, arrays);
    for (size_t a = 0; a < arrays.size(); ++a) {
      vtkDataArray* values = v.image->GetPointData()->GetArray(arrays[a].c_str());
      ASSERT_NE(values, nullptr) << arrays[a];
      ASSERT_EQ(values->GetNumberOfComponents(), components[a]) << arrays[a];
      ASSERT_EQ(uint64_t(values->GetNumberOfTuples()), grid.spec.voxel_count()) << arrays[a];
      for (int c = 0; c < components[a]; ++c) {
        const std::vector<double> expected = written_values(grid, arrays[a], c);
        int wrong = 0;
        for (size_t l = 0; l < expected.size(); ++l)
          wrong += values->GetComponent(vtkIdType(l), c) != expected[l];
        EXPECT_EQ(wrong, 0) << arrays[a] << "[" << c << "]: values differ from those written";
      }
    }
  }
  const double* o0 = volumes[0].image->GetOrigin();
  const double* o1 = volumes[1].image->GetOrigin();
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(o0[a], o1[a], 1e-6) << "origin, axis " << a;

  // Rendered offscreen, each file gives the same picture in every view.
  for (const char* view : {"slices", "volume", "iso"}) {
    std::vector<Picture> pictures;
    for (const char* ext : {".nrrd", ".vti"}) {
      SCOPED_TRACE(fmt::format("{}{} {}", stem, ext, view));
      const fs::path png = dir_ / fmt::format("{}{}.{}.png", stem, ext, view);
      const std::string array = std::string(view) == "volume" ? "normal" : "occupancy";
      const Result r = run(under_xvfb(
          fmt::format("{} --screenshot {} --view {} --array {} --size 160,120 --elevation 30 --no-overlay",
                      quoted(dir_ / (stem + ext)), quoted(png), view, array)));
      ASSERT_EQ(r.code, 0) << r.output;
      pictures.push_back(read_png(png));
      ASSERT_EQ(pictures.back().width, 160);
      // A line or single voxel has no area for the volume mapper to ray-cast: it draws nothing there.
      if (std::string(view) != "volume" || (dims.x > 1) + (dims.y > 1) + (dims.z > 1) >= 2) {
        EXPECT_FALSE(pictures.back().single_color());
      }
    }
    EXPECT_EQ(differing_values(pictures[0], pictures[1]), 0)
        << view << ": the .nrrd and .vti pictures differ";
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, SmallGridTest,
                         ::testing::Values(glm::uvec3(8, 20, 20), glm::uvec3(1, 5, 7), glm::uvec3(20, 1, 1),
                                           glm::uvec3(3, 3, 3), glm::uvec3(9, 2, 30), glm::uvec3(1, 1, 1),
                                           glm::uvec3(10, 12, 1)),
                         [](const ::testing::TestParamInfo<glm::uvec3>& info) {
                           return fmt::format("x{}_y{}_z{}", info.param.x, info.param.y, info.param.z);
                         });

// ---- Bad input -------------------------------------------------------------------------------------------

void expect_one_line_error(const Result& r, const std::string& mentions) {
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("voxr-view: error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(mentions), std::string::npos) << "expected '" << mentions << "' in: " << r.output;
}

// ---- .vdb -----------------------------------------------------------------------------------------------

#ifdef VOXR_VIEW_OPENVDB
// A .vdb (written by voxr's OpenVDB plugin) loads as the .vti of the same grid does: same shape, placement
// and values of every array (.vdb holds no inside channel), and the same pictures.
TEST(VdbLoad, LoadsAsTheVtiAndRendersTheSame) {
  setenv("VOXR_OPENVDB_PLUGIN", VOXR_OPENVDB_PLUGIN, 0);
  view::install_vtk_message_collector();
  const fs::path dir = fs::temp_directory_path() / fmt::format("voxr_view_vdb_{}", ::getpid());
  fs::create_directories(dir);
  VoxelGrid grid = make_pattern_grid(glm::uvec3(9, 20, 13));
  grid.channels.remove(Channel::kInside);
  grid.inside.clear();
  grid.inside_voxels = 0;
  const glm::mat3 turn(glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1));
  grid.spec.axes = turn;
  write_volume(grid, dir / "g.vti");
  write_volume(grid, dir / "g.vdb");
  const view::Volume a = view::load_volume(dir / "g.vti");
  const view::Volume b = view::load_volume(dir / "g.vdb");
  ASSERT_EQ(a.arrays, b.arrays);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(a.dims(axis), b.dims(axis));
    EXPECT_NEAR(a.voxel_size(axis), b.voxel_size(axis), 1e-7);
    EXPECT_NEAR(a.image->GetOrigin()[axis], b.image->GetOrigin()[axis], 1e-5);
  }
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(a.to_world->GetElement(r, c), b.to_world->GetElement(r, c), 1e-5) << r << "," << c;
  for (const std::string& name : a.arrays) {
    vtkDataArray* x = a.image->GetPointData()->GetArray(name.c_str());
    vtkDataArray* y = b.image->GetPointData()->GetArray(name.c_str());
    ASSERT_NE(y, nullptr) << name;
    EXPECT_EQ(x->GetDataType(), y->GetDataType()) << name;
    ASSERT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents()) << name;
    ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples()) << name;
    int wrong = 0;
    for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
      for (int c = 0; c < x->GetNumberOfComponents(); ++c)
        wrong += x->GetComponent(t, c) != y->GetComponent(t, c);
    EXPECT_EQ(wrong, 0) << name << ": values differ from the .vti's";
  }
  std::vector<Picture> pictures;
  for (const char* file : {"g.vti", "g.vdb"}) {
    const fs::path png = dir / fmt::format("{}.png", file);
    const Result r =
        run(under_xvfb(fmt::format("{} --screenshot {} --view slices --array count --size 160,120 "
                                   "--elevation 30 --no-overlay",
                                   quoted(dir / file), quoted(png))));
    ASSERT_EQ(r.code, 0) << r.output;
    pictures.push_back(read_png(png));
  }
  EXPECT_FALSE(pictures[0].single_color());
  EXPECT_EQ(differing_values(pictures[0], pictures[1]), 0) << "the .vti and .vdb pictures differ";
  std::ofstream(dir / "fake.vdb") << "hello\n";
  expect_one_line_error(run(viewer() + " " + quoted(dir / "fake.vdb")), "cannot read the OpenVDB file");
  remove_unless_failed(dir);
}
#endif

TEST_F(ViewerTest, MissingFileFails) {
  expect_one_line_error(run(viewer() + " " + quoted(dir_ / "nothere.vti")), "no such file");
}

TEST_F(ViewerTest, WrongFormatFails) {
  std::ofstream(dir_ / "notes.txt") << "hello\n";
  expect_one_line_error(run(viewer() + " " + quoted(dir_ / "notes.txt")), "unknown volume format '.txt'");
  std::ofstream(dir_ / "fake.vti") << "hello\n";
  expect_one_line_error(run(viewer() + " " + quoted(dir_ / "fake.vti")), "not a VTK XML ImageData file");
  std::ofstream(dir_ / "fake.nrrd") << "P6 not a nrrd\n";
  expect_one_line_error(run(viewer() + " " + quoted(dir_ / "fake.nrrd")), "not a NRRD file");
  // The right header over truncated data: VTK's reader error, reduced to one line.
  std::string vti;
  {
    std::ifstream in(dir_ / "boxes.vti", std::ios::binary);
    vti.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(dir_ / "truncated.vti", std::ios::binary) << vti.substr(0, vti.size() / 3);
  expect_one_line_error(run(viewer() + " " + quoted(dir_ / "truncated.vti")), "truncated.vti");
}

TEST_F(ViewerTest, UnknownArrayFails) {
  const Result r = run(viewer() + " " + quoted(dir_ / "boxes.vti") + " --array density");
  expect_one_line_error(r, "--array 'density'");
  EXPECT_NE(r.output.find("occupancy, count, material"), std::string::npos) << r.output;
}

TEST_F(ViewerTest, BadFlagsFail) {
  const std::string vol = quoted(dir_ / "boxes.vti");
  expect_one_line_error(run(viewer() + " " + vol + " --size 10,x"), "--size");
  expect_one_line_error(run(viewer() + " " + vol + " --view sideways"), "--view 'sideways'");
  expect_one_line_error(run(viewer() + " " + vol + " --array count --component y"), "--component 1");
  expect_one_line_error(run(viewer() + " " + vol + " --slices 0,0,32"), "--slices");
  expect_one_line_error(run(viewer() + " " + vol + " --screenshot " + quoted(dir_ / "no/such/dir/x.png")),
                        "does not exist");
  expect_one_line_error(run(viewer() + " " + vol + " --mesh " + quoted(dir_ / "nothere.obj")), "nothere.obj");
  expect_one_line_error(run(viewer() + " " + vol + " --frobnicate"), "--frobnicate");
}

TEST_F(ViewerTest, VoxelizeViewNeedsAViewableOutput) {
  // Checked before voxelizing, so no OpenCL work happens here.
  const std::string voxr =
      quoted(VOXR_CLI_PATH) + " voxelize " + quoted(dir_ / "box.obj") + " --res 8 --view";
  Result r = run(voxr);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("--view needs -o OUT"), std::string::npos) << r.output;
  r = run(voxr + " -o " + quoted(dir_ / "box.binvox"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("voxr-view reads .vti, .nrrd and .vdb"), std::string::npos) << r.output;
}

TEST_F(ViewerTest, NoDisplayFailsWithAHint) {
  const Result r = run("env -u DISPLAY " + viewer() + " " + quoted(dir_ / "boxes.vti"));
  expect_one_line_error(r, "xvfb-run -a");
}

}  // namespace
}  // namespace voxr
