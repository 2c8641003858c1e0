#include "cl/device.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

#include "cl/cl_error.h"
#include "util/error.h"

namespace voxr {

namespace {

constexpr const char* kInstallHint =
    "no OpenCL platform found; install one, e.g. PoCL for the CPU: apt-get install pocl-opencl-icd "
    "ocl-icd-libopencl1 (or scripts/install-deps.sh), or a GPU vendor's OpenCL driver";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool matches(const std::string& part, int index, const std::string& name) {
  if (part.empty()) return true;
  if (is_index(part)) {
    int value = -1;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    return error == std::errc() && end == part.data() + part.size() && value == index;
  }
  return lower(name).find(lower(part)) != std::string::npos;
}

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_GPU) return "GPU";
  if (t & CL_DEVICE_TYPE_CPU) return "CPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

}  // namespace

std::string DeviceInfo::label() const {
  return fmt::format("{}:{} {} ({})", platform_index, device_index, name, platform_name);
}

std::vector<DeviceInfo> list_devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    if (e.err() == CL_PLATFORM_NOT_FOUND_KHR || e.err() == CL_INVALID_PLATFORM) throw Error(kInstallHint);
    throw Error(describe_cl_error(e, "listing OpenCL platforms"));
  }
  if (platforms.empty()) throw Error(kInstallHint);
  std::vector<DeviceInfo> out;
  for (size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices (e.g. a GPU driver with no GPU present)
    }
    for (size_t d = 0; d < devices.size(); ++d) {
      DeviceInfo info;
      info.platform_index = int(p);
      info.device_index = int(d);
      info.platform_name = platforms[p].getInfo<CL_PLATFORM_NAME>();
      info.name = devices[d].getInfo<CL_DEVICE_NAME>();
      info.type = type_name(devices[d].getInfo<CL_DEVICE_TYPE>());
      info.driver_version = devices[d].getInfo<CL_DRIVER_VERSION>();
      info.opencl_version = devices[d].getInfo<CL_DEVICE_VERSION>();
      info.extensions = devices[d].getInfo<CL_DEVICE_EXTENSIONS>();
      info.compute_units = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.global_memory = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.max_allocation = devices[d].getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      info.correctly_rounded_sqrt =
          (devices[d].getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
      // A CPU device works on host memory: buffers over suitably aligned host arrays need no copy.
      info.host_memory = devices[d].getInfo<CL_DEVICE_TYPE>() == CL_DEVICE_TYPE_CPU;
      info.base_alignment = devices[d].getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / 8;
      info.device = devices[d];
      out.push_back(std::move(info));
    }
  }
  if (out.empty()) throw Error(kInstallHint);
  return out;
}

DeviceInfo select_device(const std::string& selector_arg) {
  std::string selector = selector_arg;
  if (selector.empty())
    if (const char* env = std::getenv("VOXR_DEVICE")) selector = env;
  const std::vector<DeviceInfo> devices = list_devices();
  if (selector.empty()) {
    for (const char* type : {"GPU", "CPU"})
      for (const DeviceInfo& d : devices)
        if (d.type == type) return d;
    return devices.front();
  }
  const size_t colon = selector.find(':');
  const std::string platform_part = colon == std::string::npos ? selector : selector.substr(0, colon);
  const std::string device_part = colon == std::string::npos ? "" : selector.substr(colon + 1);
  for (const DeviceInfo& d : devices) {
    if (colon == std::string::npos && !is_index(selector)) {
      // A bare name matches either the platform or the device.
      if (matches(selector, -1, d.platform_name) || matches(selector, -1, d.name)) return d;
    } else if (matches(platform_part, d.platform_index, d.platform_name) &&
               matches(device_part, d.device_index, d.name)) {
      return d;
    }
  }
  // One line naming where the selector came from (errors are one line: see host/cli/main.cpp).
  std::string known;
  for (const DeviceInfo& d : devices) known += (known.empty() ? "" : "; ") + d.label();
  fail("{} '{}': no OpenCL device matches (devices: {})", selector_arg.empty() ? "VOXR_DEVICE" : "--device",
       selector, known);
}

}  // namespace voxr
