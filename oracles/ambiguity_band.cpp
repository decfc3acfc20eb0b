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
  ShadowSegment segment;
  double inflation = 0.0;  // the candidates' reach: the largest cube this query decides
  bool shadowed = false;
  BandCandidate first_blocker{0.0, no_triangle};     // the first candidate that blocks p itself
  std::vector<BandCandidate>* candidates = nullptr;  // sorted by (separation, triangle)
  std::vector<BandCandidate> blockers;  // shadowed: every candidate that blocks p, first first
  std::uint32_t receiver = no_receiver;
  ReceiverPlane plane;  // the receiver's, for the receiver half-space rule
};

namespace {

glm::dvec3 vertex(const Triangle& t, int i) {
  return glm::dvec3(i == 0 ? t.v0 : i == 1 ? t.v1 : t.v2);
}

}  // namespace

ExactBandClassifier::ExactBandClassifier(const Case& c, double scale, const HardShadowLight& light,
                                         const CasterBvh& casters,
                                         const ExactShadowPredicate& predicate)
    : case_(c), light_(light), casters_(casters), predicate_(predicate), scale_(scale) {
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
  if (class_from_exponent_) {
    has_class_length_ = true;
    class_length_ = level_lengths_[std::size_t(class_exponent_ - band_min_exponent)];
  } else if (!class_lengths_.empty()) {
    has_class_length_ = true;
    class_length_ = class_lengths_.back();
  }
}

const CasterClosure& ExactBandClassifier::closure() const {
  tbb::collaborative_call_once(closure_once_,
                               [&] { closure_.emplace(case_, casters_, predicate_); });
  return *closure_;
}

bool ExactBandClassifier::blocks(const Query& q, const BandCandidate& candidate,
                                 const MovedPoint& x) const {
  return predicate_.blocks(case_.triangles[candidate.triangle], x, q.plane, candidate.reach);
}

// The 8 corners blocked by one caster put the cube inside that caster's shadowing set: the points
// whose query meets the convex part of it strictly on the light's side, a convex set.
bool ExactBandClassifier::cube_in_shadow_of(const Query& q, const BandCandidate& blocker,
                                            double delta) const {
  for (std::size_t m = first_corner_move; m < band_moves.size(); ++m)
    if (!blocks(q, blocker, MovedPoint{q.position, delta, band_moves[m]})) return false;
  return true;
}

std::size_t ExactBandClassifier::active_candidates(const Query& q, double delta) const {
  const std::vector<BandCandidate>& candidates = *q.candidates;
  std::size_t active = 0;
  while (active < candidates.size() && candidates[active].separation <= delta) ++active;
  return active;
}

bool ExactBandClassifier::answer_constant_on_cube(const Query& q, double delta) const {
  // Candidates with separation > delta miss every query from the cube (shadow_segment.h).
  const std::size_t active = active_candidates(q, delta);
  const std::vector<BandCandidate>& candidates = *q.candidates;
  if (!q.shadowed) {
    // Lit: constant iff no shadow volume meets the cube.
    if (active == 0) return true;
    const ExactCubeQuery cube(predicate_, q.position, delta);
    for (std::size_t i = 0; i < active; ++i)
      if (cube.shadow_volume_meets(case_.triangles[candidates[i].triangle])) return false;
    return true;
  }
  // Shadowed: the cube inside one blocker's shadow volume, or no exposed boundary piece in it.
  for (const BandCandidate& blocker : q.blockers)
    if (cube_in_shadow_of(q, blocker, delta)) return true;
  const ExactCubeQuery cube(predicate_, q.position, delta);
  return boundary_misses(q, cube, active);
}

// No piece of the shadow boundary that may be exposed meets the cube: no candidate meets it, and
// no wedge behind an open piece of an edge and no ray behind an open point of it does
// (caster_closure.h). Non-candidates have shadow volumes that miss the cube.
bool ExactBandClassifier::boundary_misses(const Query& q, const ExactCubeQuery& cube,
                                          std::size_t active) const {
  const std::vector<BandCandidate>& candidates = *q.candidates;
  for (std::size_t i = 0; i < active; ++i)
    if (cube.meets_triangle(case_.triangles[candidates[i].triangle])) return false;
  for (std::size_t i = 0; i < active; ++i) {
    const std::uint32_t t = candidates[i].triangle;
    const Triangle& tri = case_.triangles[t];
    if (candidates[i].reach == PlaneReach::straddles && cube.clip_wedge_meets(tri, q.plane))
      return false;
    for (int k = 0; k < 3; ++k) {
      if (!closure().may_expose(t, k, q.receiver)) continue;
      // Every piece's wedge and every point's ray lies in the wedge behind the whole edge.
      if (!cube.shadow_wedge_meets(vertex(tri, k), vertex(tri, (k + 1) % 3))) continue;
      const bool exposed = closure().any_exposed(
          t, k, q.receiver,
          [&](const glm::vec3& a, const glm::vec3& b) {
            return cube.shadow_wedge_meets(glm::dvec3(a), glm::dvec3(b));
          },
          [&](const glm::vec3& x) { return cube.shadow_ray_meets(glm::dvec3(x)); });
      if (exposed) return false;
    }
  }
  return true;
}

