#pragma once
// Brute-force hard shadows: every regular sample against every caster triangle with the exact
// predicate of the shared geometry (shadowcts/geometry/exact_segment_triangle.h: orientation signs
// by floating-point expansions, independent of the oracles' CGAL), after an exact test of the
// caster's box against the segment's, and the receiver half-space rule
// (shadowcts/geometry/receiver_half_space.h): a caster counts only where it meets the segment
// strictly on the light's side of the receiver's plane. The definition of the answer, written as
// plainly as possible; its own counters are the number of sample x caster pairs tested and of exact
// predicate calls (casters the rule's orientations exclude before it are not asked).
#include <cstdint>
#include <memory>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/geometry/segment_box.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts {

// The exact decision of one regular sample against every caster, shared by the reference
// algorithm and the host side of the device backends (their near-edge fallback).
class ExactBruteforce {
 public:
  // Throws InputError when the scene has no point or directional light or a receiver id is out
  // of range.
  explicit ExactBruteforce(const PreparedScene& scene);

  // Whether regular sample i of the scene is shadowed; adds the sample x caster pairs it visited
  // and its exact predicate calls.
  bool shadowed(std::size_t i, std::uint64_t& pairs, std::uint64_t& calls) const;

 private:
  struct CasterBox {
    FloatBox box;
    std::uint32_t triangle;
  };
  const PreparedScene& scene_;
  HardShadowLight light_;
  std::vector<CasterBox> casters_;
};

// id "bruteforce", backend "reference", variants {"exact"}.
std::unique_ptr<Algorithm> make_bruteforce_hard_shadow();

}  // namespace shadowcts
