#include "machine_info.h"

#include <fstream>
#include <thread>

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
  return m;
}

}  // namespace shadowcts