// Index of the first length (ascending) whose cube the oracle cannot certify constant;
// lengths.size() when it certifies them all. A certified cube contains every smaller one, so
// every length below a certified one is certified too.
std::size_t ExactBandClassifier::first_changing_length(const Query& q,
                                                       const std::vector<double>& lengths) const {
  const std::size_t n = lengths.size();
  if (n == 0) return 0;
  const std::vector<BandCandidate>& candidates = *q.candidates;
  std::ptrdiff_t constant = -1;  // the largest index known to be certified
  if (q.shadowed) {
    // Cube containment is monotone in the length: binary search for the largest length whose
    // cube lies in the first blocker's shadow volume.
    if (cube_in_shadow_of(q, q.first_blocker, lengths[n - 1])) return n;
    std::ptrdiff_t outside = std::ptrdiff_t(n - 1);
    while (outside - constant > 1) {
      const std::ptrdiff_t middle = (constant + outside) / 2;
      if (cube_in_shadow_of(q, q.first_blocker, lengths[std::size_t(middle)]))
        constant = middle;
      else
        outside = middle;
    }
  } else {
    // Lit: no cube of a length below the nearest candidate's separation can reach a caster.
    if (candidates.empty()) return n;
    while (constant + 1 < std::ptrdiff_t(n) &&
           lengths[std::size_t(constant + 1)] < candidates.front().separation)
      ++constant;
  }
  std::ptrdiff_t changing = std::ptrdiff_t(n);  // the smallest index known not to be certified
  while (changing - constant > 1) {
    const std::ptrdiff_t middle = (constant + changing) / 2;
    if (answer_constant_on_cube(q, lengths[std::size_t(middle)]))
      constant = middle;
    else
      changing = middle;
  }
  return std::size_t(changing);
}

ExactBandClassifier::Query ExactBandClassifier::start(const ViewSample& sample,
                                                      std::vector<BandCandidate>& candidates,
                                                      bool with_exponent,
                                                      const Query* same_receiver) const {
  Query q;
  // Candidates within the largest cube this call decides.
  q.inflation = with_exponent ? largest_move_ : class_length_;
  q.position = glm::dvec3(sample.position);
  q.receiver = sample.receiver;
  q.candidates = &candidates;
  q.segment = make_shadow_segment(q.position, light_, scale_);
  if (sample.receiver != no_receiver)
    q.plane = same_receiver != nullptr && same_receiver->receiver == sample.receiver
                  ? same_receiver->plane
                  : predicate_.receiver_plane(case_.triangles[sample.receiver]);
  candidates.clear();
  return q;
}

// Candidates: every caster that may come within the inflation of the query (conservative, see
// caster_bvh.h and shadow_segment.h). On the way, the exact answer at p: only candidates with
// separation 0 can block p itself. True when the traversal may stop (the first blocker found).
bool ExactBandClassifier::consider(Query& q, std::uint32_t triangle,
                                   bool stop_at_first_blocker) const {
  if (triangle == q.receiver) return false;
  const Triangle& t = case_.triangles[triangle];
  // The plane test first: it is cheaper than the separation, and it rejects the receiver's
  // neighbours (no point on the light's side), which touch the query and so need every axis.
  const PlaneReach reach = predicate_.reach(q.plane, t);
  if (reach == PlaneReach::none) return false;  // shadows no point of this sample's cubes
  const double separation = separation_inflation(q.segment, glm::dvec3(t.v0), glm::dvec3(t.v1),
                                                 glm::dvec3(t.v2), q.inflation);
  if (separation > q.inflation) return false;
  const BandCandidate candidate{separation, triangle, reach};
  q.candidates->push_back(candidate);
  if (separation == 0.0 && q.first_blocker.triangle == no_triangle &&
      blocks(q, candidate, MovedPoint{q.position, 0.0, {0, 0, 0}})) {
    q.first_blocker = candidate;
    return stop_at_first_blocker;
  }
  return false;
}

void ExactBandClassifier::gather(Query& q, bool stop_at_first_blocker) const {
  q.candidates->clear();
  q.first_blocker = BandCandidate{0.0, no_triangle};
  casters_.visit(q.segment, q.inflation, [&](std::uint32_t triangle) {
    return consider(q, triangle, stop_at_first_blocker);
  });
}

