#pragma once
// simd `ptsv`: the reference's Sintorn 2014 per-triangle shadow volumes (reference/ptsv/), with
// the hierarchy built from a parallel sort of the cluster keys, the child bounds of a node and
// the samples of a leaf tested in Highway lanes (runtime dispatch), and the volumes spread over
// oneTBB node by node (traversal.h), two-pass jobs at the reference's job level. Variants:
// twopass, explicit+planes, implicit (the reference's names and configurations); the keys, the
// nodes, the counters and the mask are the reference's.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"
#include "simd/ptsv/hierarchy.h"

namespace shadowcts {

// id "ptsv", backend "simd".
std::unique_ptr<Algorithm> make_simd_ptsv();

namespace simd::ptsv {

// What run() builds before the traversal, for the tests that diff it against the reference:
// the cluster key of every view sample (ref::no_key for the others) and the hierarchy.
struct Structures {
  std::vector<std::uint32_t> key;
  Hierarchy hierarchy;
};
Structures build_structures(const PreparedScene& scene, const std::string& variant);

}  // namespace simd::ptsv
}  // namespace shadowcts
