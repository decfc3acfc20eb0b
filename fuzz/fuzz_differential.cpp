// libFuzzer target: differential testing. The bytes drive the differential generator
// (fixtures/fuzz/differential_generator.cpp): random small scenes with samples where the answer
// is closest to changing, or from a 16 x 16 camera. Every registered algorithm against the exact
// oracle; any robust mismatch is shrunk and saved as a reproducer that `shadowcts run --case`
// replays.
#include <cstddef>
#include <cstdint>
#include <optional>

#include <fuzzer/FuzzedDataProvider.h>

#include "fixtures/fuzz/fuzz_generators.h"
#include "support/conformance_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  const std::optional<GeneratedCase> generated = differential_case(in);
  if (generated)
    check_every_algorithm(generated->sample_case, "fuzz_differential", generated->known_limits);
  return 0;
}
