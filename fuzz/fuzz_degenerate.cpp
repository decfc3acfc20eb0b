// libFuzzer target: degenerate triangles at huge and tiny scales. The bytes drive the degenerate
// generator (fixtures/fuzz/degenerate_generator.cpp): zero-area, sliver and needle triangles at
// scales 2^-60 ... 2^60, point, directional and sun-disk lights. No algorithm may crash, throw or
// answer NaN (soft output: a fraction in [0, 1]); every hard-shadow algorithm must agree with the
// exact oracle on robust samples (zero-area triangles cast no shadow).
#include <cstddef>
#include <cstdint>

#include <fuzzer/FuzzedDataProvider.h>

#include "fixtures/fuzz/fuzz_generators.h"
#include "support/conformance_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  const GeneratedCase generated = degenerate_case(in);
  check_every_algorithm(generated.sample_case, "fuzz_degenerate", generated.known_limits);
  return 0;
}
