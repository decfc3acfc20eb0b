#pragma once
// Closedness of a triangle mesh: the one definition that loaders (Mesh::closed, the planner's
// front-face culling) and the stencil baseline (its front-face rule) share.
#include <cstdint>
#include <span>

#include "shadowcts/case.h"

namespace shadowcts {

// True iff the triangles form closed, consistently oriented surfaces, decided on exact float
// positions (-0 and +0 are the same point; the file's vertex indexing plays no part): every
// directed edge a -> b of a triangle occurs exactly once, and its reverse b -> a occurs exactly
// once too. Triangles with two corners at the same position have no area, cast no shadow and are
// ignored; with nothing left the answer is false. A non-manifold edge (three or more triangles,
// or a face duplicated in either orientation on a closed surface) is not closed; surfaces that
// only touch at a vertex are. False is always the safe answer: it only disables front-face
// culling.
bool is_closed_surface(std::span<const Triangle> triangles);

// The same for the subset triangles[i] of `triangles`, i in `subset`.
bool is_closed_surface(std::span<const Triangle> triangles, std::span<const std::uint32_t> subset);

}  // namespace shadowcts
