#pragma once
// Embree 3 shadow rays as a peer implementation: one robust-mode occlusion ray per regular
// sample (the fast oracle's ray tracer, oracles/embree_shadow_rays.h), without the band. The
// baseline a user would otherwise pick on the CPU.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "embree", backend "embree", variants {"robust"}.
std::unique_ptr<Algorithm> make_embree_hard_shadow();

}  // namespace shadowcts
