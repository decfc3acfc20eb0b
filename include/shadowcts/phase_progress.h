#pragma once
// How far the current long phase is: the G-buffer pass, an oracle, an algorithm that reports.
// Phases add the work they finish from any thread (lock-free); the runner shows it as a progress
// line with an ETA on a terminal and as a plain line at least once a minute otherwise. Process-wide
// because the phases run deep inside libraries that know nothing of the runner.
#include <cstdint>

namespace shadowcts::phase_progress {

// A phase starts: `total` units of work (0: unknown, only the elapsed time is shown).
void begin(std::uint64_t total);
// `units` more are done.
void advance(std::uint64_t units);

struct Snapshot {
  std::uint64_t done = 0, total = 0;
  std::uint64_t generation = 0;  // changes with every begin()
};
Snapshot snapshot();

}  // namespace shadowcts::phase_progress
