#include "io/openvdb_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <vector>

#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

fs::path openvdb_module_path() {
  if (const char* env = std::getenv("VOXR_OPENVDB_PLUGIN")) return fs::path(env);
  constexpr const char* kName = "libvoxr_openvdb_peer.so";
  // Beside the executable (the build tree, an installed bin/); else beside the library this code is linked
  // into when that is not the executable: libvoxr.so in lib/ (the plugin in ../bin) or in the Python package
  // (the plugin in bin/ beside it).
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path() / kName);
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&openvdb_module_path), &info) && info.dli_fname) {
    const fs::path lib = fs::absolute(info.dli_fname, ec).parent_path();
    for (const fs::path& dir : {lib, lib / "bin", lib.parent_path() / "bin"})
      candidates.push_back(dir / kName);
  }
  for (const fs::path& c : candidates)
    if (fs::is_regular_file(c, ec)) return c;
  return candidates.empty() ? fs::path() : candidates.front();
}

bool openvdb_module_available() {
  const fs::path plugin = openvdb_module_path();
  std::error_code ec;
  return !plugin.empty() && fs::is_regular_file(plugin, ec);
}

void* openvdb_module_symbol(const char* name) {
  static std::mutex mutex;
  static void* handle = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  const fs::path plugin = openvdb_module_path();
  if (!handle) {
    if (!openvdb_module_available())
      fail(
          "{}: the OpenVDB plugin is not there (install libopenvdb-dev, configure with VOXR_WITH_OPENVDB=ON, "
          "rebuild)",
          plugin.empty() ? std::string("libvoxr_openvdb_peer.so") : plugin.string());
    handle = dlopen(plugin.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) fail("{}: cannot load the OpenVDB plugin: {}", plugin.string(), dlerror());
  }
  void* symbol = dlsym(handle, name);
  if (!symbol) fail("{}: no {} in the OpenVDB plugin", plugin.string(), name);
  return symbol;
}

}  // namespace voxr
