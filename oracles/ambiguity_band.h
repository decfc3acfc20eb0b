#pragma once
// Exact classification of one view sample in the ambiguity band (DESIGN.md, "Tolerance: the
// ambiguity band"; docs/specification.md, "The ambiguity band"): its exact answer, its class at
// the case's eps_rel and its robust_exponent.
//
// A sample is robust at a move length h when the exact answer is the same at every point of the
// closed cube of half-width h around p (which holds the 14 moves of length h and every shorter
// move); the band at eps_rel uses h = eps_rel S (when eps_rel S >= 2^-24 S), and
// robust_exponent the lengths 2^k S, k = -24 ... -10. A cube that is certified constant holds
// every smaller cube, so robustness is monotone in the length.
//
// Under the receiver half-space rule (DESIGN.md) a caster shadows only with its part strictly on
// the light's side of the receiver's plane, which stays fixed while the cube moves p. Casters with
// no vertex on that side are no candidates at all; a straddling caster's shadow volume, triangle
// and edges contain those of its shadowing part, so the tests below stay conservative with the
// whole caster, and the one new boundary piece, the wedge behind the caster's piece in the plane,
// is tested too. Closed pieces stay closed where they lie on the light's side: a caster sharing
// such a piece has points there, so it is a candidate, and near the piece both are unclipped.
//
// The oracle certifies a cube constant only by exact arguments (never by trying moves):
// - lit, cheaply: the candidate set (triangles that may come within the band of the shadow
//   query, with a conservative separation each) holds no triangle nearer than h;
// - lit, exactly: no candidate's shadow volume V_T (convex: the points whose segment to the
//   light, or ray towards it, meets the closed triangle T) meets the cube (ExactCubeQuery);
// - shadowed, cheaply: the 8 corners of the cube, all blocked by one triangle T, put the whole
//   cube inside V_T;
// - shadowed, otherwise: no piece of the shadow boundary that may be exposed meets the cube. The
//   boundary of the union of the V_T lies in the triangles, the wedges behind their edges and the
//   rays behind their vertices. Pieces of edges that another caster covers from the other side,
//   seen from the light, and vertices all round which the casters cover, are no boundary
//   (caster_closure.h: closed fans, DESIGN.md's shared edges, also across T-junctions). If the
//   cube meets none of the remaining pieces, it cannot hold a lit point: it is connected and
//   holds the shadowed p. This is conservative (a triangle or an open wedge inside another
//   caster's shadow makes a sample ambiguous that may not be), never the other way round.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <tbb/collaborative_call_once.h>

#include "oracles/caster_bvh.h"
#include "oracles/caster_closure.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"
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
  PlaneReach reach = PlaneReach::whole;  // against the sample's receiver plane
};

class ExactBandClassifier {
 public:
  // scale: c.scale(), passed in because computing it reads every triangle.
  ExactBandClassifier(const Case& c, double scale, const HardShadowLight& light,
                      const CasterBvh& casters, const ExactShadowPredicate& predicate);

  // The sample must be regular. `candidates` is scratch space, reused between calls. With
  // `with_exponent`, robust_exponent too (candidates within the largest level, 2^-10 S: 64 times
  // as many as tau needs); without, only the answer and the class at eps_rel, and robust_exponent
  // is robust_exponent_unknown. Both give the same answer and class.
  SampleTruth classify(const ViewSample& sample, std::vector<BandCandidate>& candidates,
                       bool with_exponent) const;
  // classify(samples[l], candidates[l], false) for up to CasterBvh::packet_lanes samples at once
  // (neighbours, whose queries visit much the same part of the tree): the same truths.
  void classify_packet(const ViewSample* const* samples, int count,
                       std::vector<BandCandidate>* candidates, SampleTruth* truths) const;

 private:
  struct Query;
  // A query for the sample; its receiver's plane copied from `same_receiver` when that query's
  // receiver is the sample's (neighbours in a packet often share one).
  Query start(const ViewSample& sample, std::vector<BandCandidate>& candidates, bool with_exponent,
              const Query* same_receiver = nullptr) const;
  bool consider(Query& q, std::uint32_t triangle, bool stop_at_first_blocker) const;
  void gather(Query& q, bool stop_at_first_blocker) const;
  std::optional<SampleTruth> settled(Query& q, bool with_exponent) const;
  SampleTruth finish(Query& q, bool with_exponent) const;
  bool cube_in_shadow_of(const Query& q, const BandCandidate& blocker, double delta) const;
  bool blocks(const Query& q, const BandCandidate& candidate, const MovedPoint& x) const;
  std::size_t active_candidates(const Query& q, double delta) const;
  bool answer_constant_on_cube(const Query& q, double delta) const;
  bool boundary_misses(const Query& q, const ExactCubeQuery& cube, std::size_t active) const;
  std::size_t first_changing_length(const Query& q, const std::vector<double>& lengths) const;

  const Case& case_;
  HardShadowLight light_;
  const CasterBvh& casters_;
  const ExactShadowPredicate& predicate_;
  // Built on first use (only shadowed samples that no single blocker certifies need it), by every
  // thread that asks at once.
  const CasterClosure& closure() const;
  mutable tbb::collaborative_once_flag closure_once_;
  mutable std::optional<CasterClosure> closure_;
  double scale_;
  std::vector<double> level_lengths_;  // 2^k S for k = band_min_exponent ... band_max_exponent
  // The band at eps_rel: either read off robust_exponent (eps_rel = 2^e, e in the level range),
  // or decided with its own move lengths (ascending).
  bool class_from_exponent_ = false;
  int class_exponent_ = 0;
  std::vector<double> class_lengths_;
  // The cube that decides the class at eps_rel (when there is one: tau >= 2^-24 S).
  bool has_class_length_ = false;
  double class_length_ = 0.0;
  double largest_move_ = 0.0;  // the largest move of any level and of the class
};

}  // namespace shadowcts
