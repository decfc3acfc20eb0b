#pragma once
// Which closed caster meshes may drop the faces turned towards the light (the papers' front-face
// culling). Dropping one orientation of a closed surface is only safe when every shadow segment
// crosses it as often inwards as outwards: when neither the sample nor the light lies inside the
// solid. A segment from a sample inside a closed mesh leaves it only through faces turned towards
// the light — exactly the ones culled (found by the watertightness fuzzer).
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Per mesh, the box of its triangles' vertices (an empty mesh's is empty: +inf to -inf).
struct MeshBoxes {
  std::vector<glm::vec3> lo, hi;
  explicit MeshBoxes(std::size_t n);
  // Float comparisons of float coordinates are exact: "inside the box" is decided exactly.
  bool holds(std::size_t m, const glm::vec3& p) const {
    return p.x >= lo[m].x && p.x <= hi[m].x && p.y >= lo[m].y && p.y <= hi[m].y && p.z >= lo[m].z &&
           p.z <= hi[m].z;
  }
};

// The boxes of c's meshes, on oneTBB threads (the caller's arena).
MeshBoxes mesh_boxes(const Case& c);

// Per mesh: closed, a caster, and its bounding box (closed) holds no regular sample and no point
// light, so no sample or light can be inside the solid.
std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples);
// The same from the prepared scene's regular samples (the same answer).
std::vector<bool> meshes_safe_for_face_culling(const Case& c, const RegularSamples& samples);

}  // namespace shadowcts
