#include "pareto_front.h"

#include <algorithm>

namespace shadowcts {

std::vector<std::size_t> pareto_front(const std::vector<TimeErrorPoint>& points) {
  // Quadratic, on purpose: a case has tens of records, and this form is obviously right.
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
      const TimeErrorPoint &a = points[j], &b = points[i];
      dominated = a.time <= b.time && a.error <= b.error && (a.time < b.time || a.error < b.error);
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].time != points[b].time) return points[a].time < points[b].time;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  return front;
}

}  // namespace shadowcts
