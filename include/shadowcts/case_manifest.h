#pragma once
// JSON case manifests: a scene file or a procedural generator, camera, light(s), parameters.
#include <string>

#include "shadowcts/case.h"

namespace shadowcts {

// Loads and validates a manifest; relative scene paths resolve against the manifest's folder.
// Throws InputError naming the file and the JSON element.
Case load_case_manifest(const std::string& path);

}  // namespace shadowcts
