#pragma once
// Exact classification of one view sample in the ambiguity band (DESIGN.md, "Tolerance: the
// ambiguity band"): its exact answer, its class at the case's eps_rel and its robust_exponent.
//
// A sample is robust at a set of move lengths when no move p + delta u (u one of band_moves,
// delta in the set) changes the exact answer; the band at eps_rel uses the lengths
// eps_rel S 2^-j >= 2^-24 S, and robust_exponent the lengths 2^k S, k = -24 ... -10.
//
// Most samples need no move at all, by two exact sufficient tests:
// - lit: the candidate set (triangles that may come within the band of the shadow query, with a
//   conservative separation each) is empty at the largest move, or holds only triangles farther
//   than the moves of a level: nothing can block a moved query, so the answer cannot change;
// - shadowed: the 8 corners of the cube of half-width delta around p, all blocked by one triangle
//   T (exact predicate), put the whole cube inside T's shadow volume (convex: the points whose
//   segment to the light, or ray, meets T), so every move of length <= delta stays shadowed.
// Otherwise the moves are tried, level by level from the smallest, against the candidates.
#include <array>
#include <cstdint>
#include <vector>

#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "oracles/hard_shadow_inputs.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_truth.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct SampleTruth {
  bool shadowed = false;
  BandClass band = BandClass::not_compared;
  std::int8_t robust_exponent = ambiguous_at_every_exponent;
};

// A caster that may come within the band of a sample's shadow query, and a lower bound on how far
// the query must be inflated to meet it (separation_inflation).
struct BandCandidate {
  double separation = 0.0;
  std::uint32_t triangle = 0;
};

class ExactBandClassifier {
 public:
  ExactBandClassifier(const Case& c, const HardShadowLight& light, const CasterBvh& casters,
                      const ExactShadowPredicate& predicate);

  // The sample must be regular. `candidates` is scratch space, reused between calls.
  SampleTruth classify(const ViewSample& sample, std::vector<BandCandidate>& candidates) const;

  // The largest move of any level: the inflation of the candidate query.
  double largest_move() const { return largest_move_; }

 private:
  struct Query;
  bool moved_answer(const Query& q, double delta, const glm::ivec3& move, std::size_t active) const;
  bool cube_in_shadow_of(const Query& q, std::uint32_t triangle, double delta) const;
  std::size_t first_changing_length(const Query& q, const std::vector<double>& lengths) const;

  const Case& case_;
  HardShadowLight light_;
  const CasterBvh& casters_;
  const ExactShadowPredicate& predicate_;
  double scale_;
  std::vector<double> level_lengths_;  // 2^k S for k = band_min_exponent ... band_max_exponent
  // The band at eps_rel: either read off robust_exponent (eps_rel = 2^e, e in the level range),
  // or decided with its own move lengths (ascending).
  bool class_from_exponent_ = false;
  int class_exponent_ = 0;
  std::vector<double> class_lengths_;
  double largest_move_ = 0.0;
};

}  // namespace shadowcts
