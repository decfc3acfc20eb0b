#pragma once
// Front-face culling (closed_mesh_culling.h) under the receiver half-space rule. Culling is exact
// when the counted part of every shadow segment crosses each culled surface as often inwards as
// outwards. Under the rule that part starts where the segment leaves the far side of the
// receiver's plane, at a point p* that may lie inside a solid standing on the receiver although
// the sample lies outside it: a sample one ulp below a floor, at the base of a box on that floor,
// whose segment enters the box through its bottom face (in the floor's plane: it does not count)
// and leaves it only through the faces turned towards the light, the culled ones.
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::psv {

// `safe` (per mesh, from meshes_safe_for_face_culling) with every mesh switched off whose
// bounding box may hold the p* of a regular sample. p* is bounded in double with a proven error
// margin, so culling is lost only where some p* lies within rounding of a box.
std::vector<bool> culling_clear_of_segment_starts(const Case& c, const ViewSamples& samples,
                                                  const HardShadowLight& light,
                                                  std::vector<bool> safe);
// The same from the prepared scene's regular samples (the same answer).
std::vector<bool> culling_clear_of_segment_starts(const Case& c, const RegularSamples& samples,
                                                  const HardShadowLight& light,
                                                  std::vector<bool> safe);

}  // namespace shadowcts::psv
