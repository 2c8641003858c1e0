#include "cl/cl_runtime.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "cl/embedded_kernels.h"

namespace voxr {

ClRuntime::ClRuntime(const std::string& device_selector) : ClRuntime(select_device(device_selector)) {}

ClRuntime::ClRuntime(const DeviceInfo& device) : device_(device) {
  try {
    context_ = cl::Context(device_.device);
    queue_ = cl::CommandQueue(context_, device_.device, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, "opening device " + device_.label()));
  }
}

std::string ClRuntime::load_source(const std::string& file) const {
  if (const char* dir = std::getenv("VOXR_KERNEL_DIR"); dir && *dir) {
    const std::string path = std::string(dir) + "/" + file;
    std::ifstream in(path);
    if (!in) fail("VOXR_KERNEL_DIR: cannot read kernel source {}", path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  for (const EmbeddedKernel& k : embedded_kernels())
    if (k.name == file) return std::string(k.source);
  throw InternalError("no embedded kernel source named " + file);
}

namespace {

// Inlines `#include "x.h"` lines (each file once), so embedded sources need no include path.
std::string expand_includes(const std::string& source,
                            const std::function<std::string(const std::string&)>& load,
                            std::set<std::string>& seen) {
  std::istringstream in(source);
  std::string line, out;
  while (std::getline(in, line)) {
    const size_t pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      const size_t start = pos + 10;
      const std::string name = line.substr(start, line.find('"', start) - start);
      if (seen.insert(name).second) out += expand_includes(load(name), load, seen);
      continue;
    }
    out += line + "\n";
  }
  return out;
}

}  // namespace

cl::Kernel ClRuntime::kernel(const std::string& file, const std::string& name, const Defines& defines) {
  std::string options = "-cl-std=CL1.2";
  if (device_.correctly_rounded_sqrt) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  for (const auto& [key, value] : defines) options += " -D" + key + "=" + value;
  const std::string cache_key = file + "|" + options;
  auto it = programs_.find(cache_key);
  if (it == programs_.end()) {
    std::set<std::string> seen;
    const std::string source = expand_includes(
        load_source(file), [this](const std::string& f) { return load_source(f); }, seen);
    cl::Program program(context_, source);
    try {
      program.build({device_.device}, options.c_str());
    } catch (const cl::Error& e) {
      std::string log;
      try {
        log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_.device);
      } catch (const cl::Error&) {
        log = "(no build log)";
      }
      fail("building kernel file {} with options '{}' failed: {} ({})\n{}", file, options,
           cl_status_name(e.err()), e.err(), log);
    }
    it = programs_.emplace(cache_key, std::move(program)).first;
  }
  try {
    return cl::Kernel(it->second, name.c_str());
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, "creating kernel " + name + " from " + file));
  }
}

void ClRuntime::enqueue(const std::string& name, cl::Kernel& kernel, size_t global, size_t local) {
  const size_t rounded = (global + local - 1) / local * local;
  cl::Event event;
  queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(rounded), cl::NDRange(local), nullptr,
                              &event);
  profiler_.record(name, event);
#ifndef NDEBUG
  finish("running kernel " + name);
#endif
}

cl::Buffer ClRuntime::buffer(uint64_t bytes, const std::string& what, cl_mem_flags flags) {
  bytes = std::max<uint64_t>(bytes, 4);
  if (bytes > device_.max_allocation)
    fail(
        "{} needs {:.1f} MiB but the largest buffer {} allows is {:.1f} MiB; use a smaller grid (--res) or "
        "fewer channels",
        what, double(bytes) / (1 << 20), device_.name, double(device_.max_allocation) / (1 << 20));
  try {
    return cl::Buffer(context_, flags, bytes);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, "allocating " + what));
  }
}

void ClRuntime::fill_zero(cl::Buffer& buffer, uint64_t bytes, const std::string& name) {
  if (bytes == 0) return;
  try {
    cl::Event event;
    queue_.enqueueFillBuffer(buffer, cl_uint(0), 0, (bytes + 3) / 4 * 4, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
}

void ClRuntime::upload(cl::Buffer& buffer, const void* data, uint64_t bytes, const std::string& name) {
  if (bytes == 0) return;
  try {
    cl::Event event;
    queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, bytes, data, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
}

void ClRuntime::download(const cl::Buffer& buffer, void* data, uint64_t bytes, const std::string& name,
                         uint64_t offset) {
  if (bytes == 0) return;
  try {
    cl::Event event;
    queue_.enqueueReadBuffer(buffer, CL_TRUE, offset, bytes, data, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
}

void ClRuntime::finish(const std::string& context) {
  try {
    queue_.finish();
    profiler_.resolve();
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, context));
  }
}

}  // namespace voxr
