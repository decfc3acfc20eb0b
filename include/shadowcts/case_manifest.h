#pragma once
// JSON case manifests: a scene file or a procedural generator, camera, light(s), parameters.
#include <string>

#include "shadowcts/case.h"
#include "shadowcts/gbuffer_format.h"

namespace shadowcts {

// Loads and validates a manifest; relative scene paths resolve against the manifest's folder.
// Throws InputError naming the file and the JSON element.
Case load_case_manifest(const std::string& path);

// The same, and how the case's G-buffer (Case::gbuffer_path) is laid out: the manifest's
// "gbuffer" as an object; a plain file name is GBufferFormat{} (world positions, triangle ids).
Case load_case_manifest(const std::string& path, GBufferFormat& gbuffer_format);

}  // namespace shadowcts
