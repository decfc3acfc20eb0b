#include "machine_info.h"

#include <cstdint>
#include <fstream>
#include <thread>

#include <hwy/targets.h>

namespace shadowcts {

MachineInfo machine_info() {
  MachineInfo m;
  m.cpu = "unknown";
  m.hardware_threads = std::thread::hardware_concurrency();
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon != std::string::npos && colon + 2 <= line.size()) m.cpu = line.substr(colon + 2);
    break;
  }
  // HWY_DYNAMIC_DISPATCH calls the best of the targets that the CPU supports and that a
  // translation unit compiled with the default flags generates (HWY_TARGETS); a lower bit is a
  // better target.
  const std::int64_t targets = hwy::SupportedTargets() & HWY_TARGETS;
  for (std::int64_t rest = targets; rest != 0; rest &= rest - 1)
    m.isa_targets.push_back(hwy::TargetName(rest & -rest));
  m.isa = m.isa_targets.empty() ? hwy::TargetName(HWY_STATIC_TARGET) : m.isa_targets.front();
  return m;
}

}  // namespace shadowcts
