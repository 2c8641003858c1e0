// The one place that talks to raw OpenCL: a context and profiling queue on one device, programs built
// from the embedded kernel sources (or $VOXR_KERNEL_DIR) with generated defines, named and profiled
// launches, and checked buffers. Every OpenCL object is held by the C++ wrapper's RAII handles.
#pragma once

#include <CL/opencl.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cl/cl_error.h"
#include "cl/defines.h"
#include "cl/device.h"
#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "util/error.h"

namespace voxr {

// One program: a kernel file and the defines it is built with.
struct ProgramSpec {
  std::string file;
  Defines defines;
};

class ClRuntime {
 public:
  explicit ClRuntime(const std::string& device_selector = "");
  explicit ClRuntime(const DeviceInfo& device);

  const DeviceInfo& device() const { return device_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  Profiler& profiler() { return profiler_; }

  // Kernel `name` from kernel file `file` (e.g. "vox_raster.cl") built with `defines`. Programs are built
  // once per (file, defines) and process, from the on-disk ProgramCache when it holds them; a failed build
  // throws voxr::Error with the full build log.
  cl::Kernel kernel(const std::string& file, const std::string& name, const Defines& defines = {});
  // Builds (or loads) the programs now, so that a timed run that follows pays nothing for them: those not
  // built yet, on up to one thread per core (OpenCL builds are thread-safe; PoCL's reading of a stored
  // binary is most of a fresh process's program time). The first failure is rethrown.
  void build_programs(const std::vector<ProgramSpec>& specs);
  // Milliseconds spent building or loading programs so far.
  double build_ms() const { return build_ms_; }

  // Sets the arguments in order and enqueues `global` work items (rounded up to `local`), recording the
  // event under `name`. Debug builds finish the queue and check the status after every launch. An
  // argument with a member set_kernel_args(cl::Kernel&, cl_uint& index) sets several consecutive
  // parameters (e.g. DeviceVoxelGrid::view_args() for VOXR_GRID_VIEW_PARAMS).
  template <typename... Args>
  void launch(const std::string& name, cl::Kernel& kernel, size_t global, size_t local, const Args&... args) {
    if (global == 0) return;
    try {
      cl_uint index = 0;
      (set_arg(kernel, index, args), ...);
      enqueue(name, kernel, global, local);
    } catch (const cl::Error& e) {
      throw Error(describe_cl_error(e, "launching kernel " + name));
    }
  }

  // A device buffer of `bytes` (at least 1). Throws voxr::Error naming `what` when it exceeds the
  // device's largest allocation.
  cl::Buffer buffer(uint64_t bytes, const std::string& what, cl_mem_flags flags = CL_MEM_READ_WRITE);
  // Throws the error buffer() would throw for `bytes`, without allocating.
  void check_allocation(uint64_t bytes, const std::string& what) const;
  // A read-only buffer over `bytes` of host memory at `data`: on a CPU device whose alignment `data` meets,
  // the device reads the host memory in place (no copy; `data` must then stay alive and unchanged while the
  // buffer is used); otherwise an upload named `name`. Returns whether it is in place.
  bool host_buffer(cl::Buffer& buffer, const void* data, uint64_t bytes, const std::string& what,
                   const std::string& name);
  // Whether host memory at `data` can back a buffer in place (a CPU device, aligned memory).
  bool can_use_in_place(const void* data) const;
  // A read-write buffer that uses `bytes` of host memory at `data` in place (can_use_in_place must hold).
  cl::Buffer in_place_buffer(void* data, uint64_t bytes, const std::string& what);
  // Makes the kernels' writes to an in-place buffer visible in its host memory (a map and unmap).
  void sync_to_host(cl::Buffer& buffer, uint64_t bytes, const std::string& name);
  void fill_zero(cl::Buffer& buffer, uint64_t bytes, const std::string& name);
  void upload(cl::Buffer& buffer, const void* data, uint64_t bytes, const std::string& name);
  void download(const cl::Buffer& buffer, void* data, uint64_t bytes, const std::string& name,
                uint64_t offset = 0);
  // Enqueues a read into `data` without waiting: `data` must stay alive and untouched until the next
  // synchronisation (finish or a blocking transfer), after which it holds the bytes. Lets several small
  // counts travel back with one wait.
  void download_later(const cl::Buffer& buffer, void* data, uint64_t bytes, const std::string& name,
                      uint64_t offset = 0);
  // Waits for the queue, turns asynchronous failures into voxr::Error, resolves profiling events.
  void finish(const std::string& context = "running kernels");

  // Counts read back together (issue 18: a frame reads its small counts with its last wait, not one wait
  // each). While counts are deferred (set_counts_deferred(true): the frame renderer's frames), a stage whose
  // launches depend on a count it produced on the device runs them over a capacity it kept from the run
  // before (work items past the true count, read from the device, do nothing) and hands the count to
  // read_count_later: the `bytes` (4 or 8) at `buffer` travel with the next wait, and settle_counts(),
  // called after that wait, passes each to its `check`. A check grows a capacity the count exceeded and
  // returns false: the work that ran over it must be redone. A stage whose capacity is not known yet (its
  // first run) reads its count at once.
  void set_counts_deferred(bool deferred) { counts_deferred_ = deferred; }
  bool counts_deferred() const { return counts_deferred_; }
  void read_count_later(const cl::Buffer& buffer, uint32_t bytes, const std::string& name,
                        std::function<bool(uint64_t)> check);
  // Runs the checks of the counts read so far (after a wait) and forgets them; false when any count
  // exceeded its capacity. A check that throws (a count that must be 0 is not) throws from here.
  bool settle_counts();
  // The capacity a check grows to for a count of `count`: a quarter more, and slack for small counts.
  static uint64_t with_headroom(uint64_t count) { return count + count / 4 + 1024; }
  // Forgets the counts read so far without checking them (after a failure), once the queue is done with
  // their host memory.
  void discard_counts();

  // Host synchronisations so far: every finish, blocking upload or download and map (each waits for the
  // queue), and the milliseconds the host spent blocked in them. A frame's count is the difference.
  // Debug builds' per-launch checks are not counted.
  uint64_t syncs() const { return syncs_; }
  double sync_ms() const { return sync_ms_; }
  // CPU time of the calling thread inside those waits (thread_cpu_ms's clock).
  double sync_cpu_ms() const { return sync_cpu_ms_; }
  // CPU time the calling thread has used, in milliseconds: host work measured apart from the device's
  // threads, which share the cores on a CPU device.
  static double thread_cpu_ms();

 private:
  template <typename T>
  static void set_arg(cl::Kernel& kernel, cl_uint& index, const T& arg) {
    if constexpr (requires { arg.set_kernel_args(kernel, index); })
      arg.set_kernel_args(kernel, index);
    else
      kernel.setArg(index++, arg);
  }
  void enqueue(const std::string& name, cl::Kernel& kernel, size_t global, size_t local);
  std::string load_source(const std::string& file) const;
  cl::Program& program(const std::string& file, const Defines& defines);
  std::string build_options(const Defines& defines) const;
  // Builds `file` with `options`, from the ProgramCache when it holds it (then stores it); safe to call
  // from several threads at once (build_programs).
  cl::Program load_program(const std::string& file, const std::string& options) const;
  cl::Program build_from_source(const std::string& file, const std::string& source,
                                const std::string& options) const;

  DeviceInfo device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  Profiler profiler_;
  std::map<std::string, cl::Program> programs_;  // by file and build options
  ProgramCache program_cache_;
  double build_ms_ = 0.0;
  struct PendingCount {
    uint64_t value = 0;  // a 4-byte count lands in the low half (little-endian host and device)
    std::function<bool(uint64_t)> check;
  };
  bool counts_deferred_ = false;
  std::vector<std::unique_ptr<PendingCount>> pending_counts_;  // stable addresses for the reads in flight
  uint64_t syncs_ = 0;
  double sync_ms_ = 0.0;
  double sync_cpu_ms_ = 0.0;
};

}  // namespace voxr
