#pragma once
// `shadowcts export`: what an engine needs to render a case's frame: DIR/scene.glb (the caster
// meshes, glTF 2.0 with KHR_lights_punctual), DIR/receivers.glb when the case has meshes that
// cast no shadow, DIR/case.json (a manifest that loads back to the same triangles, bit for bit,
// with the camera and lights) and DIR/gbuffer.exr (the view samples of that manifest: the
// camera's, or the case's own where it places them, as the fuzz cases do).
#include <iosfwd>
#include <optional>
#include <string>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Writes into `dir` (created; must be new or empty) and loads it back to check that it gives
// the case and its samples bit for bit (std::logic_error otherwise; light directions are
// written as the loader's normalization leaves them). `samples`: the case's own view samples
// (width x height of its camera); absent: one per pixel of its camera. Throws InputError /
// UsageError before writing when the case or the folder is unusable, OutputError when a file
// cannot be written; on any error nothing is left.
void export_case(const Case& c, const std::optional<ViewSamples>& samples, const std::string& dir,
                 std::ostream& out);

}  // namespace shadowcts