SampleTruth ExactBandClassifier::classify(const ViewSample& sample,
                                          std::vector<BandCandidate>& candidates,
                                          bool with_exponent) const {
  Query q = start(sample, candidates, with_exponent);
  gather(q, true);
  if (const std::optional<SampleTruth> truth = settled(q, with_exponent)) return *truth;
  if (q.shadowed) gather(q, false);  // the candidate set is complete only after a full traversal
  return finish(q, with_exponent);
}

void ExactBandClassifier::classify_packet(const ViewSample* const* samples, int count,
                                          std::vector<BandCandidate>* candidates,
                                          SampleTruth* truths) const {
  constexpr int lanes = CasterBvh::packet_lanes;
  Query q[lanes];
  ShadowSegment segments[lanes];
  for (int l = 0; l < count; ++l) {
    q[l] = start(*samples[l], candidates[l], false, l > 0 ? &q[l - 1] : nullptr);
    segments[l] = q[l].segment;
  }
  casters_.visit_packet(segments, count, class_length_, [&](int lane, std::uint32_t triangle) {
    return consider(q[lane], triangle, true);
  });
  // The shadowed samples the first blocker does not settle gather every candidate: a second
  // traversal, as a packet of those lanes.
  int open[lanes], full[lanes], opened = 0, fulls = 0;
  for (int l = 0; l < count; ++l) {
    if (const std::optional<SampleTruth> truth = settled(q[l], false)) {
      truths[l] = *truth;
      continue;
    }
    open[opened++] = l;
    if (!q[l].shadowed) continue;
    q[l].candidates->clear();
    q[l].first_blocker = BandCandidate{0.0, no_triangle};
    segments[fulls] = q[l].segment;
    full[fulls++] = l;
  }
  casters_.visit_packet(segments, fulls, class_length_, [&](int lane, std::uint32_t triangle) {
    return consider(q[full[lane]], triangle, false);
  });
  for (int k = 0; k < opened; ++k) truths[open[k]] = finish(q[open[k]], false);
}

// The answer at p after the first gather (stopped at the first blocker), and the truth where that
// settles it: lit or shadowed at every point of the cube.
std::optional<SampleTruth> ExactBandClassifier::settled(Query& q, bool with_exponent) const {
  q.shadowed = q.first_blocker.triangle != no_triangle;
  SampleTruth truth;
  truth.shadowed = q.shadowed;
  if (!with_exponent) {
    truth.robust_exponent = robust_exponent_unknown;
    // Below the float32 resolution every sample is robust.
    truth.band = q.shadowed ? BandClass::robust_shadowed : BandClass::robust_lit;
    if (!has_class_length_) return truth;
    if (q.shadowed && cube_in_shadow_of(q, q.first_blocker, class_length_)) return truth;
  } else if (q.shadowed && cube_in_shadow_of(q, q.first_blocker, largest_move_)) {
    truth.band = BandClass::robust_shadowed;
    truth.robust_exponent = band_max_exponent;
    return truth;
  }
  return std::nullopt;
}

// The rest of classify(), on the complete candidate set.
SampleTruth ExactBandClassifier::finish(Query& q, bool with_exponent) const {
  std::vector<BandCandidate>& candidates = *q.candidates;
  const MovedPoint at_p{q.position, 0.0, {0, 0, 0}};
  SampleTruth truth;
  truth.shadowed = q.shadowed;
  truth.band = q.shadowed ? BandClass::robust_shadowed : BandClass::robust_lit;
  truth.robust_exponent = robust_exponent_unknown;
  std::sort(candidates.begin(), candidates.end(),
            [](const BandCandidate& a, const BandCandidate& b) {
              if (a.separation != b.separation) return a.separation < b.separation;
              return a.triangle < b.triangle;
            });
  if (q.shadowed) {
    // Every candidate that blocks p (only those with separation 0 can), the first one first.
    q.blockers.push_back(q.first_blocker);
    for (const BandCandidate& candidate : candidates) {
      if (candidate.separation != 0.0) break;
      if (candidate.triangle != q.first_blocker.triangle && blocks(q, candidate, at_p))
        q.blockers.push_back(candidate);
    }
  }

  if (!with_exponent) {
    if (!answer_constant_on_cube(q, class_length_)) truth.band = BandClass::ambiguous;
    return truth;
  }
  const std::size_t level = first_changing_length(q, level_lengths_);
  truth.robust_exponent = std::int8_t(band_min_exponent - 1 + int(level));
  // At eps_rel, the largest cube decides (it holds every smaller one).
  bool robust = true;
  if (class_from_exponent_)
    robust = truth.robust_exponent >= class_exponent_;
  else if (!class_lengths_.empty())
    robust = answer_constant_on_cube(q, class_lengths_.back());
  truth.band = !robust      ? BandClass::ambiguous
               : q.shadowed ? BandClass::robust_shadowed
                            : BandClass::robust_lit;
  return truth;
}

}  // namespace shadowcts
