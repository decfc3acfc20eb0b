#pragma once
// Embree 3 shadow rays as a peer implementation: one robust-mode occlusion ray per regular
// sample, traced in packets of 16 (shadow_ray_packets.h), without the band. The baseline a user
// would otherwise pick on the CPU.
#include <memory>

#include "shadowcts/algorithm.h"
#include "shadowcts/embree_scene.h"

namespace shadowcts {

// Embree intersects in float32. Its robust-mode (Pluecker) ray/triangle test forms products of
// three lengths: S^3 for the hit distance's numerator, S^2 |d| for the edge tests and the
// denominator, with S the case scale (Case::scale(): vertices relative to the ray origin and the
// segment to a point light are at most a few S long) and d the ray direction (the segment to a
// point light, or a directional light's direction vector as given). A robust sample is decided by
// differences down to 2^-24 of such a product (the band resolves moves down to the case's float32
// resolution 2^-24 S); they keep float32's 24-bit precision only while normal (>= 2^-126), and the
// largest product (below 2^9 S^3) must stay finite (< 2^128). Hence 2^-102 <= S^3 <= 2^117 and the
// same for S^2 |d|: the algorithm answers NotSupported, saying so, outside
// 2^embree_min_scale_exponent <= S <= 2^embree_max_scale_exponent, and for directional lights
// with S^2 |d|_inf outside [2^-102, 2^117]. (Fuzzed: it leaks from S ~ 2^-43 and shadows falsely
// from S ~ 2^42 on.)
// (The two exponents are defined beside EmbreeScene, whose cases beyond them go into Embree
// scaled by a power of two: the oracles and the view samples use that, this peer does not.)

// id "embree", backend "embree", variants {"robust"}.
std::unique_ptr<Algorithm> make_embree_hard_shadow();

}  // namespace shadowcts
