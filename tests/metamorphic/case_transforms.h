#pragma once
// Exact transforms of a case together with its view samples: every output coordinate is the
// exact image of an input coordinate (powers of two, permutations, sign flips, reordering,
// splitting at representable points), so the transformed inputs are exactly the transformed
// scene, and a robust shadow answer must not change.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::metamorphic {

struct CaseWithSamples {
  Case c;
  ViewSamples samples;
};

// Every coordinate (triangles, samples, camera, near/far, point light, ranged lights) times 2^k.
CaseWithSamples scale_by_power_of_two(const CaseWithSamples& in, int k);

// x' = (sign[0] x[axis[0]], sign[1] x[axis[1]], sign[2] x[axis[2]]) for positions, normals and
// directions. A mirroring map reverses each triangle's vertex order so that winding (closed
// meshes' outward orientation) is kept.
CaseWithSamples permute_axes(const CaseWithSamples& in, const int axis[3], const float sign[3]);

// After a mirroring permute_axes the camera's right vector (a cross product) turns round, so the
// image turns over left to right: the sample seen at pixel (x, y) is now seen at (W - 1 - x, y).
// Moves each sample to that pixel (the row-major order and pixel_x), as the camera would cast it;
// `new_index` receives, per sample of the input, its index in the result.
CaseWithSamples turn_image_over(const CaseWithSamples& in, std::vector<std::size_t>& new_index);

// (v0, v1, v2) -> (v1, v2, v0): same triangle, same winding.
CaseWithSamples rotate_vertex_order(const CaseWithSamples& in);

// (v0, v1, v2) -> (v0, v2, v1) and every mesh marked open, so that no algorithm culls by
// orientation (the relation is stated with front-face culling off).
CaseWithSamples flip_winding(const CaseWithSamples& in);

// Every mesh marked open (the reference to compare flip_winding against).
CaseWithSamples open_meshes(const CaseWithSamples& in);

// Triangles in a pseudo-random order (deterministic for the seed); receivers remapped.
CaseWithSamples shuffle_triangles(const CaseWithSamples& in, std::uint64_t seed);

// Ranged lights in a pseudo-random order (deterministic for the seed); `old_index` receives, per
// light of the result, its index in the input.
CaseWithSamples shuffle_lights(const CaseWithSamples& in, std::uint64_t seed,
                               std::vector<std::uint32_t>& old_index);

// Splits every triangle that receives no sample at an exactly representable point of its longest
// edge (the midpoint, else a quarter point, else the next edge) into two triangles sharing the
// edge from that point to the opposite vertex; each keeps the winding. `split_count` receives the
// number of triangles split. Receiver ids are remapped.
CaseWithSamples split_triangles(const CaseWithSamples& in, std::size_t& split_count);

}  // namespace shadowcts::metamorphic
