#pragma once
// What the timings were measured on, recorded with every run.
#include <string>
#include <vector>

namespace shadowcts {

struct MachineInfo {
  std::string cpu;                // model name, e.g. from /proc/cpuinfo; "unknown" if unreadable
  unsigned hardware_threads = 0;  // std::thread::hardware_concurrency()
  // The instruction set Highway's dynamic dispatch picks on this CPU (hwy::TargetName of the best
  // target that this CPU supports and this build compiles, e.g. "AVX2"), and every such target,
  // best first. Never empty: Highway always has a scalar or emulated target.
  std::string isa;
  std::vector<std::string> isa_targets;
};

MachineInfo machine_info();

}  // namespace shadowcts
