// The voxr executable end to end: success writes the files and the report; bad input exits non-zero
// with one line that names what is wrong.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_support.h"

namespace {

namespace fs = std::filesystem;

using Result = voxr::test::CliResult;
using voxr::test::scratch;
using voxr::test::slurp;

Result run_with_env(const std::string& env, const std::string& args) {
  return voxr::test::run_voxr(args, env);
}

Result run(const std::string& args) {
  return voxr::test::run_voxr(args);
}

fs::path write_file(const std::string& name, const std::string& content) {
  return voxr::test::write_scratch_file(name, content);
}

void expect_one_line_error(const Result& r, const std::string& needle) {
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
}

const std::string kTetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(Cli, VoxelizeWritesVolumesAndReport) {
  const fs::path mesh = write_file("tetra.obj", kTetra);
  const fs::path out = scratch() / "tetra.nrrd", report = scratch() / "tetra.json";
  const Result r = run("voxelize " + mesh.string() + " --res 32 --channels occ,count,normal,material -o " +
                       out.string() + " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(scratch() / "tetra.count.nrrd"));
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  for (const char* key : {"device", "triangles", "dims", "copies", "voxels_set"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["triangles"], 4);
  EXPECT_GT(j["voxels_set"].get<uint64_t>(), 0u);
  for (const char* key : {"upload", "kernels", "total", "stages"}) EXPECT_TRUE(j["ms"].contains(key)) << key;
  EXPECT_TRUE(j["ms"]["stages"].contains("raster"));
}

TEST(Cli, MissingFile) {
  expect_one_line_error(run("voxelize /nonexistent/mesh.obj"), "/nonexistent/mesh.obj");
}

TEST(Cli, GarbledFile) {
  const fs::path p = write_file("garbage.off", std::string("\x01\x02OFF\xff\xfe garbage \x00\x13", 18));
  expect_one_line_error(run("voxelize " + p.string()), p.string());
}

TEST(Cli, EmptyMesh) {
  const fs::path p = write_file("empty.obj", "# nothing here\n");
  expect_one_line_error(run("voxelize " + p.string()), p.string());
}

// Issue 20, kind 1 (../shared/cases/render/r01_deep_json.json): a scene whose camera.position is an array
// nested 100 000 deep (200 KB) crashed voxelize and render while quoting it; both now refuse it in one line
// that names the file and the key, exit 1.
TEST(Cli, DeeplyNestedSceneValueIsAOneLineError) {
  const int depth = 100000;
  const fs::path p = write_file("deep.json", R"({"meshes":[{"generator":"box"}],"camera":{"position":)" +
                                                 std::string(depth, '[') + std::string(depth, ']') + "}}");
  for (const std::string command : {"voxelize -o " + (scratch() / "deep.nrrd").string(),
                                    "render -o " + (scratch() / "deep.png").string()}) {
    const Result r = run(command + " " + p.string());
    expect_one_line_error(r, p.string() + ": 'camera.position' must be an array of 3 numbers");
  }
}

// Issue 20, kind 9: an existing read-only output is refused in one line before any work, and left as it was.
TEST(Cli, ReadOnlyOutputIsAOneLineErrorAndUntouched) {
  const fs::path mesh = write_file("ro-tetra.obj", kTetra);
  const fs::path out = write_file("locked.nrrd", "old");
  fs::permissions(out, fs::perms::owner_read);
  expect_one_line_error(run("voxelize " + mesh.string() + " --res 8 -o " + out.string()),
                        out.string() + ": the file exists and is read-only");
  EXPECT_EQ(slurp(out), "old");
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read);
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write);
}

TEST(Cli, NanVertex) {
  const fs::path p = write_file("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_one_line_error(run("voxelize " + p.string()), p.string());
}

TEST(Cli, ZeroResolution) {
  const fs::path p = write_file("tetra2.obj", kTetra);
  expect_one_line_error(run("voxelize " + p.string() + " --res 0"), "--res");
}

TEST(Cli, AbsurdSizeExceedsMemory) {
  const fs::path p = write_file("tetra3.obj", kTetra);
  expect_one_line_error(run("voxelize " + p.string() + " --dims 16384,16384,16384 --layout dense"), "MiB");
}

TEST(Cli, SparseLayoutWritesWhatDenseWritesAndReportsItsMemory) {
  const fs::path mesh = write_file("tetra-sparse.obj", kTetra);
  std::string files[2];
  int i = 0;
  for (const char* layout : {"dense", "sparse"}) {
    const fs::path out = scratch() / fmt::format("tetra-{}.vti", layout);
    const fs::path report = scratch() / fmt::format("tetra-{}.json", layout);
    // A 1 MiB budget cuts the 200^3 grid into slabs.
    const Result r =
        run("voxelize " + mesh.string() + " --res 200 --channels occ,count,normal,material --layout " +
            layout + " --memory-budget 1M -o " + out.string() + " --report " + report.string());
    ASSERT_EQ(r.code, 0) << r.err;
    files[i++] = slurp(out);
    const nlohmann::json j = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(j["layout"], layout);
    if (std::string(layout) == "sparse") {
      EXPECT_GT(j["sparse"]["slabs"].get<int>(), 1);
      EXPECT_GT(j["sparse"]["bricks"].get<uint64_t>(), 0u);
      EXPECT_GE(j["sparse"]["bricks_marked"].get<uint64_t>(), j["sparse"]["bricks"].get<uint64_t>());
      EXPECT_GT(j["sparse"]["peak_device_bytes"].get<uint64_t>(), 0u);
      EXPECT_NE(r.out.find("layout     sparse"), std::string::npos) << r.out;
    }
  }
  EXPECT_FALSE(files[0].empty());
  EXPECT_TRUE(files[0] == files[1]) << "the sparse run's .vti differs from the dense run's";
}

TEST(Cli, LayoutAndBudgetMistakesAreOneLineErrors) {
  const fs::path p = write_file("tetra-layout.obj", kTetra);
  expect_one_line_error(run("voxelize " + p.string() + " --layout bricks"), "--layout 'bricks'");
  expect_one_line_error(run("voxelize " + p.string() + " --memory-budget 12X"), "unknown unit");
  expect_one_line_error(run("voxelize " + p.string() + " --memory-budget lots"), "--memory-budget 'lots'");
  expect_one_line_error(run("voxelize " + p.string() + " --memory-budget 10K"), "at least 1M");
  expect_one_line_error(run("voxelize " + p.string() + " --layout sparse --solid parity"), "--layout dense");
  expect_one_line_error(run("voxelize " + p.string() + " --layout sparse --method slicemap"), "slicemap");
}

TEST(Cli, BadChannelModeAndExtension) {
  const fs::path p = write_file("tetra4.obj", kTetra);
  expect_one_line_error(run("voxelize " + p.string() + " --channels occ,colour"), "colour");
  expect_one_line_error(run("voxelize " + p.string() + " --mode sideways"), "sideways");
  expect_one_line_error(run("voxelize " + p.string() + " -o " + (scratch() / "x.png").string()), "x.png");
  expect_one_line_error(
      run("voxelize " + p.string() + " --dims 4,5,6 -o " + (scratch() / "x.binvox").string()), "x.binvox");
}

}  // namespace

namespace {

// --progress shows each step on stderr as one line with the seconds since the start, with -q and with stderr
// not a terminal (a pipe here); without it, -q prints nothing.
TEST(Cli, ProgressPrintsOneLinePerStep) {
  const fs::path mesh = write_file("tetra_progress.obj", kTetra);
  const fs::path out = scratch() / "progress.vti";
  const Result r = run("voxelize " + mesh.string() + " --res 16 -q --progress -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("voxr: ["), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" s] reading " + mesh.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" s] voxelizing: surface"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" s] writing " + out.string()), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  const Result quiet = run("voxelize " + mesh.string() + " --res 16 -q -o " + out.string());
  EXPECT_EQ(quiet.err, "");
}

TEST(Cli, MethodsAndTheirFlags) {
  const fs::path mesh = write_file("tetra5.obj", kTetra);
  for (const char* method : {"--method slice --mode center", "--method grid", "--method slicemap",
                             "--method slicemap --slicing local"}) {
    const Result r = run("voxelize " + mesh.string() + " --res 24 -q " + method);
    EXPECT_EQ(r.code, 0) << method << ": " << r.err;
  }
  expect_one_line_error(run("voxelize " + mesh.string() + " --method octree"), "octree");
  expect_one_line_error(run("voxelize " + mesh.string() + " --method slicemap --mode conservative"),
                        "mode does not apply to method slicemap");
  expect_one_line_error(run("voxelize " + mesh.string() + " --slicing local"),
                        "slicing applies to method slicemap");
  expect_one_line_error(run("voxelize " + mesh.string() + " --method slicemap --channels occ,count"), "occ");
}

}  // namespace

