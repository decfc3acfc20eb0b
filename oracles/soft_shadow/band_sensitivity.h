#pragma once
// How much one caster triangle's share of the disk can change when the sample moves inside the
// ambiguity band: the soft-shadow oracle sums this over the triangles near the light cone to bound
// |f(p') - f(p)| (docs/soft-shadow-oracle.md, "Band sensitivity").
//
// Let the sample move by delta (|delta| <= move). A triangle point b at distance z from the moved
// sample along d, projecting into the unit disk, moves in disk units by at most
//   m = move (1 + tan a) / (tan a ((r - move) cos a - move)),   r = distance from p to the triangle
// (z >= (r - move) cos a inside the cone). A disk point can change its coverage only within m of
// the boundary of the unmoved projection K, inside the disk of radius 1 + m; that band has area at
// most 2 m L + pi m^2, L the length of the boundary of K in that disk. Divided by the disk's area
// pi.
#include <array>

#include <glm/vec3.hpp>

#include "oracles/soft_shadow/light_cone_bvh.h"
#include "oracles/soft_shadow/sun_disk_projection.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Upper bound on the change of area(K ∩ disk) / pi for moves of p up to `move` (Euclidean), given a
// lower bound `distance` on the distance from p to the triangle. Returns 1 where it cannot bound it
// (the triangle is within about `move` of p, or the bound exceeds 1).
double triangle_band_sensitivity(const SunDiskFrame& frame, const glm::dvec3& p,
                                 const std::array<glm::dvec3, 3>& v, double distance, double move);

// What caster triangle v adds to the band sensitivity of the sample at p: its
// triangle_band_sensitivity where it comes within `move` of the light cone, else 0. angle: the
// smallest angle between the cone's axis and a direction from p into the triangle
// (angle_to_triangle).
double caster_band_sensitivity(const SunDiskFrame& frame, const glm::dvec3& p,
                               const std::array<glm::dvec3, 3>& v, double angle, double move);

// The band sensitivity of one view sample: the sum over the casters near its light cone (all but
// its receiver), at most 1. The exact oracle computes it in the pass that also gathers the
// projections; the sampled oracle, whose rays cannot tell how close the answer is to changing,
// calls this.
double sample_band_sensitivity(const Case& c, const SunDiskFrame& frame,
                               const LightConeBvh& casters, const ViewSample& sample, double move);

}  // namespace shadowcts
