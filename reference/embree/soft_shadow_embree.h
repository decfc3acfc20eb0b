#pragma once
// Embree 3 soft shadows by ray sampling: the baseline a user would otherwise pick for a sun disk.
// From each regular sample, robust-mode occlusion rays towards N stratified points of the disk in
// the gnomonic plane (DESIGN.md, "Soft shadow"); the answer is the fraction of rays that reach the
// sky. A caster hit counts only under the receiver half-space rule, decided for each ray's own
// direction with the shared geometry (reference/sample_half_space.h), as the hard-shadow Embree
// peer decides it for its one ray. Independent of the oracles' ray tracers (oracles/): judged by
// the exact disk oracle like every soft-shadow record.
#include <cstdint>
#include <memory>
#include <string>

#include <glm/vec2.hpp>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "embree_soft", backend "embree", output soft_shadow, sun disks only. Variants rays16
// (default), rays64, rays256: N rays per sample, one per stratum of a sqrt(N) x sqrt(N) grid.
// Counters, in order: rays, occluded_rays.
std::unique_ptr<Algorithm> make_embree_soft_shadow();

// The number of rays of a variant; throws std::invalid_argument for an unknown one.
std::uint32_t embree_soft_rays(const std::string& variant);

// The error budget of a variant (docs/soft-shadow-budgets.md), from its N alone. Throws
// std::invalid_argument for an unknown variant.
SoftErrorBudget embree_soft_error_budget(const std::string& variant);

// Point `stratum` (row-major in the k x k grid, k * k = rays) of the sample with pixel index
// `pixel` on the unit disk: the stratum jittered by a generator seeded with (seed, pixel), mapped
// to the disk by the equal-area concentric map, so every stratum covers area pi / rays of it.
// Deterministic; exposed for the tests.
glm::dvec2 embree_soft_disk_point(std::uint64_t seed, std::uint32_t pixel, std::uint32_t rays,
                                  std::uint32_t stratum);

}  // namespace shadowcts
