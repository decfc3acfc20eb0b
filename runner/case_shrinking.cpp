#include "case_shrinking.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace shadowcts {
namespace {

// The original with only the samples and triangles at these indices (ascending), receivers
// renumbered, explicit samples placed in one row again (finish() decides closedness anew).
fuzzing::SampleCase subset(const fuzzing::SampleCase& original,
                           const std::vector<std::size_t>& samples,
                           const std::vector<std::size_t>& triangles) {
  fuzzing::SampleCase s = original;
  const std::size_t n = original.c.triangles.size();
  std::vector<std::uint32_t> renumbered(n, no_receiver);
  s.c.triangles.clear();
  for (std::size_t t : triangles) {
    renumbered[t] = std::uint32_t(s.c.triangles.size());
    s.c.triangles.push_back(original.c.triangles[t]);
  }
  s.samples.samples.clear();
  for (std::size_t i : samples) {
    ViewSample v = original.samples.samples[i];
    if (v.receiver != no_receiver) v.receiver = renumbered[v.receiver];
    if (original.explicit_samples) {
      v.pixel_x = std::uint32_t(s.samples.samples.size());
      v.pixel_y = 0;
    }
    s.samples.samples.push_back(v);
  }
  s.finish();
  return s;
}

// Removes chunks of `items` (halving the chunk size down to 1) while `fails` of what remains
// says so, never leaving fewer than `at_least`. False when the test said stop.
bool remove_chunks(std::vector<std::size_t>& items, std::size_t at_least,
                   const std::function<CandidateResult(const std::vector<std::size_t>&)>& fails) {
  if (items.size() <= at_least) return true;
  std::size_t chunk = (items.size() + 1) / 2;
  for (;;) {
    for (std::size_t at = 0; at < items.size();) {
      const std::size_t end = std::min(items.size(), at + chunk);
      if (items.size() - (end - at) < at_least) {
        at = end;
        continue;
      }
      std::vector<std::size_t> candidate(items.begin(), items.begin() + std::ptrdiff_t(at));
      candidate.insert(candidate.end(), items.begin() + std::ptrdiff_t(end), items.end());
      const CandidateResult result = fails(candidate);
      if (result == CandidateResult::stop) return false;
      if (result == CandidateResult::fails)
        items = std::move(candidate);  // the next chunk now starts at `at`
      else
        at = end;
    }
    if (chunk == 1 || items.size() <= at_least) return true;
    chunk = (chunk + 1) / 2;
  }
}

}  // namespace

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
    // finish() decides again whether its mesh is closed, as the reproducer's loader will.
    candidate.c.triangles.erase(candidate.c.triangles.begin() + std::ptrdiff_t(t));
    for (ViewSample& s : candidate.samples.samples)
      if (s.receiver != no_receiver && s.receiver > t) --s.receiver;
    candidate.finish();
    if (still_fails(candidate)) best = std::move(candidate);
  }
  return best;
}

ChunkShrinking shrink_case_in_chunks(
    const fuzzing::SampleCase& original,
    const std::function<CandidateResult(const fuzzing::SampleCase&)>& test) {
  ChunkShrinking result{original, 0, false};
  std::vector<std::size_t> samples(original.samples.samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = i;
  std::vector<std::size_t> triangles(original.c.triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) triangles[t] = t;
  auto run = [&](const std::vector<std::size_t>& s, const std::vector<std::size_t>& t) {
    fuzzing::SampleCase candidate = subset(original, s, t);
    const CandidateResult answer = test(candidate);
    if (answer != CandidateResult::stop) ++result.tests;
    if (answer == CandidateResult::fails) result.best = std::move(candidate);
    return answer;
  };
  if (original.explicit_samples && !samples.empty())
    result.stopped = !remove_chunks(
        samples, 1, [&](const std::vector<std::size_t>& s) { return run(s, triangles); });
  if (result.stopped) return result;
  // The receivers of the kept samples stay; the other triangles are removed in chunks.
  std::vector<bool> receiver(original.c.triangles.size(), false);
  for (std::size_t i : samples) {
    const std::uint32_t r = original.samples.samples[i].receiver;
    if (r != no_receiver && r < receiver.size()) receiver[r] = true;
  }
  std::vector<std::size_t> removable;
  for (std::size_t t : triangles)
    if (!receiver[t]) removable.push_back(t);
  const std::size_t receivers = triangles.size() - removable.size();
  auto with_receivers = [&](const std::vector<std::size_t>& kept) {
    std::vector<std::size_t> all = kept;
    for (std::size_t t = 0; t < receiver.size(); ++t)
      if (receiver[t]) all.push_back(t);
    std::sort(all.begin(), all.end());
    return all;
  };
  result.stopped = !remove_chunks(
      removable, receivers > 0 ? 0 : 1,
      [&](const std::vector<std::size_t>& kept) { return run(samples, with_receivers(kept)); });
  return result;
}

}  // namespace shadowcts
