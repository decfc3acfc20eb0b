#pragma once
// Exact signs for the shadow-volume counting. Every decision of the stencil baseline is the sign
// of a 3x3 determinant whose columns are differences of double points (float inputs, and extruded
// volume vertices computed once in double): evaluated in double with Shewchuk's static error bound
// for orient3d (the same shape: three rounded differences, then the determinant), and, only when
// that bound cannot decide, again in exact rationals. The signs are therefore exact for the
// doubles they are given, and a determinant and its column-swapped twin always have opposite
// signs, which is what makes the crossing counts consistent on shared edges.
#include <glm/vec3.hpp>

namespace shadowcts::stencil {

// det[a1 - a0, b1 - b0, c1 - c0] in double, and a bound on the distance of `value` from the exact
// determinant (Shewchuk's orient3d bound doubled, plus the absolute error of underflowing
// products); infinite `error` when an intermediate overflowed.
struct DeterminantEstimate {
  double value = 0.0, error = 0.0;
};
DeterminantEstimate estimate_determinant(const glm::dvec3& a1, const glm::dvec3& a0,
                                         const glm::dvec3& b1, const glm::dvec3& b0,
                                         const glm::dvec3& c1, const glm::dvec3& c0);

// Sign (-1, 0, 1) of det[a1 - a0, b1 - b0, c1 - c0].
int sign_of_determinant(const glm::dvec3& a1, const glm::dvec3& a0, const glm::dvec3& b1,
                        const glm::dvec3& b0, const glm::dvec3& c1, const glm::dvec3& c0);

// Sign of det[q - p, r - p, s - p]: positive when s lies on the side of the plane (p, q, r) that
// its normal (q - p) x (r - p) points to.
inline int orientation(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r,
                       const glm::dvec3& s) {
  return sign_of_determinant(q, p, r, p, s, p);
}

// On which side of the directed edge a -> b the line through l0 and l1 passes: the sign of
// det[l1 - l0, a - l0, b - l0] (a Pluecker side product). Ties (the line meets the edge's line)
// are broken by simulation of simplicity: the line is translated by eps * e_i + eps^2 * e_j, with
// e_i, e_j the two axes other than the line's largest direction component, which adds
// eps * det[w, e_i, a - b] + eps^2 * det[w, e_j, a - b] (w = l1 - l0). That is one real
// perturbation of the line, so the answers of all edges stay simultaneously realizable: a line
// through a shared edge or vertex crosses exactly one of the faces around it. Zero only when the
// edge is parallel to the line (its faces are then edge-on to the line and never crossed), and
// always edge_side(l0, l1, b, a) == -edge_side(l0, l1, a, b).
int edge_side(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& a, const glm::dvec3& b);

// edge_side(l0, l1, a, b) for an edge whose end b = a + s (u1 - u0), s > 0, is known only rounded
// (a side quad's extruded vertex): the same sign and the same simulated tie, from a and the exact
// direction u1 - u0, so the edge is exactly the line the rounded b only approximates.
int edge_side_along(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& a,
                    const glm::dvec3& u1, const glm::dvec3& u0);

// edge_side(l0, l1, a, b) for an edge between two extruded points, both known only rounded: a is
// exactly origin + factor (minuend - subtrahend) (Extrusion::Exact) and b - a a positive multiple
// of u1 - u0. The sign of the exact edge, with edge_side_along's simulated tie, so that faces
// sharing the edge (a dark cap and its neighbour or its side quad) see one line, and a counting
// line in the plane through the light and the edge's original (the eye at the light, the sample
// on the original) passes it on the side the original's tie chose.
int extruded_edge_side(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& origin,
                       const glm::dvec3& minuend, const glm::dvec3& subtrahend, double factor,
                       const glm::dvec3& u1, const glm::dvec3& u0);

}  // namespace shadowcts::stencil
