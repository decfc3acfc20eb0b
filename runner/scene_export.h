#pragma once
// `shadowcts export`: what an engine needs to render a case's frame: DIR/scene.glb (the caster
// meshes, glTF 2.0 with KHR_lights_punctual), DIR/receivers.glb when the case has meshes that
// cast no shadow, DIR/case.json (a manifest that loads back to the same triangles, bit for bit,
// with the camera and lights) and DIR/gbuffer.exr (the view samples of that manifest).
#include <iosfwd>
#include <string>

#include "shadowcts/case.h"

namespace shadowcts {

// Writes into `dir` (created; must be new or empty). Throws InputError / UsageError before
// writing when the case or the folder is unusable, OutputError when a file cannot be written.
void export_case(const Case& c, const std::string& dir, std::ostream& out);

}  // namespace shadowcts
