#pragma once
// The first difference between a port's output and the reference's, for the diff tests of every
// port: "" when there is none, else which counter, which view sample or which list differs first,
// so that a port developer learns where to look.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"

namespace shadowcts::port_test {

// The reference's counters, in its order and with its values; an emulated backend adds
// `emulated_threads` (not zero) after them and nothing else.
inline std::string counter_difference(const Counters& reference, const Counters& port,
                                      bool emulated) {
  const std::size_t expected = reference.size() + (emulated ? 1 : 0);
  for (std::size_t i = 0; i < std::min(reference.size(), port.size()); ++i)
    if (reference[i] != port[i])
      return "counter " + reference[i].first + ": " + std::to_string(reference[i].second) +
             " (reference) vs " + port[i].first + " " + std::to_string(port[i].second);
  if (port.size() != expected)
    return std::to_string(port.size()) + " counters, " + std::to_string(expected) + " expected";
  if (emulated && (port.back().first != "emulated_threads" || port.back().second == 0))
    return "the last counter must be a non-zero emulated_threads";
  return "";
}

// Per view sample, equal values (floats: the same bits).
template <class T>
std::string sample_difference(const std::vector<T>& reference, const std::vector<T>& port) {
  if (reference.size() != port.size())
    return std::to_string(port.size()) + " view samples, " + std::to_string(reference.size()) +
           " expected";
  for (std::size_t i = 0; i < reference.size(); ++i)
    if (std::memcmp(&reference[i], &port[i], sizeof(T)) != 0) {
      std::ostringstream why;
      why << "view sample " << i << ": " << +reference[i] << " (reference) vs " << +port[i];
      return why.str();
    }
  return "";
}

// The same list for every sample, the same box per list (bit for bit) and each list the
// reference's lights in the reference's order.
inline std::string light_list_difference(const LightLists& a, const LightLists& b) {
  std::ostringstream why;
  if (a.list_of_sample.size() != b.list_of_sample.size()) return "list_of_sample sizes differ";
  for (std::size_t s = 0; s < a.list_of_sample.size(); ++s)
    if (a.list_of_sample[s] != b.list_of_sample[s]) {
      why << "sample " << s << ": list " << a.list_of_sample[s] << " vs " << b.list_of_sample[s];
      return why.str();
    }
  if (a.offsets.size() != b.offsets.size() || a.bounds.size() != b.bounds.size()) {
    why << "list counts " << a.offsets.size() - 1 << " vs " << b.offsets.size() - 1;
    return why.str();
  }
  const auto same_float = [](float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  for (std::size_t k = 0; k < a.bounds.size(); ++k)
    for (int i = 0; i < 3; ++i)
      if (!same_float(a.bounds[k].min[i], b.bounds[k].min[i]) ||
          !same_float(a.bounds[k].max[i], b.bounds[k].max[i])) {
        why << "list " << k << ": box axis " << i << " [" << a.bounds[k].min[i] << ", "
            << a.bounds[k].max[i] << "] vs [" << b.bounds[k].min[i] << ", " << b.bounds[k].max[i]
            << "]";
        return why.str();
      }
  for (std::size_t k = 0; k + 1 < a.offsets.size(); ++k) {
    std::vector<std::uint32_t> la(a.lights.begin() + a.offsets[k],
                                  a.lights.begin() + a.offsets[k + 1]);
    std::vector<std::uint32_t> lb(b.lights.begin() + b.offsets[k],
                                  b.lights.begin() + b.offsets[k + 1]);
    const bool same_order = la == lb;
    std::sort(la.begin(), la.end());
    std::sort(lb.begin(), lb.end());
    if (la != lb) {
      std::vector<std::uint32_t> only_a, only_b;
      std::set_difference(la.begin(), la.end(), lb.begin(), lb.end(), std::back_inserter(only_a));
      std::set_difference(lb.begin(), lb.end(), la.begin(), la.end(), std::back_inserter(only_b));
      why << "list " << k << ": " << la.size() << " lights vs " << lb.size();
      if (!only_a.empty()) why << "; light " << only_a.front() << " only in the reference's";
      if (!only_b.empty()) why << "; light " << only_b.front() << " only in the port's";
      return why.str();
    }
    if (!same_order) {
      why << "list " << k << ": the reference's lights in another order";
      return why.str();
    }
  }
  return "";
}

// All of an output: its counters (`emulated`: the port adds emulated_threads), then whichever of
// the shadow mask, the visible fractions and the light lists it carries.
inline std::string output_difference(const AlgorithmOutput& reference, const AlgorithmOutput& port,
                                     bool emulated) {
  for (const std::string& why :
       {counter_difference(reference.counters, port.counters, emulated),
        sample_difference(reference.shadowed, port.shadowed),
        sample_difference(reference.visible_fraction, port.visible_fraction),
        light_list_difference(reference.light_lists, port.light_lists)})
    if (!why.empty()) return why;
  return "";
}

}  // namespace shadowcts::port_test
