#pragma once
// The 14 moves of the ambiguity band (DESIGN.md): the face centres and the corners of the cube of
// half-width delta around a sample, as unnormalized directions.
#include <array>
#include <cstddef>

#include <glm/vec3.hpp>

namespace shadowcts {

inline const std::array<glm::ivec3, 14> band_moves = {{
    {1, 0, 0},
    {-1, 0, 0},
    {0, 1, 0},
    {0, -1, 0},
    {0, 0, 1},
    {0, 0, -1},  // face centres
    {-1, -1, -1},
    {1, -1, -1},
    {-1, 1, -1},
    {1, 1, -1},  // corners
    {-1, -1, 1},
    {1, -1, 1},
    {-1, 1, 1},
    {1, 1, 1},
}};
inline constexpr std::size_t first_corner_move = 6;

}  // namespace shadowcts
