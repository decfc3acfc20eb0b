#pragma once
// Diffs an algorithm's light lists (AlgorithmOutput::light_lists) against the exact
// light-assignment truth: completeness, soundness and the papers' efficiency metric.
//
// - Completeness: every robust member of a regular sample's exact set is in the sample's list.
//   A miss is a Fail. Ambiguous members that are not listed are counted, never a failure.
// - Soundness: every regular sample lies in its list's declared box (float comparisons, exact),
//   and every listed light's sphere meets the box of its list (exact predicate). Spots are judged
//   by their bounding sphere, as the papers cull them; a tighter cone test is efficiency, not
//   soundness. Either violation is a Fail.
// - Efficiency (Paper I's metric, reported, no verdict): lighting computations = sum over regular
//   samples of their list's length, against the exact minimum = sum of the exact set sizes.
// Malformed lists (offsets, indices, sizes, a light twice in one list, a regular sample without a
// list) are a Fail with the first problem as the reason.
//
// How the runner calls it, per case with ranged lights and per light-list algorithm variant:
//   const bool normals = light_lists_use_normal_rule(variant);
//   const LightAssignmentTruth& truth = /* once per case and value of normals: */
//       exact_light_assignment_oracle(c, samples, normals);
//   const LightAssignmentComparison cmp =
//       compare_light_lists(output.light_lists, c, samples, truth);
//   record.verdict = cmp.verdict; record.reason = cmp.reason;
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/verdict.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct LightListMiss {
  std::uint32_t sample = 0, light = 0, list = 0;
};

struct UnsoundListing {
  std::uint32_t list = 0, light = 0;
};

struct SampleOutsideList {
  std::uint32_t sample = 0, list = 0;
};

// At most this many examples of each failure are kept (the first ones in sample or list order).
inline constexpr std::size_t light_comparison_examples = 8;

struct LightAssignmentComparison {
  std::uint64_t compared = 0;  // regular samples
  std::uint64_t lists = 0;
  std::uint64_t robust_members = 0;     // exact-set entries that must be listed
  std::uint64_t ambiguous_members = 0;  // exact-set entries in the band
  std::uint64_t ambiguous_unlisted = 0;

  std::uint64_t completeness_misses = 0;
  std::vector<LightListMiss> first_misses;
  std::uint64_t unsound_listings = 0;
  std::vector<UnsoundListing> first_unsound;
  std::uint64_t samples_outside_bounds = 0;
  std::vector<SampleOutsideList> first_outside;

  std::uint64_t listed_lights = 0;          // total length of all lists
  std::uint64_t lighting_computations = 0;  // sum over regular samples of their list's length
  std::uint64_t exact_minimum = 0;          // sum over regular samples of the exact set size
  // lighting_computations / exact_minimum (1 is optimal); 0 when the minimum is 0.
  double lighting_ratio = 0.0;

  std::string structure_error;  // the first structural problem; empty when well formed
  Verdict verdict = Verdict::pass;
  std::string reason;  // one line explaining the verdict
};

LightAssignmentComparison compare_light_lists(const LightLists& lists, const Case& c,
                                              const ViewSamples& samples,
                                              const LightAssignmentTruth& truth);

// Whether a light-list variant drops lights behind its samples (Paper II's back-face culling by
// normal cones), so that it must be compared against the truth with the normal rule. The
// convention follows the suffixes of Paper II's Table 1: a variant name with "+en" (explicit
// normal cones) or "+nk" (clustering on normals, implicit cones) culls by normals.
bool light_lists_use_normal_rule(std::string_view variant);

}  // namespace shadowcts
