#include "cl/count_bits.h"

namespace voxr {

namespace {
constexpr size_t kGroup = 256;
constexpr uint64_t kWordsPerItem = 64;
}  // namespace

std::vector<ProgramSpec> count_bits_programs() {
  return {{"count_bits.cl",
           {{"WG_SIZE", std::to_string(kGroup)}, {"COUNT_WORDS", std::to_string(kWordsPerItem)}}}};
}

uint64_t count_bits(ClRuntime& cl, const cl::Buffer& words, uint64_t n, const std::string& name) {
  if (n == 0) return 0;
  if (cl.device().extensions.find("cl_khr_int64_base_atomics") == std::string::npos)
    fail("{} lacks cl_khr_int64_base_atomics, which counting the {} voxels needs", cl.device().label(), name);
  cl::Buffer total = cl.buffer(8, name + " total");
  cl.fill_zero(total, 8, "clear");
  const ProgramSpec spec = count_bits_programs().front();
  cl::Kernel kernel = cl.kernel(spec.file, "count_bits", spec.defines);
  cl.launch(name, kernel, (n + kWordsPerItem - 1) / kWordsPerItem, kGroup, words, cl_ulong(n), total);
  cl_ulong result = 0;
  cl.download(total, &result, 8, "readback " + name + " total");
  return result;
}

}  // namespace voxr
