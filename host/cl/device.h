// OpenCL platforms and devices: listing (`voxr devices`) and selection (--device P:D or VOXR_DEVICE).
#pragma once

#include <CL/opencl.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace voxr {

struct DeviceInfo {
  int platform_index = 0;
  int device_index = 0;
  std::string platform_name;
  std::string name;
  std::string type;  // "GPU", "CPU", "accelerator", "other"
  std::string driver_version;
  std::string opencl_version;
  std::string extensions;
  uint32_t compute_units = 0;
  uint64_t global_memory = 0;
  uint64_t max_allocation = 0;
  bool correctly_rounded_sqrt = false;  // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT
  bool host_memory = false;             // a CPU device: its buffers live in host memory
  uint64_t base_alignment = 0;          // CL_DEVICE_MEM_BASE_ADDR_ALIGN, in bytes
  cl::Device device;

  std::string label() const;  // "P:D name (platform)"
};

// Every device of every platform. Throws voxr::Error explaining how to install PoCL when there is no
// OpenCL platform at all.
std::vector<DeviceInfo> list_devices();

// Selector "P:D", "P", or a name substring; each of P and D is an index or a case-insensitive substring
// of the platform/device name. Empty: $VOXR_DEVICE if set, else the first GPU, else the first CPU.
DeviceInfo select_device(const std::string& selector);

}  // namespace voxr
