#pragma once
// Built-in fixtures: procedural generators scalable by triangle count, and real models from
// Debian's assimp-testmodels placed over a ground plane.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"

namespace shadowcts {

struct FixtureGenerator {
  std::string name;     // e.g. "ground_blockers"
  std::string summary;  // one line for `shadowcts list`
  bool scalable;        // procedural: honours the triangle target; models: fixed size
};

const std::vector<FixtureGenerator>& fixture_generators();

// Builds generator `generator` with about `target_triangles` triangles (procedural generators;
// the result is within a factor 2 of the target), deterministic for the seed. The case name is
// "<generator>.<size>", e.g. "gate_house.20k". Throws InputError for unknown names or impossible
// sizes (0, or more than 100 M).
Case make_fixture(const std::string& generator, std::uint64_t target_triangles,
                  std::uint64_t seed = 1);

// Parses "<generator>.<size>" (size: 500, 20k, 1M) or a bare model generator name.
Case make_fixture(const std::string& fixture_name);

// The default set a bare `shadowcts run` uses: every light kind covered, under a minute in all.
std::vector<std::string> default_fixtures();

}  // namespace shadowcts
