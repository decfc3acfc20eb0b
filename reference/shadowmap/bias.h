#pragma once
// Depth bias of the shadow-map comparison, in texels of the map at the sample, so that it (and the
// light leaking it causes at contact points) shrinks with the resolution like the aliasing does.
//
//   bias = texel_size(p) * (constant_texels + slope_texels * min(tan(theta), max_tan))
//
// theta is the angle between the receiver's normal and the direction to the light. Why these
// values: a sample is compared against the depth at the nearest texel centre, up to half a texel
// diagonal (0.71 texel) away on its own surface, across which a surface tilted by theta changes
// depth by up to 0.71 * tan(theta) texels on axis and about twice that near cube-face corners
// (slope_texels = 1.5 covers both); constant_texels = 1 absorbs the 1/256-texel vertex snapping and
// the float rounding of stored depths with a wide margin; tan(theta) is clamped at 10 (84 degrees),
// beyond which surfaces are so grazing that a larger bias only moves shadows away.
namespace shadowcts::shadowmap {

struct DepthBias {
  double constant_texels = 1.0;
  double slope_texels = 1.5;
  double max_tan = 10.0;
};

inline constexpr DepthBias no_bias{0.0, 0.0, 0.0};

// cos_theta: |normal . unit direction to the light|, in [0, 1].
double depth_bias(const DepthBias& bias, double texel_size, double cos_theta);

}  // namespace shadowcts::shadowmap
