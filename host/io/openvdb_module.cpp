#include "io/openvdb_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

fs::path openvdb_module_path() {
  if (const char* env = std::getenv("VOXR_OPENVDB_PLUGIN")) return fs::path(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path() / "libvoxr_openvdb_peer.so";
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
