#pragma once
// Reproducers (of the fuzz targets and of `shadowcts certify --profile fuzz`): a case with explicit
// view samples written as files that `shadowcts run --case` replays bit for bit: a JSON case
// manifest, one glTF file per run of consecutive triangles of one mesh (float32 positions in a
// binary buffer, identity transform, so the loader reads back the very same floats in the same
// order) and an EXR G-buffer holding the samples.
#include <string>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Writes the reproducer into `folder` (created if needed) and returns the manifest's path.
// The samples must be width x height = camera.width x camera.height; the case's light and spot
// directions must be manifest_stable_direction() of themselves (shadowcts/manifest_direction.h:
// the manifest normalizes them), and each mesh closed exactly when is_closed_surface says so (the
// loader decides it so).
std::string write_reproducer(const std::string& folder, const Case& c, const ViewSamples& samples);

}  // namespace shadowcts
