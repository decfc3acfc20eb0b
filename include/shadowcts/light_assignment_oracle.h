#pragma once
// The exact light-assignment oracle (DESIGN.md, "Light assignment"; thesis Papers I and II).
//
// For every regular view sample p it gives the exact light set: every ranged light whose closed
// volume contains p (sphere |p - c| <= r; spot: sphere and angle(p - c, axis) <= half angle,
// apex included), and with the normal rule only those with n . (c - p) > 0 as well. Decided by
// exact predicates on the float inputs (oracles/light_assignment/light_volume_predicates.h:
// double filters with proven error bounds, exact GMP rationals behind them, MPFR intervals for
// the spot cone's cosine).
//
// The ambiguity band, adapted to light volumes: a light is ambiguous for p when its membership
// (volume, and normal rule if applied) changes for some move p + 2^-j tau u, with u one of the
// 14 band moves and 2^-j tau >= 2^-24 S (tau = eps_rel S, S = Case::scale()), exactly the moves
// of the hard-shadow band. A light farther than sqrt(3) tau from the boundary of its volume (and
// of the half-space n . (c - x) > 0) is robust without trying the moves. Completeness is
// required for the robust members only; ambiguous lights are reported, never a failure.
//
// Runs on Case::parameters.threads threads (0: all); the result does not depend on the thread
// count.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct LightAssignmentTruth {
  std::string method;  // how the truth was obtained (predicates, index, band)
  bool exact = true;
  bool normal_rule = false;  // lights behind the sample (n . (c - p) <= 0) were dropped
  double eps_rel = 0.0;
  double tau = 0.0;  // eps_rel * Case::scale()
  // Per view sample s: the exact light set, lights[offsets[s] .. offsets[s + 1]) ascending
  // (indices into Case::ranged_lights). Empty for samples that are not regular.
  std::vector<std::uint64_t> offsets{0};
  std::vector<std::uint32_t> lights;
  // Per view sample s: the ambiguous lights, ambiguous_lights[ambiguous_offsets[s] ..
  // ambiguous_offsets[s + 1]) ascending. A light may be ambiguous whether it is in the exact set
  // or not.
  std::vector<std::uint64_t> ambiguous_offsets{0};
  std::vector<std::uint32_t> ambiguous_lights;
  // Work done, for the report: light candidates from the index, pairs that needed the band moves.
  std::uint64_t candidate_pairs = 0;
  std::uint64_t band_move_pairs = 0;

  std::size_t set_size(std::size_t sample) const { return offsets[sample + 1] - offsets[sample]; }
  // Sum over regular samples of the exact set sizes: the fewest lighting computations any
  // complete light assignment can make (Paper I's metric).
  std::uint64_t exact_minimum() const { return lights.size(); }
};

// Throws InputError for a case without ranged lights, and std::invalid_argument when the samples
// do not match the camera's resolution.
LightAssignmentTruth exact_light_assignment_oracle(const Case& c, const ViewSamples& samples,
                                                   bool normal_rule);

}  // namespace shadowcts
