// The OpenCL plumbing a fresh process relies on: the on-disk program cache (round trip, UTF-8 keys, stale
// and corrupt entries rebuilt from source, programs built together on several threads) and the profiler's
// bounded window.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>

#include "cl/program_cache.h"
#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

TEST(ProgramCache, StoresAndLoadsByTheFullKey) {
  test::TempDir dir;
  const ProgramCache cache(dir.path());
  // Kernel sources are UTF-8 (em dashes in their banners): keys must compare as bytes.
  const std::string key = "platform\ndevice\noptions\n/* scan.cl \xe2\x80\x94 prefix sums */";
  const std::vector<unsigned char> binary = {0, 1, 2, 250, 255};
  EXPECT_FALSE(cache.load(key));
  cache.store(key, binary);
  ASSERT_TRUE(cache.load(key));
  EXPECT_EQ(*cache.load(key), binary);
  EXPECT_FALSE(cache.load(key + " "));                 // another key: never the stored binary
  EXPECT_FALSE(ProgramCache(std::nullopt).load(key));  // no folder: no cache, no error
}

TEST(ProgramCache, TruncatedEntriesAreIgnored) {
  test::TempDir dir;
  const ProgramCache cache(dir.path());
  for (const uintmax_t cut : {uintmax_t(12), uintmax_t(1)}) {  // in the header; the binary's last byte
    cache.store("k", {1, 2, 3});
    ASSERT_TRUE(cache.load("k"));
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      std::filesystem::resize_file(entry.path(), cut == 1 ? entry.file_size() - 1 : cut);
    EXPECT_FALSE(cache.load("k")) << cut;
  }
}

// What layout_probe.cl writes: one value per layout entry and the lattice constant.
#define VOXR_COUNT_ENTRY(...) +1
constexpr size_t kProbeValues = 1 VOXR_LAYOUT_ENTRIES(VOXR_COUNT_ENTRY, VOXR_COUNT_ENTRY);
#undef VOXR_COUNT_ENTRY

TEST(ProgramCache, CorruptBinariesAreRebuiltFromSource) {
  test::TempDir dir;
  const char* old = std::getenv("VOXR_CACHE_DIR");
  const std::string saved = old ? old : "";
  setenv("VOXR_CACHE_DIR", dir.path().c_str(), 1);
  {
    ClRuntime cl;  // fills the cache
    cl.kernel("layout_probe.cl", "layout_probe");
  }
  size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
    // Keep the header and key, replace the binary with garbage.
    std::ifstream in(entry.path(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    // magic (8), key length (8), binary length (8), key, binary
    uint64_t key_size = 0;
    std::memcpy(&key_size, bytes.data() + 8, 8);
    const std::string garbage = "not a program binary";
    const uint64_t garbage_size = garbage.size();
    bytes.resize(24 + key_size);
    std::memcpy(bytes.data() + 16, &garbage_size, 8);
    bytes += garbage;
    std::ofstream(entry.path(), std::ios::binary) << bytes;
  }
  EXPECT_EQ(entries, 1u);
  std::map<std::filesystem::path, uintmax_t> corrupt_size;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    corrupt_size[entry.path()] = entry.file_size();
  {
    ClRuntime cl;
    cl::Buffer out = cl.buffer(kProbeValues * sizeof(cl_uint), "probe");
    cl::Kernel k = cl.kernel("layout_probe.cl", "layout_probe");
    cl.launch("layout_probe", k, 1, 1, out);
    cl.finish();
  }
  for (const auto& [path, size] : corrupt_size)
    EXPECT_GT(std::filesystem::file_size(path), size) << "the entry was stored again";
  if (saved.empty())
    unsetenv("VOXR_CACHE_DIR");
  else
    setenv("VOXR_CACHE_DIR", saved.c_str(), 1);
}

// build_programs loads the programs not built yet on several threads: each distinct (file, defines) is
// built and stored once, duplicates and programs built before are not built again, and a failure on a worker
// thread reaches the caller.
TEST(ProgramCache, ProgramsBuiltTogetherAreBuiltOnceEach) {
  test::TempDir dir;
  const char* old = std::getenv("VOXR_CACHE_DIR");
  const std::string saved = old ? old : "";
  setenv("VOXR_CACHE_DIR", dir.path().c_str(), 1);
  const auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(dir.path()),
                         std::filesystem::directory_iterator());
  };
  {
    ClRuntime cl;
    cl.kernel("refract_none.cl", "identity_paths");
    EXPECT_EQ(entries(), 1);
    cl.build_programs({{"layout_probe.cl", {}},
                       {"refract_none.cl", {}},
                       {"layout_probe.cl", {{"VOXR_UNUSED", "1"}}},
                       {"layout_probe.cl", {}}});
    EXPECT_EQ(entries(), 3);
    const double built_ms = cl.build_ms();
    cl::Buffer out = cl.buffer(kProbeValues * sizeof(cl_uint), "probe");
    cl::Kernel k = cl.kernel("layout_probe.cl", "layout_probe", {{"VOXR_UNUSED", "1"}});
    cl.launch("layout_probe", k, 1, 1, out);
    cl.finish();
    EXPECT_EQ(cl.build_ms(), built_ms) << "a program build_programs built was built again";
    EXPECT_THROW(cl.build_programs({{"layout_probe.cl", {{"VOXR_UNUSED", "2"}}}, {"no_such_kernel.cl", {}}}),
                 InternalError);
  }
  if (saved.empty())
    unsetenv("VOXR_CACHE_DIR");
  else
    setenv("VOXR_CACHE_DIR", saved.c_str(), 1);
}

TEST(Profiler, KeepsABoundedWindowPerName) {
  ClRuntime& cl = test::runtime();
  cl::Buffer out = cl.buffer(kProbeValues * sizeof(cl_uint), "probe");
  cl::Kernel k = cl.kernel("layout_probe.cl", "layout_probe");
  const size_t launches = Profiler::kWindow + 100;
  const size_t before = cl.profiler().stats()["window probe"].count;
  for (size_t i = 0; i < launches; ++i) cl.launch("window probe", k, 1, 1, out);
  cl.finish();
  const Profiler::Stat s = cl.profiler().stats()["window probe"];
  EXPECT_EQ(s.count, before + launches);
  EXPECT_GT(s.total_ms, 0.0);
  EXPECT_GT(s.median_ms, 0.0);
  EXPECT_EQ(cl.profiler().window("window probe"), Profiler::kWindow);
}

}  // namespace
}  // namespace voxr
