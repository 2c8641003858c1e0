#include "cl/cl_runtime.h"

#include <atomic>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "cl/embedded_kernels.h"
#include "util/clock.h"

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
    // Kernels are named by file name alone: search the stage folders for it.
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
      if (it->path().filename() != file) continue;
      std::ifstream in(it->path());
      if (!in) fail("VOXR_KERNEL_DIR: cannot read kernel source {}", it->path().string());
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    }
    fail("VOXR_KERNEL_DIR: no kernel source named {} under {}", file, dir);
  }
  if (const EmbeddedKernel* k = find_embedded_kernel(file)) return std::string(k->source);
  throw InternalError("no embedded kernel source named " + file);
}

namespace {

// The key of a built program in ClRuntime::programs_: its file and build options.
std::string program_key(const std::string& file, const std::string& options) {
  return file + "|" + options;
}

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

cl::Program ClRuntime::build_from_source(const std::string& file, const std::string& source,
                                         const std::string& options) const {
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
  return program;
}

std::string ClRuntime::build_options(const Defines& defines) const {
  std::string options = "-cl-std=CL1.2";
  if (device_.correctly_rounded_sqrt) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  for (const auto& [key, value] : defines) options += " -D" + key + "=" + value;
  return options;
}

cl::Program ClRuntime::load_program(const std::string& file, const std::string& options) const {
  std::set<std::string> seen;
  const std::string source = expand_includes(
      load_source(file), [this](const std::string& f) { return load_source(f); }, seen);
  const std::string cache_key = fmt::format("{}\n{}\n{}\n{}\n{}", device_.platform_name, device_.name,
                                            device_.driver_version, options, source);
  if (const auto binary = program_cache_.load(cache_key)) {
    try {
      cl::Program from_binary(context_, {device_.device}, cl::Program::Binaries{*binary});
      from_binary.build({device_.device}, options.c_str());
      return from_binary;
    } catch (const cl::Error&) {
      // A stale or corrupt entry: build from source below and store a fresh one.
    }
  }
  cl::Program program = build_from_source(file, source, options);
  try {
    const std::vector<std::vector<unsigned char>> binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    if (binaries.size() == 1) program_cache_.store(cache_key, binaries[0]);
  } catch (const cl::Error&) {
    // Drivers that cannot return binaries simply build from source every time.
  }
  return program;
}

cl::Program& ClRuntime::program(const std::string& file, const Defines& defines) {
  const std::string options = build_options(defines);
  const std::string memo_key = program_key(file, options);
  if (auto it = programs_.find(memo_key); it != programs_.end()) return it->second;
  const auto start = Clock::now();
  cl::Program program = load_program(file, options);
  build_ms_ += ms_since(start);
  return programs_.emplace(memo_key, std::move(program)).first->second;
}

void ClRuntime::build_programs(const std::vector<ProgramSpec>& specs) {
  // The programs not built yet, loaded on a few threads: most of a fresh process's program time is the
  // driver reading each stored binary (PoCL parses its LLVM bitcode), which runs in parallel.
  std::vector<std::pair<std::string, std::string>> todo;  // file, options
  std::set<std::string> queued;
  for (const ProgramSpec& spec : specs) {
    std::string options = build_options(spec.defines);
    const std::string memo_key = program_key(spec.file, options);
    if (programs_.count(memo_key) == 0 && queued.insert(memo_key).second)
      todo.emplace_back(spec.file, std::move(options));
  }
  if (todo.empty()) return;
  const auto start = Clock::now();
  std::vector<std::optional<cl::Program>> built(todo.size());
  std::vector<std::exception_ptr> errors(todo.size());
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t i = next++; i < todo.size(); i = next++) {
      try {
        built[i] = load_program(todo[i].first, todo[i].second);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  {
    std::vector<std::jthread> threads;
    const size_t count = std::min<size_t>(todo.size(), std::max(1u, std::thread::hardware_concurrency())) - 1;
    for (size_t t = 0; t < count; ++t) threads.emplace_back(work);
    work();
  }
  for (size_t i = 0; i < todo.size(); ++i) {
    if (errors[i]) std::rethrow_exception(errors[i]);
    programs_.emplace(program_key(todo[i].first, todo[i].second), std::move(*built[i]));
  }
  build_ms_ += ms_since(start);
}

cl::Kernel ClRuntime::kernel(const std::string& file, const std::string& name, const Defines& defines) {
  cl::Program& built = program(file, defines);
  try {
    return cl::Kernel(built, name.c_str());
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
  --syncs_;  // a Debug build's launch check, not one of the program's own synchronisations (syncs())
#endif
}

void ClRuntime::check_allocation(uint64_t bytes, const std::string& what) const {
  if (bytes > device_.max_allocation)
    fail(
        "{} needs {:.1f} MiB but the largest buffer {} allows is {:.1f} MiB; use a smaller grid (--res) or "
        "fewer channels",
        what, double(bytes) / (1 << 20), device_.name, double(device_.max_allocation) / (1 << 20));
}

cl::Buffer ClRuntime::buffer(uint64_t bytes, const std::string& what, cl_mem_flags flags) {
  bytes = std::max<uint64_t>(bytes, 4);
  check_allocation(bytes, what);
  try {
    return cl::Buffer(context_, flags, bytes);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, "allocating " + what));
  }
}

bool ClRuntime::can_use_in_place(const void* data) const {
  return device_.host_memory && device_.base_alignment > 0 &&
         reinterpret_cast<uintptr_t>(data) % device_.base_alignment == 0;
}

cl::Buffer ClRuntime::in_place_buffer(void* data, uint64_t bytes, const std::string& what) {
  VOXR_CHECK(can_use_in_place(data) && bytes > 0);
  try {
    return cl::Buffer(context_, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes, data);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, "allocating " + what));
  }
}

