#pragma once
// Stencil shadow volumes in software, the classic baseline with the eye-in-shadow problem: per
// view sample, the signed crossings of shadow-volume faces (silhouette.h, shadow_volume.h) along
// the sample's eye line are counted (volume_counting.h) with exact predicates; a non-zero count
// means shadowed.
//  - "zpass": counts from the eye to the sample, assuming the eye is lit (Heidmann 1991). Wrong
//    wherever the eye is inside a shadow volume.
//  - "zfail": counts from beyond the sample, with light and dark caps (Carmack's reverse / Everitt
//    and Kilgard 2002). Robust wherever the eye is.
// Open caster meshes (ground planes, leaves) get one capped volume per triangle (merged along
// shared edges); no case is declined for them. The receiver half-space rule removes, from a
// shadowed count, the caps it rejects for the sample (receiver_rule.h).
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "stencil", backend "reference", variants "zfail" (default) and "zpass". Counters:
// silhouette_edges (side quads built), caps (light caps), quads_tested and caps_tested (sample x
// face crossing tests after screen binning, and of the own volumes of the receiver and of the
// caps the rule asks about), rule_samples (shadowed counts whose sample the rule was asked about)
// and rule_candidates (caps near those samples' segments that it sorted), light_on_caster_samples.
// Per-sample counter: faces_tested.
std::unique_ptr<Algorithm> make_stencil();

}  // namespace shadowcts
