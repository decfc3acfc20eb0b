#pragma once
// Shadow maps, the de-facto standard baseline: a light-space depth map rasterized in software
// (reference/shadowmap/rasterizer.h), a cube map of six faces for a point light and one
// orthographic map fitted to the view samples for a directional light (a sun disk reaches
// hard-shadow algorithms as its centre direction), then one nearest-texel depth comparison per
// sample with a constant and a slope-scaled bias (bias.h). Approximate by design: its robust
// mismatches against the exact oracle are its error figures (QualityWarning, not Fail).
//
// Memory: the cube faces are rasterized and looked up one at a time and only faces that hold a
// sample are drawn, so an 8k map needs one 8192^2 float face (256 MiB) at a time, not 6 of them.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "shadowmap", backend "reference", variants "1k", "2k", "4k", "8k" (map side 1024 ... 8192
// texels, default bias) and "2k+nobias" (no bias at all: shows shadow acne). Counters:
// texels_written (depth-test passes at the texels the samples read: each map keeps only those,
// whose depths are the full map's), triangles_rasterized (caster x map pairs left after
// clipping), depth_maps (maps drawn).
std::unique_ptr<Algorithm> make_shadowmap();

}  // namespace shadowcts
