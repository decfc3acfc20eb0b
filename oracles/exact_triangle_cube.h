#pragma once
// Does a closed triangle meet the closed axis-aligned cube of half-width h around a point? The
// question the receiver search asks (receiver_search.h): the cube is the ambiguity band's
// (DESIGN.md), so a triangle meets it exactly when some move of the sample within the band lies
// on the triangle. Exact for float vertices and double centre and half-width: CGAL's exact
// predicates on the cube's bounds, in doubles where p +- h is a double and in exact rationals
// where it is not.
#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

bool triangle_meets_cube(const Triangle& t, const glm::dvec3& centre, double half_width);

}  // namespace shadowcts
