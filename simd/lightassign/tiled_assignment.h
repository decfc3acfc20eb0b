#pragma once
// Tiled light assignment (Paper I), the port of reference/lightassign/tiled_assignment.h: the same
// tiles, sub-frusta, boxes and candidate lists (lights inserted into the tiles their bounding
// rectangle covers, in light order), the candidates of a tile tested against its planes and box
// in Highway lanes, tiles spread over oneTBB.
#include <cstdint>

#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd {

AlgorithmOutput assign_lights_tiled(const PreparedScene& scene, std::uint32_t tile_size);

}  // namespace shadowcts::simd
