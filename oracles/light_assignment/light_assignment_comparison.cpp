#include "oracles/light_assignment/light_assignment_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/light_assignment/light_volume_predicates.h"

namespace shadowcts {
namespace {

bool contains_sorted(const std::uint32_t* first, const std::uint32_t* last, std::uint32_t value) {
  return std::binary_search(first, last, value);
}

// The first structural problem of the lists, or "".
std::string structure_problem(const LightLists& lists, const Case& c, const ViewSamples& samples) {
  const std::size_t list_count = lists.offsets.empty() ? 0 : lists.offsets.size() - 1;
  if (lists.offsets.empty() || lists.offsets.front() != 0) return "offsets must start with 0";
  for (std::size_t k = 0; k < list_count; ++k)
    if (lists.offsets[k + 1] < lists.offsets[k])
      return "offsets decrease at list " + std::to_string(k);
  if (lists.offsets.back() != lists.lights.size())
    return "offsets end at " + std::to_string(lists.offsets.back()) + " but there are " +
           std::to_string(lists.lights.size()) + " list entries";
  if (lists.bounds.size() != list_count)
    return std::to_string(lists.bounds.size()) + " bounds for " + std::to_string(list_count) +
           " lists";
  if (lists.list_of_sample.size() != samples.samples.size())
    return "list_of_sample has " + std::to_string(lists.list_of_sample.size()) + " entries for " +
           std::to_string(samples.samples.size()) + " samples";
  for (std::size_t i = 0; i < lists.lights.size(); ++i)
    if (lists.lights[i] >= c.ranged_lights.size())
      return "list entry " + std::to_string(i) + " names light " + std::to_string(lists.lights[i]) +
             " of " + std::to_string(c.ranged_lights.size());
  for (std::size_t k = 0; k < list_count; ++k) {
    const Aabb& b = lists.bounds[k];
    for (int i = 0; i < 3; ++i)
      if (!(std::isfinite(b.min[i]) && std::isfinite(b.max[i]) && b.min[i] <= b.max[i]))
        return "bounds of list " + std::to_string(k) + " are not a finite box with min <= max";
  }
  for (std::size_t s = 0; s < samples.samples.size(); ++s) {
    if (samples.samples[s].sample_class != SampleClass::regular) continue;
    if (lists.list_of_sample[s] >= list_count)
      return "regular sample " + std::to_string(s) + " has no list";
  }
  return "";
}

bool box_contains(const Aabb& b, const glm::vec3& p) {
  return b.min.x <= p.x && p.x <= b.max.x && b.min.y <= p.y && p.y <= b.max.y && b.min.z <= p.z &&
         p.z <= b.max.z;
}

std::string pixel_of(const ViewSamples& samples, std::uint32_t s) {
  const ViewSample& v = samples.samples[s];
  return "sample " + std::to_string(s) + " (pixel " + std::to_string(v.pixel_x) + "," +
         std::to_string(v.pixel_y) + ")";
}

}  // namespace

bool light_lists_use_normal_rule(std::string_view variant) {
  return variant.find("+en") != std::string_view::npos ||
         variant.find("+nk") != std::string_view::npos;
}

LightAssignmentComparison compare_light_lists(const LightLists& lists, const Case& c,
                                              const ViewSamples& samples,
                                              const LightAssignmentTruth& truth) {
  LightAssignmentComparison cmp;
  cmp.compared = samples.count(SampleClass::regular);
  cmp.structure_error = structure_problem(lists, c, samples);
  if (truth.offsets.size() != samples.samples.size() + 1)
    cmp.structure_error = "the truth does not belong to these samples";
  if (!cmp.structure_error.empty()) {
    cmp.verdict = Verdict::fail;
    cmp.reason = "malformed light lists: " + cmp.structure_error;
    return cmp;
  }
  const std::size_t list_count = lists.offsets.size() - 1;
  cmp.lists = list_count;
  cmp.listed_lights = lists.lights.size();

  // Sorted copies of the lists for lookups; a light twice in one list is malformed (it would be
  // shaded twice).
  std::vector<std::uint32_t> sorted = lists.lights;
  std::vector<std::uint8_t> duplicate(list_count, 0);
  std::vector<std::uint64_t> unsound_per_list(list_count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, list_count, 64), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const auto first = sorted.begin() + std::ptrdiff_t(lists.offsets[k]);
      const auto last = sorted.begin() + std::ptrdiff_t(lists.offsets[k + 1]);
      std::sort(first, last);
      duplicate[k] = std::adjacent_find(first, last) != last;
      for (std::uint32_t e = lists.offsets[k]; e < lists.offsets[k + 1]; ++e) {
        const RangedLight& light = c.ranged_lights[lists.lights[e]];
        unsound_per_list[k] += !sphere_meets_box(light.centre, light.range, lists.bounds[k]);
      }
    }
  });
  for (std::size_t k = 0; k < list_count; ++k)
    if (duplicate[k]) {
      cmp.structure_error = "list " + std::to_string(k) + " holds a light twice";
      cmp.verdict = Verdict::fail;
      cmp.reason = "malformed light lists: " + cmp.structure_error;
      return cmp;
    }

  // Per sample: misses, ambiguous members left out, containment in the list's box.
  const std::size_t n = samples.samples.size();
  std::vector<std::uint32_t> misses(n, 0);
  std::vector<std::uint8_t> outside(n, 0);
  struct Sums {
    std::uint64_t robust = 0, ambiguous = 0, ambiguous_unlisted = 0, lighting = 0, minimum = 0;
  };
  std::vector<Sums> block_sums((n + 4095) / 4096);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, block_sums.size(), 1), [&](const auto& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      Sums& sums = block_sums[b];
      for (std::size_t s = b * 4096; s < std::min(n, (b + 1) * 4096); ++s) {
        const ViewSample& sample = samples.samples[s];
        if (sample.sample_class != SampleClass::regular) continue;
        const std::uint32_t list = lists.list_of_sample[s];
        const std::uint32_t* first = sorted.data() + lists.offsets[list];
        const std::uint32_t* last = sorted.data() + lists.offsets[list + 1];
        sums.lighting += std::uint64_t(last - first);
        sums.minimum += truth.set_size(s);
        outside[s] = !box_contains(lists.bounds[list], sample.position);
        const std::uint32_t* amb_first = truth.ambiguous_lights.data() + truth.ambiguous_offsets[s];
        const std::uint32_t* amb_last =
            truth.ambiguous_lights.data() + truth.ambiguous_offsets[s + 1];
        for (std::uint64_t e = truth.offsets[s]; e < truth.offsets[s + 1]; ++e) {
          const std::uint32_t light = truth.lights[e];
          const bool listed = contains_sorted(first, last, light);
          if (contains_sorted(amb_first, amb_last, light)) {
            ++sums.ambiguous;
            sums.ambiguous_unlisted += !listed;
          } else {
            ++sums.robust;
            misses[s] += !listed;
          }
        }
      }
    }
  });
  for (const Sums& s : block_sums) {
    cmp.robust_members += s.robust;
    cmp.ambiguous_members += s.ambiguous;
    cmp.ambiguous_unlisted += s.ambiguous_unlisted;
    cmp.lighting_computations += s.lighting;
    cmp.exact_minimum += s.minimum;
  }
  cmp.lighting_ratio =
      cmp.exact_minimum == 0 ? 0.0 : double(cmp.lighting_computations) / double(cmp.exact_minimum);

  // Examples, in sample and list order.
  for (std::size_t s = 0; s < n; ++s) {
    cmp.completeness_misses += misses[s];
    cmp.samples_outside_bounds += outside[s];
    const std::uint32_t list = lists.list_of_sample[s];
    if (outside[s] && cmp.first_outside.size() < light_comparison_examples)
      cmp.first_outside.push_back({std::uint32_t(s), list});
    if (misses[s] == 0 || cmp.first_misses.size() >= light_comparison_examples) continue;
    const std::uint32_t* first = sorted.data() + lists.offsets[list];
    const std::uint32_t* last = sorted.data() + lists.offsets[list + 1];
    const std::uint32_t* amb_first = truth.ambiguous_lights.data() + truth.ambiguous_offsets[s];
    const std::uint32_t* amb_last = truth.ambiguous_lights.data() + truth.ambiguous_offsets[s + 1];
    for (std::uint64_t e = truth.offsets[s]; e < truth.offsets[s + 1]; ++e) {
      const std::uint32_t light = truth.lights[e];
      if (!contains_sorted(amb_first, amb_last, light) && !contains_sorted(first, last, light) &&
          cmp.first_misses.size() < light_comparison_examples)
        cmp.first_misses.push_back({std::uint32_t(s), light, list});
    }
  }
  for (std::size_t k = 0; k < list_count; ++k) {
    cmp.unsound_listings += unsound_per_list[k];
    if (unsound_per_list[k] == 0 || cmp.first_unsound.size() >= light_comparison_examples) continue;
    for (std::uint32_t e = lists.offsets[k]; e < lists.offsets[k + 1]; ++e) {
      const RangedLight& light = c.ranged_lights[lists.lights[e]];
      if (!sphere_meets_box(light.centre, light.range, lists.bounds[k]) &&
          cmp.first_unsound.size() < light_comparison_examples)
        cmp.first_unsound.push_back({std::uint32_t(k), lists.lights[e]});
    }
  }

  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.3g", cmp.lighting_ratio);
  const std::string efficiency = std::to_string(cmp.lighting_computations) +
                                 " lighting computations, " + ratio + "x the exact minimum " +
                                 std::to_string(cmp.exact_minimum);
  std::string failures;
  auto add = [&](const std::string& text) { failures += (failures.empty() ? "" : "; ") + text; };
  if (cmp.completeness_misses > 0) {
    const LightListMiss& m = cmp.first_misses.front();
    add(std::to_string(cmp.completeness_misses) +
        " completeness misses (first: " + pixel_of(samples, m.sample) + " lacks light " +
        std::to_string(m.light) + " in list " + std::to_string(m.list) + ")");
  }
  if (cmp.unsound_listings > 0) {
    const UnsoundListing& u = cmp.first_unsound.front();
    add(std::to_string(cmp.unsound_listings) + " unsound listings (first: light " +
        std::to_string(u.light) + " cannot reach the bounds of list " + std::to_string(u.list) +
        ")");
  }
  if (cmp.samples_outside_bounds > 0) {
    const SampleOutsideList& o = cmp.first_outside.front();
    add(std::to_string(cmp.samples_outside_bounds) +
        " samples outside their list's bounds (first: " + pixel_of(samples, o.sample) + ", list " +
        std::to_string(o.list) + ")");
  }
  if (!failures.empty()) {
    cmp.verdict = Verdict::fail;
    cmp.reason = failures;
  } else {
    cmp.verdict = Verdict::pass;
    cmp.reason = "complete and sound: " + efficiency + "; " +
                 std::to_string(cmp.ambiguous_members) + " ambiguous members (" +
                 std::to_string(cmp.ambiguous_unlisted) + " unlisted)";
  }
  return cmp;
}

}  // namespace shadowcts
