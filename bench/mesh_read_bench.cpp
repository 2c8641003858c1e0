// Reading a large mesh in each format voxr reads itself: bunnyx16 (1.1 M triangles, midpoint subdivision of
// the packaged bunny) written once per format to a temporary folder — ASCII OFF (%.9g, 42 MB), OBJ
// (%.9g), binary little-endian PLY (float xyz, uchar/int lists) and binary STL — then load_mesh timed
// (wall clock, page cache warm after the first iteration): the parse, the triangulation and the
// validation, what a fresh `voxr voxelize` pays before any kernel runs. The file size is a counter.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include "bench/bench_meshes.h"
#include "core/mesh_loader.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0)
    fail("{}: cannot write the benchmark mesh", path.string());
}

// World positions (anchor + position), as the files voxr was given hold them.
glm::dvec3 world(const TriangleSoup& s, const glm::vec4& p) {
  return s.anchor + glm::dvec3(glm::vec3(p));
}

std::string as_off(const TriangleSoup& s) {
  std::string t = fmt::format("OFF\n{} {} 0\n", s.positions.size(), s.triangles.size());
  for (const glm::vec4& p : s.positions) {
    const glm::vec3 w(world(s, p));
    fmt::format_to(std::back_inserter(t), "{:.9g} {:.9g} {:.9g}\n", w.x, w.y, w.z);
  }
  for (const glm::uvec4& f : s.triangles)
    fmt::format_to(std::back_inserter(t), "3 {} {} {}\n", f.x, f.y, f.z);
  return t;
}

std::string as_obj(const TriangleSoup& s) {
  std::string t;
  for (const glm::vec4& p : s.positions) {
    const glm::vec3 w(world(s, p));
    fmt::format_to(std::back_inserter(t), "v {:.9g} {:.9g} {:.9g}\n", w.x, w.y, w.z);
  }
  for (const glm::uvec4& f : s.triangles)
    fmt::format_to(std::back_inserter(t), "f {} {} {}\n", f.x + 1, f.y + 1, f.z + 1);
  return t;
}

std::string as_ply(const TriangleSoup& s) {
  std::string t = fmt::format(
      "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
      "property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      s.positions.size(), s.triangles.size());
  for (const glm::vec4& p : s.positions) {
    const glm::vec3 w(world(s, p));
    t.append(reinterpret_cast<const char*>(&w), 12);
  }
  for (const glm::uvec4& f : s.triangles) {
    t.push_back(3);
    t.append(reinterpret_cast<const char*>(&f), 12);
  }
  return t;
}

std::string as_stl(const TriangleSoup& s) {
  std::string t(80, ' ');
  const uint32_t n = uint32_t(s.triangles.size());
  t.append(reinterpret_cast<const char*>(&n), 4);
  const float normal[3] = {0, 0, 0};
  for (const glm::uvec4& f : s.triangles) {
    t.append(reinterpret_cast<const char*>(normal), 12);
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 w(world(s, s.positions[f[c]]));
      t.append(reinterpret_cast<const char*>(&w), 12);
    }
    t.append(2, '\0');
  }
  return t;
}

// The file for `format`, written on first use; removed at exit.
const fs::path& mesh_file(const std::string& format) {
  static const fs::path dir = fs::temp_directory_path() / ("voxr-mesh-read-" + std::to_string(getpid()));
  static struct Cleanup {
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup;
  static std::map<std::string, fs::path> files;
  auto it = files.find(format);
  if (it != files.end()) return it->second;
  static const BenchMesh mesh = make_bench_mesh("bunnyx16");
  fs::create_directories(dir);
  const fs::path path = dir / ("bunnyx16." + format);
  write_bytes(path, format == "off"   ? as_off(mesh.soup)
                    : format == "obj" ? as_obj(mesh.soup)
                    : format == "ply" ? as_ply(mesh.soup)
                                      : as_stl(mesh.soup));
  return files.emplace(format, path).first->second;
}

void read_mesh(benchmark::State& state, const std::string& format) {
  fs::path path;
  try {
    path = mesh_file(format);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
    return;
  }
  size_t triangles = 0;
  for (auto _ : state) {
    const TriangleSoup soup = load_mesh(path);
    triangles = soup.triangles.size();
    benchmark::DoNotOptimize(soup.positions.data());
  }
  state.counters["MB"] = double(fs::file_size(path)) / 1e6;
  state.counters["triangles"] = double(triangles);
}

BENCHMARK_CAPTURE(read_mesh, off, std::string("off"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(read_mesh, obj, std::string("obj"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(read_mesh, ply, std::string("ply"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(read_mesh, stl, std::string("stl"))->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace voxr
