#pragma once
// Which closed caster meshes may drop the faces turned towards the light (the papers' front-face
// culling). Dropping one orientation of a closed surface is only safe when every shadow segment
// crosses it as often inwards as outwards: when neither the sample nor the light lies inside the
// solid. A segment from a sample inside a closed mesh leaves it only through faces turned towards
// the light — exactly the ones culled (found by the watertightness fuzzer).
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Per mesh: closed, a caster, and its bounding box (closed) holds no regular sample and no point
// light, so no sample or light can be inside the solid.
std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples);

}  // namespace shadowcts
