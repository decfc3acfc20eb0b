// libFuzzer target: shared-edge watertightness. The bytes drive the watertight generator
// (fixtures/fuzz/watertight_generator.cpp): closed fans, bipyramids, tessellated boxes and
// T-junctions with dyadic vertices (one case in four rotated off the lattice), each triangle's
// vertex list starting at another corner, samples aimed through shared edges and vertices.
// Every registered algorithm must agree with the exact oracle on every robust sample, apart from
// Embree's documented limits the generator reports (T-junctions, rays through shared vertices).
// Violations are shrunk and written as reproducers (support/conformance_check.h).
#include <cstddef>
#include <cstdint>

#include <fuzzer/FuzzedDataProvider.h>

#include "fixtures/fuzz/fuzz_generators.h"
#include "support/conformance_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  const GeneratedCase generated = watertight_case(in);
  check_every_algorithm(generated.sample_case, "fuzz_watertight", generated.known_limits);
  return 0;
}