namespace {

TEST(Cli, NoOpenClPlatformSaysHowToInstallPocl) {
  const Result r = run_with_env("OCL_ICD_VENDORS=/nonexistent-vendors", "devices");
  expect_one_line_error(r, "pocl-opencl-icd");
}

TEST(Cli, KernelBuildFailureShowsTheLog) {
  const fs::path dir = scratch() / "broken-kernels";
  fs::remove_all(dir);
  fs::copy(fs::path(VOXR_SOURCE_DIR) / "kernels", dir, fs::copy_options::recursive);
  std::ofstream(dir / "voxelize" / "vox_setup.cl", std::ios::app) << "\nthis is not OpenC\n";
  const fs::path mesh = write_file("tetra6.obj", kTetra);
  const Result r =
      run_with_env("VOXR_KERNEL_DIR=" + dir.string() + " POCL_CACHE_DIR=" + (scratch() / "pocl").string(),
                   "voxelize " + mesh.string() + " --res 16");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("building kernel file vox_setup.cl"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("this"), std::string::npos) << "the compiler's log names the bad line: " << r.err;
}

}  // namespace

namespace {

TEST(Cli, EmptyVolumeIsWrittenWithAWarning) {
  // A grid beside the mesh: the volume is empty, which is the right answer, but never a silent one.
  const fs::path mesh = write_file("tetra-beside.obj", kTetra);
  const fs::path out = scratch() / "beside.vox";
  for (const std::string solid : {"", " --solid parity"}) {
    const Result r =
        run("voxelize " + mesh.string() + " --bounds 5,5,5,6,6,6 --res 8 -q -o " + out.string() + solid);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: no voxel of the 8 x 8 x 8 grid touches"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(check the bounds)"), std::string::npos) << r.err;
  }
  const Result r = run("voxelize " + mesh.string() + " --res 8 -q -o " + out.string());
  EXPECT_EQ(r.err, "");
}

