#include "shadowcts/phase_progress.h"

#include <atomic>

namespace shadowcts::phase_progress {
namespace {

std::atomic<std::uint64_t> done_units{0};
std::atomic<std::uint64_t> total_units{0};
std::atomic<std::uint64_t> generation_count{0};
std::atomic<const char*> unit_name{""};
std::atomic<const char*> of_name{""};

}  // namespace

void begin(std::uint64_t total, const char* unit, const char* of) {
  done_units.store(0, std::memory_order_relaxed);
  total_units.store(total, std::memory_order_relaxed);
  unit_name.store(unit != nullptr ? unit : "", std::memory_order_relaxed);
  of_name.store(of != nullptr ? of : "", std::memory_order_relaxed);
  generation_count.fetch_add(1, std::memory_order_release);
}

void advance(std::uint64_t units) {
  done_units.fetch_add(units, std::memory_order_relaxed);
}

Snapshot snapshot() {
  Snapshot s;
  s.generation = generation_count.load(std::memory_order_acquire);
  s.total = total_units.load(std::memory_order_relaxed);
  s.done = done_units.load(std::memory_order_relaxed);
  s.unit = unit_name.load(std::memory_order_relaxed);
  s.of = of_name.load(std::memory_order_relaxed);
  return s;
}

}  // namespace shadowcts::phase_progress
