#pragma once
// The six faces of a point light's cube map and the face that sees a given direction.
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/shadowmap/light_view.h"

namespace shadowcts::shadowmap {

inline constexpr int cube_faces = 6;

// Face order +x, -x, +y, -y, +z, -z. Each face is a 90-degree perspective view from the light.
LightView cube_face_view(const glm::dvec3& light, int face, std::uint32_t resolution, double near);

// The face whose frustum holds direction d (from the light): its largest |component|, ties going
// to x before y before z, so that every direction has exactly one face.
int cube_face_of(const glm::dvec3& d);

}  // namespace shadowcts::shadowmap
