#pragma once
// How far the current long phase is: the G-buffer pass, an oracle, an algorithm's per-sample or
// per-triangle work, an emulated kernel launch. Phases add the work they finish from any thread
// (lock-free); the runner shows it as a progress line with an ETA on a terminal and as a plain
// line at least once a minute otherwise. Process-wide because the phases run deep inside libraries
// that know nothing of the runner.
#include <cstdint>

namespace shadowcts::phase_progress {

// A phase starts: `total` units of work (0: unknown, only the elapsed time is shown). `unit` names
// what is counted ("samples", "triangles", "blocks") and `of` what, if anything ("the kernel
// traverse"): both string literals (or other static storage), shown after the counts. One unit
// per begin(): every advance() until the next begin() counts the same thing.
void begin(std::uint64_t total, const char* unit = "", const char* of = "");
// `units` more are done. Call it per chunk of work (a TBB range, a block), not per item.
void advance(std::uint64_t units);

struct Snapshot {
  std::uint64_t done = 0, total = 0;
  std::uint64_t generation = 0;  // changes with every begin()
  const char* unit = "";
  const char* of = "";
};
Snapshot snapshot();

// Counts units on one thread and passes them on in chunks of `every` (and the rest when it goes
// out of scope): for sequential loops, so that one unit is not one atomic.
class Batch {
 public:
  explicit Batch(std::uint64_t every = 256) : every_(every) {}
  ~Batch() { flush(); }
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;
  void add(std::uint64_t units = 1) {
    pending_ += units;
    if (pending_ >= every_) flush();
  }
  void flush() {
    if (pending_ != 0) advance(pending_);
    pending_ = 0;
  }

 private:
  std::uint64_t every_, pending_ = 0;
};

}  // namespace shadowcts::phase_progress
