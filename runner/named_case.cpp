#include "named_case.h"

#include "fixtures/fuzz/fuzz_fixtures.h"
#include "shadowcts/fixtures.h"

namespace shadowcts {

NamedCase make_named_case(const std::string& name) {
  if (!fuzzing::is_fuzz_case_name(name)) return {make_fixture(name), std::nullopt, {}};
  fuzzing::GeneratedCase generated = fuzzing::make_fuzz_case(name);
  return {std::move(generated.sample_case.c), std::move(generated.sample_case.samples),
          std::move(generated.known_limits)};
}

}  // namespace shadowcts
