#include "oracles/ambiguity_band.h"

#include <algorithm>
#include <cmath>

#include "oracles/band_moves.h"
#include "oracles/shadow_segment.h"

namespace shadowcts {

namespace {
constexpr std::uint32_t no_triangle = 0xffffffffu;
}  // namespace

struct ExactBandClassifier::Query {
  glm::dvec3 position;
  bool shadowed = false;
  std::uint32_t first_blocker = no_triangle;  // the first candidate that blocks p itself
  const std::vector<BandCandidate>* candidates = nullptr;  // sorted by (separation, triangle)
};

ExactBandClassifier::ExactBandClassifier(const Case& c, const HardShadowLight& light,
                                         const CasterBvh& casters,
                                         const ExactShadowPredicate& predicate)
    : case_(c), light_(light), casters_(casters), predicate_(predicate), scale_(c.scale()) {
  for (int k = band_min_exponent; k <= band_max_exponent; ++k)
    level_lengths_.push_back(std::ldexp(scale_, k));  // exact: S times a power of two

  const double eps_rel = c.parameters.eps_rel;
  int exponent = 0;
  const double mantissa = std::frexp(eps_rel, &exponent);  // eps_rel = mantissa 2^exponent
  if (mantissa == 0.5 && exponent - 1 >= band_min_exponent && exponent - 1 <= band_max_exponent) {
    class_from_exponent_ = true;
    class_exponent_ = exponent - 1;
  } else {
    // tau 2^-j >= 2^-24 S, compared exactly (both sides are exact products by powers of two).
    const double tau = eps_rel * scale_;
    const double smallest = std::ldexp(scale_, band_min_exponent);
    for (double length = tau; length >= smallest && length > 0.0; length *= 0.5)
      class_lengths_.push_back(length);
    std::reverse(class_lengths_.begin(), class_lengths_.end());
  }
  largest_move_ = level_lengths_.back();
  if (!class_lengths_.empty()) largest_move_ = std::max(largest_move_, class_lengths_.back());
}

bool ExactBandClassifier::moved_answer(const Query& q, double delta, const glm::ivec3& move,
                                       std::size_t active) const {
  const MovedPoint moved{q.position, delta, move};
  if (q.first_blocker != no_triangle && predicate_.blocks(case_.triangles[q.first_blocker], moved))
    return true;
  for (std::size_t i = 0; i < active; ++i) {
    const std::uint32_t triangle = (*q.candidates)[i].triangle;
    if (triangle != q.first_blocker && predicate_.blocks(case_.triangles[triangle], moved))
      return true;
  }
  return false;
}

bool ExactBandClassifier::cube_in_shadow_of(const Query& q, std::uint32_t triangle,
                                            double delta) const {
  for (std::size_t m = first_corner_move; m < band_moves.size(); ++m)
    if (!predicate_.blocks(case_.triangles[triangle], MovedPoint{q.position, delta, band_moves[m]}))
      return false;
  return true;
}

// Index of the first length (ascending) at which some move changes the answer; lengths.size()
// when none does.
std::size_t ExactBandClassifier::first_changing_length(const Query& q,
                                                       const std::vector<double>& lengths) const {
  const std::size_t n = lengths.size();
  if (n == 0) return 0;
  const std::vector<BandCandidate>& candidates = *q.candidates;
  std::size_t start = 0;
  if (q.shadowed) {
    // Cube containment is monotone in the length: binary search for the largest length whose
    // cube lies in the first blocker's shadow volume; no move up to it changes the answer.
    if (cube_in_shadow_of(q, q.first_blocker, lengths[n - 1])) return n;
    std::ptrdiff_t inside = -1, outside = std::ptrdiff_t(n - 1);
    while (outside - inside > 1) {
      const std::ptrdiff_t middle = (inside + outside) / 2;
      if (cube_in_shadow_of(q, q.first_blocker, lengths[std::size_t(middle)]))
        inside = middle;
      else
        outside = middle;
    }
    start = std::size_t(inside + 1);
  } else {
    // Lit: no move of a length below the nearest candidate's separation can reach a caster.
    if (candidates.empty()) return n;
    while (start < n && lengths[start] < candidates.front().separation) ++start;
  }
  std::size_t active = 0;
  for (std::size_t level = start; level < n; ++level) {
    const double delta = lengths[level];
    // Candidates with separation > delta miss every query moved by at most delta.
    while (active < candidates.size() && candidates[active].separation <= delta) ++active;
    for (const glm::ivec3& move : band_moves)
      if (moved_answer(q, delta, move, active) != q.shadowed) return level;
  }
  return n;
}

SampleTruth ExactBandClassifier::classify(const ViewSample& sample,
                                          std::vector<BandCandidate>& candidates) const {
  Query q;
  q.position = glm::dvec3(sample.position);
  q.candidates = &candidates;
  const ShadowSegment segment = make_shadow_segment(q.position, light_, scale_);

  // Candidates: every caster that may come within largest_move_ of the query (conservative, see
  // caster_bvh.h and shadow_segment.h). On the way, the exact answer at p: only candidates with
  // separation 0 can block p itself.
  auto gather = [&](bool stop_at_first_blocker) {
    candidates.clear();
    q.first_blocker = no_triangle;
    casters_.visit(segment, largest_move_, [&](std::uint32_t triangle) {
      if (triangle == sample.receiver) return false;
      const Triangle& t = case_.triangles[triangle];
      const double separation = separation_inflation(segment, glm::dvec3(t.v0), glm::dvec3(t.v1),
                                                     glm::dvec3(t.v2), largest_move_);
      if (separation > largest_move_) return false;
      candidates.push_back({separation, triangle});
      if (separation == 0.0 && q.first_blocker == no_triangle &&
          predicate_.blocks(t, MovedPoint{q.position, 0.0, {0, 0, 0}})) {
        q.first_blocker = triangle;
        return stop_at_first_blocker;
      }
      return false;
    });
  };
  gather(true);
  q.shadowed = q.first_blocker != no_triangle;

  SampleTruth truth;
  truth.shadowed = q.shadowed;
  if (q.shadowed && cube_in_shadow_of(q, q.first_blocker, largest_move_)) {
    truth.band = BandClass::robust_shadowed;
    truth.robust_exponent = band_max_exponent;
    return truth;
  }
  if (q.shadowed) gather(false);  // the candidate set is complete only after a full traversal
  std::sort(candidates.begin(), candidates.end(),
            [](const BandCandidate& a, const BandCandidate& b) {
              if (a.separation != b.separation) return a.separation < b.separation;
              return a.triangle < b.triangle;
            });

  const std::size_t level = first_changing_length(q, level_lengths_);
  truth.robust_exponent = std::int8_t(band_min_exponent - 1 + int(level));
  const bool robust = class_from_exponent_
                          ? truth.robust_exponent >= class_exponent_
                          : first_changing_length(q, class_lengths_) == class_lengths_.size();
  truth.band = !robust      ? BandClass::ambiguous
               : q.shadowed ? BandClass::robust_shadowed
                            : BandClass::robust_lit;
  return truth;
}

}  // namespace shadowcts