void ClRuntime::sync_to_host(cl::Buffer& buffer, uint64_t bytes, const std::string& name) {
  const auto start = Clock::now();
  const double cpu_start = thread_cpu_ms();
  ++syncs_;
  try {
    void* mapped = queue_.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
    queue_.enqueueUnmapMemObject(buffer, mapped);
    queue_.finish();
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
  sync_ms_ += ms_since(start);
  sync_cpu_ms_ += thread_cpu_ms() - cpu_start;
}

bool ClRuntime::host_buffer(cl::Buffer& buffer, const void* data, uint64_t bytes, const std::string& what,
                            const std::string& name) {
  if (can_use_in_place(data) && bytes > 0) {
    try {
      buffer = cl::Buffer(context_, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, const_cast<void*>(data));
      return true;
    } catch (const cl::Error& e) {
      throw Error(describe_cl_error(e, "allocating " + what));
    }
  }
  buffer = this->buffer(bytes, what, CL_MEM_READ_ONLY);
  upload(buffer, data, bytes, name);
  return false;
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
  const auto start = Clock::now();
  const double cpu_start = thread_cpu_ms();
  ++syncs_;
  try {
    cl::Event event;
    queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, bytes, data, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
  sync_ms_ += ms_since(start);
  sync_cpu_ms_ += thread_cpu_ms() - cpu_start;
}

void ClRuntime::download(const cl::Buffer& buffer, void* data, uint64_t bytes, const std::string& name,
                         uint64_t offset) {
  if (bytes == 0) return;
  const auto start = Clock::now();
  const double cpu_start = thread_cpu_ms();
  ++syncs_;
  try {
    cl::Event event;
    queue_.enqueueReadBuffer(buffer, CL_TRUE, offset, bytes, data, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
  sync_ms_ += ms_since(start);
  sync_cpu_ms_ += thread_cpu_ms() - cpu_start;
}

void ClRuntime::download_later(const cl::Buffer& buffer, void* data, uint64_t bytes, const std::string& name,
                               uint64_t offset) {
  if (bytes == 0) return;
  try {
    cl::Event event;
    queue_.enqueueReadBuffer(buffer, CL_FALSE, offset, bytes, data, nullptr, &event);
    profiler_.record(name, event);
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, name));
  }
}

double ClRuntime::thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

void ClRuntime::finish(const std::string& context) {
  const auto start = Clock::now();
  const double cpu_start = thread_cpu_ms();
  ++syncs_;
  try {
    queue_.finish();
    profiler_.resolve();
  } catch (const cl::Error& e) {
    throw Error(describe_cl_error(e, context));
  }
  sync_ms_ += ms_since(start);
  sync_cpu_ms_ += thread_cpu_ms() - cpu_start;
}

void ClRuntime::read_count_later(const cl::Buffer& buffer, uint32_t bytes, const std::string& name,
                                 std::function<bool(uint64_t)> check) {
  VOXR_CHECK(bytes == 4 || bytes == 8);
  auto pending = std::make_unique<PendingCount>();
  pending->check = std::move(check);
  download_later(buffer, &pending->value, bytes, name);
  pending_counts_.push_back(std::move(pending));
}

bool ClRuntime::settle_counts() {
  const std::vector<std::unique_ptr<PendingCount>> pending = std::move(pending_counts_);
  pending_counts_.clear();
  bool fits = true;
  for (const std::unique_ptr<PendingCount>& p : pending) fits = p->check(p->value) && fits;
  return fits;
}

void ClRuntime::discard_counts() {
  if (pending_counts_.empty()) return;
  try {
    queue_.finish();
  } catch (...) {
    // already failing; the queue's error was or will be reported
  }
  pending_counts_.clear();
}

}  // namespace voxr
