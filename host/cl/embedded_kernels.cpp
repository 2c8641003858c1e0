#include "cl/embedded_kernels.h"

namespace voxr {

namespace {

// Function-local, so registration from another translation unit's static initializer finds it constructed.
std::vector<const std::vector<EmbeddedKernel>& (*)()>& registered_tables() {
  static std::vector<const std::vector<EmbeddedKernel>& (*)()> tables;
  return tables;
}

}  // namespace

bool register_embedded_kernels(const std::vector<EmbeddedKernel>& (*table)()) {
  registered_tables().push_back(table);
  return true;
}

const EmbeddedKernel* find_embedded_kernel(std::string_view name) {
  for (const EmbeddedKernel& k : embedded_kernels())
    if (k.name == name) return &k;
  for (const auto table : registered_tables())
    for (const EmbeddedKernel& k : table())
      if (k.name == name) return &k;
  return nullptr;
}

}  // namespace voxr
