#include "reference/lightassign/brute_assignment.h"

#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/light_assignment/light_volume_predicates.h"
#include "reference/lightassign/light_bvh.h"
#include "reference/lightassign/light_list_builder.h"

namespace shadowcts {

AlgorithmOutput assign_lights_brute(const Case& c, const ViewSamples& samples) {
  std::vector<ExactLightVolume> volumes(c.ranged_lights.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, volumes.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      volumes[i] = prepare_light_volume(c.ranged_lights[i]);
  });
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

  const ListWork work = build_light_lists(regular.size(), out, [&](std::size_t k, auto& list) {
    ListWork w;
    const LightQueryPoint p{glm::dvec3(samples.samples[regular[k]].position), 0.0, {0, 0, 0}};
    w.nodes_tested = bvh.traverse(out.bounds[k], [&](std::uint32_t index) {
      ++w.light_tests;
      if (light_volume_contains(volumes[index], p)) list.push_back(index);
    });
    return w;
  });

  AlgorithmOutput output;
  output.counters = light_assignment_counters(out, samples, work, 0, 0);
  output.light_lists = std::move(out);
  return output;
}

}  // namespace shadowcts
