#include "reference/lightassign/brute_assignment.h"

#include <atomic>
#include <vector>

#include "reference/lightassign/light_bvh.h"
#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/light_volume_check.h"

namespace shadowcts {

AlgorithmOutput assign_lights_brute(const Case& c, const ViewSamples& samples) {
  std::vector<LightVolumeCheck> volumes;
  volumes.reserve(c.ranged_lights.size());
  for (const RangedLight& light : c.ranged_lights) volumes.emplace_back(light);
  const LightBvh bvh(c.ranged_lights);

  // One list per regular sample, in sample order; its box is the sample itself.
  std::vector<std::uint32_t> regular;
  LightLists out;
  out.list_of_sample.assign(samples.samples.size(), LightLists::no_list);
  for (std::size_t s = 0; s < samples.samples.size(); ++s)
    if (samples.samples[s].sample_class == SampleClass::regular) {
      out.list_of_sample[s] = std::uint32_t(regular.size());
      regular.push_back(std::uint32_t(s));
    }
  out.bounds.resize(regular.size());
  for (std::size_t k = 0; k < regular.size(); ++k)
    out.bounds[k].min = out.bounds[k].max = samples.samples[regular[k]].position;

  std::atomic<std::uint64_t> undecided{0};
  const ListWork work = build_light_lists(regular.size(), out, [&](std::size_t k, auto& list) {
    ListWork w;
    const glm::vec3& p = samples.samples[regular[k]].position;
    w.nodes_tested = bvh.traverse(out.bounds[k], [&](std::uint32_t index) {
      ++w.light_tests;
      const int inside = volumes[index].contains(p);
      if (inside != 0) list.push_back(index);
      if (inside < 0) undecided.fetch_add(1, std::memory_order_relaxed);
    });
    return w;
  });

  AlgorithmOutput output;
  output.counters = light_assignment_counters(out, samples, work, 0, 0);
  // Lights kept because rounding could not place the sample against a spot's cone.
  output.counters.emplace_back("cone_tests_undecided", undecided.load());
  output.light_lists = std::move(out);
  return output;
}

}  // namespace shadowcts
