#pragma once
// The receiver half-space rule (DESIGN.md) of one view sample, for the reference algorithms and
// the host side of the device backends: its receiver's plane against the case's shadow light.
#include "shadowcts/case.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Without a receiver there is no plane, and every caster counts.
geometry::ReceiverHalfSpace sample_half_space(const Case& c, const HardShadowLight& light,
                                              const ViewSample& sample);

}  // namespace shadowcts
