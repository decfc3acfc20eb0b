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

// Procedural: ground_blockers, closed_shapes, gate_house, foliage, shared_edges, many_lights.
// Models (fixed size, from /usr/share/assimp/models or $SHADOWCTS_ASSIMP_MODELS):
// model.2cylinder_engine, model.spider, model.wuson, model.sphere_with_hole.
const std::vector<FixtureGenerator>& fixture_generators();

// Builds generator `generator` with about `target_triangles` triangles (procedural generators;
// the result is within a factor 2 of the target), deterministic for the seed (the same bytes
// on every platform: std::mt19937_64 with our own distributions; the regular scenes gate_house
// and shared_edges do not use it). The case name is "<generator>.<size>" with the requested
// target, e.g. "gate_house.20k"; Case::source is "generator:<generator>", and
// Case::parameters.seed is `seed`. Throws InputError for unknown names and impossible sizes
// (0, below the generator's smallest meaningful size, or more than 100 M). Model generators
// ignore the target and the seed; their case name is the generator name, their source the
// model file, and a missing file is an InputError that says to run ci/setup.sh.
Case make_fixture(const std::string& generator, std::uint64_t target_triangles,
                  std::uint64_t seed = 1);

// Parses "<generator>.<size>" (size: 500, 20k, 1M: digits with an optional k or M) or a bare
// model generator name, and builds it with seed 1.
Case make_fixture(const std::string& fixture_name);

// The default set a bare `shadowcts run` uses: every light kind (point, directional, sun disk,
// ranged lights), the watertightness fixture and real models; each at most ~20k triangles and
// 256x256 samples so that exact oracles finish the whole set in under a minute.
std::vector<std::string> default_fixtures();

// The stiff-case suite (`shadowcts run --suite stiff`): fixed cases named "stiff.<trap>", each a
// deliberate numerical trap (fixtures/stiff/); make_fixture() builds them by name.
std::vector<std::string> stiff_fixtures();

}  // namespace shadowcts
