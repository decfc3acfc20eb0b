#pragma once
// Phase times of one Algorithm::run() call (AlgorithmOutput::phase_ms): a steady clock read
// around the algorithm's own phases, lap by lap.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// The two phases the report shows side by side (see Algorithm::timed_phases).
inline constexpr const char* build_phase = "build";
inline constexpr const char* query_phase = "query";

inline std::vector<std::string> build_and_query_phases() {
  return {build_phase, query_phase};
}

class PhaseClock {
 public:
  // Starts timing now; every named phase starts at 0 ms, so it is reported even when it takes no
  // lap (a shadow map with no sample to draw for).
  explicit PhaseClock(const std::vector<std::string>& phases = build_and_query_phases())
      : last_(Clock::now()) {
    for (const std::string& name : phases) times_.emplace_back(name, 0.0);
  }

  // Adds the time since the previous lap (or since construction or restart()) to phase `name`
  // (appended when it was not named: the runner then reports the undeclared phase) and starts
  // the next lap. A phase may take several laps (one per shadow-map face, say).
  void lap(const std::string& name) {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    for (auto& [phase, total] : times_)
      if (phase == name) {
        total += ms;
        return;
      }
    times_.emplace_back(name, ms);
  }

  // Starts the next lap without counting the time since the previous one in any phase.
  void restart() { last_ = Clock::now(); }

  const PhaseTimes& times() const { return times_; }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_;
  PhaseTimes times_;
};

}  // namespace shadowcts
