#pragma once
// A case by its fixture name, for every command that takes --fixture: a built-in fixture, whose
// samples the camera casts, or a fuzz case `fuzz.<generator>.<seed>.<index>`
// (fixtures/fuzz/fuzz_fixtures.h), which brings its own samples and the limits of peers its
// generator declares.
#include <optional>
#include <string>
#include <vector>

#include "fixtures/fuzz/generated_case.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct NamedCase {
  Case c;
  std::optional<ViewSamples> samples;  // a fuzz case's own; nullopt: cast from the camera
  std::vector<fuzzing::KnownLimit> known_limits;
};

// Throws InputError naming the fixture for an unknown or malformed name.
NamedCase make_named_case(const std::string& name);

}  // namespace shadowcts