TEST(Cli, SolidWritesTheInsideChannel) {
  const fs::path mesh = write_file("tetra7.obj", kTetra);
  const fs::path out = scratch() / "solid.nrrd", report = scratch() / "solid.json";
  const Result r = run("voxelize " + mesh.string() + " --res 24 --solid parity -o " + out.string() +
                       " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(scratch() / "solid.inside.nrrd"));
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(j["solid"]["mode"], "parity");
  EXPECT_GT(j["solid"]["inside_voxels"].get<uint64_t>(), 0u);
}

TEST(Cli, SolidParityOnAnOpenMeshWarnsAndFillsLate) {
  // The tetrahedron without its last face: open.
  const fs::path mesh =
      write_file("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  const Result r = run("voxelize " + mesh.string() + " --res 24 --solid parity --report " +
                       (scratch() / "open.json").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("not closed"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch() / "open.json"))["solid"]["mode"], "late");
}

TEST(Cli, ReportIsCompleteForEveryMode) {
  // Surface methods, solid modes and channels in one call: every report has the voxels set, the timings
  // (wall included) and, with --solid, the interior; the surface and the solid come from one run.
  const fs::path mesh =
      write_file("cube-report.obj",
                 "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\n"
                 "v 1 1 1\nf 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\n"
                 "f 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n");
  const std::pair<const char*, const char*> modes[] = {
      {"", "occ"},
      {"--method slice --mode center", "occ"},
      {"--method grid --channels occ,count", "occ,count"},
      {"--method slicemap --slicing local", "occ"},
      {"--solid parity --channels occ,count,normal,material", "occ,count,normal,material,inside"},
      {"--solid late --channels occ,normal", "occ,normal,inside"},
      {"--solid flood", "occ,inside"},
      {"--solid xor --mode center", "occ,inside"},
  };
  for (const auto& [flags, channels] : modes) {
    const fs::path report = scratch() / "modes.json";
    const Result r =
        run("voxelize " + mesh.string() + " --res 20 -q " + flags + " --report " + report.string());
    ASSERT_EQ(r.code, 0) << flags << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(j["channels"], channels) << flags;
    EXPECT_GT(j["voxels_set"].get<uint64_t>(), 100u) << flags;
    EXPECT_EQ(j["triangles"], 12) << flags;
    for (const char* key : {"kernels", "total", "wall", "process"})
      EXPECT_GT(j["ms"][key].get<double>(), 0.0) << flags << " ms." << key;
    EXPECT_FALSE(j["ms"]["stages"].empty()) << flags;
    if (std::string(channels).find("inside") != std::string::npos) {
      EXPECT_GT(j["solid"]["inside_voxels"].get<uint64_t>(), 1000u) << flags;
    } else {
      EXPECT_FALSE(j.contains("solid")) << flags;
    }
  }
}

