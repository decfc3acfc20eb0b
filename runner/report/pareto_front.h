#pragma once
// The Pareto front of (time, error) points: those no other point beats in both.
#include <cstddef>
#include <vector>

namespace shadowcts {

struct TimeErrorPoint {
  double time = 0, error = 0;
};

// Indices of the points that no other point dominates (another point dominates when it is no
// slower and no worse, and strictly better in one). Equal points are all on the front. Sorted by
// time, then error, then index.
std::vector<std::size_t> pareto_front(const std::vector<TimeErrorPoint>& points);

}  // namespace shadowcts
