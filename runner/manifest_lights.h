#pragma once
// A case's lights as a case manifest states them (docs/case-manifest.md), written so that loading
// the manifest gives back the same floats: fuzz reproducers and `shadowcts export` replay bit for
// bit.
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

// The manifest's "light" object.
nlohmann::ordered_json shadow_light_json(const ShadowLight& light);

// The manifest's "ranged_lights" array.
nlohmann::ordered_json ranged_lights_json(const std::vector<RangedLight>& lights);

}  // namespace shadowcts