TEST(Cli, BinvoxFromResolutionIsCubic) {
  const fs::path mesh = write_file("tetra-binvox.obj", kTetra);
  const fs::path out = scratch() / "tetra.binvox";
  const Result r = run("voxelize " + mesh.string() + " --res 24 -q -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(out).find("dim 24 24 24\n"), std::string::npos);
  expect_one_line_error(run("voxelize " + mesh.string() + " --dims 24,20,24 -q -o " + out.string()), "cubic");
}

TEST(Cli, Table1RunsTheOpenVdbPeerWhenBuilt) {
  const fs::path plugin = fs::path(VOXR_CLI_PATH).parent_path() / "libvoxr_openvdb_peer.so";
  if (!fs::exists(plugin)) GTEST_SKIP() << "built without OpenVDB";
  const fs::path out = scratch() / "t1";
  const Result r =
      run("bench table1 --models torus --res 16 --methods hybrid-conservative,openvdb --repeat 1 "
          "--warmup 0 --out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(out.string() + ".csv");
  EXPECT_NE(csv.find(",openvdb,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",hybrid-conservative,"), std::string::npos) << csv;
}

TEST(Cli, SparseFormatsVdbAndNpz) {
  const fs::path mesh = write_file("tetra-sparse.obj", kTetra);
  const fs::path npz = scratch() / "tetra.npz";
  Result r = run("voxelize " + mesh.string() + " --res 16 -q --channels occ,count -o " + npz.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(npz).substr(0, 4), std::string("PK\x03\x04", 4));
  // Without the OpenVDB plugin .vdb is refused before any work, in one line, and nothing is written.
  const fs::path vdb = scratch() / "tetra.vdb";
  r = run_with_env("VOXR_OPENVDB_PLUGIN=" + (scratch() / "no-plugin.so").string(),
                   "voxelize " + mesh.string() + " --res 16 -q -o " + vdb.string());
  expect_one_line_error(r, "tetra.vdb");
  EXPECT_NE(r.err.find("OpenVDB plugin"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(vdb));
  if (!fs::exists(fs::path(VOXR_CLI_PATH).parent_path() / "libvoxr_openvdb_peer.so")) return;
  r = run("voxelize " + mesh.string() + " --res 16 -q -o " + vdb.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(vdb).substr(0, 4), std::string(" BDV", 4));  // OpenVDB's magic number, little endian
}

TEST(Cli, InsideChannelNeedsSolid) {
  const fs::path mesh = write_file("tetra8.obj", kTetra);
  expect_one_line_error(run("voxelize " + mesh.string() + " --channels occ,inside"), "--solid");
  expect_one_line_error(run("voxelize " + mesh.string() + " --solid fill"), "fill");
}

}  // namespace

namespace {

const std::string kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
    "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 "
    "8 6\n";

uint64_t inside_voxels(const std::string& args, const std::string& name) {
  const fs::path report = scratch() / (name + ".json");
  const Result r = run(args + " -q --report " + report.string());
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(slurp(report))["solid"]["inside_voxels"].get<uint64_t>();
}

TEST(Cli, SolidKeepsCrossingsOfSplitTrianglesOutsideTheGrid) {
  // A thin column inside a cube, so deep that the cube's faces are split: the faces below (and, for late
  // filling, above) the grid must still count.
  const fs::path cube = write_file("cube.obj", kCube);
  const std::string inner = "voxelize " + cube.string() +
                            " --dims 2,2,2000 --bounds -0.00025,-0.00025,-0.25,"
                            "0.00025,0.00025,0.25";
  for (const char* mode : {"parity", "xor", "late"})
    EXPECT_EQ(inside_voxels(inner + " --solid " + mode, mode), 8000u) << mode;
  const std::string top = "voxelize " + cube.string() +
                          " --dims 2,2,2000 --bounds -0.00025,-0.00025,-1.01,"
                          "0.00025,0.00025,-0.51";
  EXPECT_EQ(inside_voxels(top + " --solid late", "late-top"),
            inside_voxels(top + " --solid parity", "parity-top"));
}

// Voxels set in a .binvox file (its run-length pairs of value, count after the "data" line).
uint64_t binvox_voxels_set(const fs::path& path) {
  const std::string data = slurp(path);
  const size_t start = data.find("data\n") + 5;
  uint64_t set = 0;
  for (size_t p = start; p + 1 < data.size(); p += 2) set += data[p] ? uint8_t(data[p + 1]) : 0;
  return set;
}

TEST(Cli, SolidBinvoxHoldsTheSolid) {
  const fs::path cube = write_file("cube2.obj", kCube);
  const fs::path out = scratch() / "solid.binvox";
  const uint64_t inside = inside_voxels(
      "voxelize " + cube.string() + " --dims 16,16,16 --solid parity -o " + out.string(), "binvox");
  const uint64_t set = binvox_voxels_set(out);
  // The single-set format holds the solid: surface and interior. The fitted grid puts the cube's faces a
  // quarter voxel inside the grid on every side, so every voxel centre is inside: all 16^3, symmetric.
  EXPECT_EQ(inside, 16u * 16u * 16u);
  EXPECT_EQ(set, 16u * 16u * 16u);
}

// A closed box [0,x]x[0,y]x[z0,z0+depth] as OFF, corners listed as in the shared failing cases.
std::string box_off(double x, double y, double z0, double depth) {
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n8 12 0\n";
  for (double z : {z0, z0 + depth})
    off << "0 0 " << z << "\n"
        << x << " 0 " << z << "\n"
        << x << " " << y << " " << z << "\n0 " << y << " " << z << "\n";
  off << "3 0 3 2\n3 0 2 1\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 2 3 7\n3 2 7 6\n3 0 4 7\n3 0 7 3\n"
         "3 1 2 6\n3 1 6 5\n";
  return off.str();
}

TEST(Cli, SolidBinvoxOfAUnitCubeIsTheWholeGrid) {
  // Case c02: a unit cube at --res 8 fills its fitted 8^3 grid, surface and interior alike.
  const fs::path cube = write_file("unit-cube.off", box_off(1, 1, 0, 1));
  const fs::path out = scratch() / "unit-cube.binvox";
  inside_voxels("voxelize " + cube.string() + " --res 8 --solid parity -o " + out.string(), "unit-cube");
  EXPECT_EQ(binvox_voxels_set(out), 512u);
}

// Voxels set in a .vox file (its XYZI chunk's count) and in an occupancy .nrrd (non-zero samples).
uint32_t vox_voxels_set(const fs::path& vox) {
  const std::string v = slurp(vox);
  const size_t xyzi = v.find("XYZI");
  if (xyzi == std::string::npos) return 0;
  uint32_t n = 0;
  std::memcpy(&n, v.data() + xyzi + 12, 4);
  return n;
}
uint64_t nrrd_voxels_set(const fs::path& nrrd) {
  const std::string n = slurp(nrrd);
  const size_t data = n.find("\n\n") + 2;
  return uint64_t(std::count_if(n.begin() + data, n.end(), [](char c) { return c != 0; }));
}

TEST(Cli, SolidOfAPlateThinnerThanAVoxelKeepsItsSurface) {
  // Case c08: a 10x10 plate 1/31.5 thick has no voxel centre inside, so the solid is its surface, in the
  // single-set .vox and in the occupancy .nrrd alike (never empty). The default grid holds it in one layer of
  // 64x64; the grid of the shared case's README (half-voxel margin: the plate on the face between two
  // layers, dims 64x64x2) gives its 8 192.
  const fs::path plate = write_file("plate.off", box_off(10, 10, 3, 2.0 / 63.0));
  const double h = 10.0 / 63.0, mid = 3.0 + 1.0 / 63.0;
  const std::string old_grid = fmt::format(" --dims 64,64,2 --bounds {},{},{},{},{},{}", -0.5 * h, -0.5 * h,
                                           mid - h, 10 + 0.5 * h, 10 + 0.5 * h, mid + h);
  for (const auto& [grid, expected] :
       {std::pair<std::string, uint32_t>{" --res 64", 4096u}, {old_grid, 8192u}}) {
    const fs::path vox = scratch() / "plate.vox", nrrd = scratch() / "plate.nrrd";
    for (const fs::path& out : {vox, nrrd})
      EXPECT_EQ(
          inside_voxels("voxelize " + plate.string() + grid + " --solid parity -o " + out.string(), "plate"),
          0u);
    EXPECT_EQ(vox_voxels_set(vox), expected) << grid;
    EXPECT_EQ(nrrd_voxels_set(nrrd), expected) << grid;
  }
}

TEST(Cli, HugeDeviceIndexIsNotACrash) {
  const Result r = run("voxelize --res 8 --device 99999999999999:0");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("no OpenCL device matches"), std::string::npos) << r.err;
}

TEST(Cli, FormatErrorsComeBeforeTheWork) {
  const fs::path mesh = write_file("tetra9.obj", kTetra);
  expect_one_line_error(
      run("voxelize " + mesh.string() + " --dims 300,300,300 -o " + (scratch() / "big.vox").string()),
      "at most 256");
  expect_one_line_error(run("voxelize " + mesh.string() + " --report /nonexistent-folder/r.json"),
                        "/nonexistent-folder/r.json");
  expect_one_line_error(run("bench voxelize --meshes torus --res 8 --cases nope"),
                        "unknown benchmark case 'nope'");
}

}  // namespace
