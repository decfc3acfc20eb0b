#pragma once
// What a case written to files (`shadowcts export`, a reproducer) must load back as, so that
// `shadowcts run --case` on the files judges the very case that was written.
#include <string>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// A case with its view samples, as the runner loads a manifest: the manifest, then its G-buffer
// (world positions and triangle ids), classified by the case's light.
struct LoadedCase {
  Case c;
  ViewSamples samples;
};
LoadedCase load_case_with_gbuffer(const std::string& manifest);

// The first difference between what was written and what loaded, "" when there is none:
// triangles in order (vertices bit for bit, their mesh's caster and closed flags), the shadow
// light, the ranged lights, the camera, the parameters and every sample (position, normal,
// receiver, pixel, class). Mesh indices and names may differ (an export regroups meshes).
std::string first_difference(const Case& written, const ViewSamples& written_samples,
                             const LoadedCase& loaded);

}  // namespace shadowcts
