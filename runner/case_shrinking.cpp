#include "case_shrinking.h"

#include <utility>

namespace shadowcts {

fuzzing::SampleCase shrink_case(
    const fuzzing::SampleCase& original, std::optional<std::size_t> failing_sample,
    const std::function<bool(const fuzzing::SampleCase&)>& still_fails) {
  fuzzing::SampleCase best = original;
  if (failing_sample && original.explicit_samples) {
    fuzzing::SampleCase single = original;
    single.samples.samples = {original.samples.samples[*failing_sample]};
    single.samples.samples[0].pixel_x = 0;
    single.finish();
    if (still_fails(single)) best = single;
  }
  for (std::size_t t = best.c.triangles.size(); t-- > 0;) {
    bool is_receiver = false;
    for (const ViewSample& s : best.samples.samples) is_receiver |= s.receiver == t;
    if (is_receiver || best.c.triangles.size() == 1) continue;
    fuzzing::SampleCase candidate = best;
    // A mesh that loses a triangle is no longer closed (and the reproducer's loader agrees).
    candidate.c.meshes[candidate.c.triangles[t].mesh].closed = false;
    candidate.c.triangles.erase(candidate.c.triangles.begin() + std::ptrdiff_t(t));
    for (ViewSample& s : candidate.samples.samples)
      if (s.receiver != no_receiver && s.receiver > t) --s.receiver;
    candidate.finish();
    if (still_fails(candidate)) best = std::move(candidate);
  }
  return best;
}

}  // namespace shadowcts
