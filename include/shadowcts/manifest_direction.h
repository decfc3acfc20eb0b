#pragma once
// Directions as case manifests give them (docs/case-manifest.md: light and spot directions):
// what a written vector loads as, and the directions that load back as themselves, which a case
// written to files must use to replay bit for bit.
#include <glm/vec3.hpp>

namespace shadowcts {

// The unit direction a manifest's vector v loads as: v divided by its largest |component| in
// double (its length can neither overflow nor underflow), normalized, rounded to float. v must
// not be zero.
glm::vec3 manifest_direction(const glm::dvec3& v);

// A direction within a few ulps of d's manifest_direction that manifest_direction leaves
// unchanged: the iteration's fixed point, or, where the iteration alternates between floats (about
// one direction in 1,600), the first fixed point among the floats a few ulps around it.
glm::vec3 manifest_stable_direction(const glm::vec3& d);

}  // namespace shadowcts
