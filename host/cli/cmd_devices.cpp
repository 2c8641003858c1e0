// voxr devices: every OpenCL platform and device with the index that --device / VOXR_DEVICE accept.
#include <fmt/format.h>

#include "cl/device.h"
#include "cli/commands.h"

namespace voxr::cli {

Command add_devices(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("devices", "List OpenCL platforms and devices (for --device P:D)");
  return {sub, [] {
            const std::vector<DeviceInfo> devices = list_devices();
            const DeviceInfo chosen = select_device("");
            fmt::print("{:<5} {:<4} {:<40} {:<32} {:>4} {:>10} {:>10}\n", "P:D", "type", "device", "platform",
                       "CUs", "memory", "max alloc");
            for (const DeviceInfo& d : devices) {
              const bool is_default =
                  d.platform_index == chosen.platform_index && d.device_index == chosen.device_index;
              fmt::print("{:<5} {:<4} {:<40} {:<32} {:>4} {:>7.2f} GiB {:>6.2f} GiB{}\n",
                         fmt::format("{}:{}", d.platform_index, d.device_index), d.type, d.name.substr(0, 40),
                         d.platform_name.substr(0, 32), d.compute_units, d.global_memory / double(1ull << 30),
                         d.max_allocation / double(1ull << 30), is_default ? "  (default)" : "");
            }
            return 0;
          }};
}

}  // namespace voxr::cli
