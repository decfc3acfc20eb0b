#pragma once
// What the timings were measured on, recorded with every run.
#include <string>

namespace shadowcts {

struct MachineInfo {
  std::string cpu;                // model name, e.g. from /proc/cpuinfo; "unknown" if unreadable
  unsigned hardware_threads = 0;  // std::thread::hardware_concurrency()
};

MachineInfo machine_info();

}  // namespace shadowcts
