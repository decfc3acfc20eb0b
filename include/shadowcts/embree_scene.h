#pragma once
// An Embree 3 scene in robust mode over a chosen subset of a case's triangles: one triangle
// geometry (geomID 0), with maps between Embree's primID and the index into Case::triangles.
//
// Embree works in float32 and asserts on ray origins beyond about 1.8e18; its products of three
// coordinates (vertices relative to the ray's origin) overflow from magnitudes near 2^42 and its
// tests lose hits below 2^-34. A scene whose magnitude M (the largest absolute coordinate of its
// triangles and of its rays' origins) lies outside [2^embree_min_scale_exponent,
// 2^embree_max_scale_exponent] is therefore put into Embree multiplied by a power of two that
// brings M into [1/2, 1): exact for every coordinate that stays a normal float, so hits,
// barycentrics and the triangles hit are those of the case itself. Rays must be given in the same
// units: to_scene() for points and lengths. M is not the case's scale S: a far point light or a
// far camera that no ray starts from must not shrink the triangles into Embree's denormals.
#include <cstdint>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

namespace shadowcts {

struct Case;

// The scales at which a case goes into Embree unchanged (S = 2^-34 .. 2^39, where the Embree
// peer runs: reference/embree/hard_shadow_embree.h).
inline constexpr int embree_min_scale_exponent = -34;
inline constexpr int embree_max_scale_exponent = 39;

class EmbreeScene {
 public:
  static constexpr std::uint32_t absent = std::numeric_limits<std::uint32_t>::max();

  // `triangles`: indices into c.triangles, in primID order. `occluded_filter`, if given, is the
  // geometry's occlusion filter function. `magnitude`: M above, or 0 for a scene that is never
  // scaled (the Embree peers, which run only inside the range). Throws std::runtime_error when
  // Embree fails.
  EmbreeScene(const Case& c, std::vector<std::uint32_t> triangles,
              RTCFilterFunctionN occluded_filter, double magnitude);
  // Every triangle of the case; primID == triangle index.
  EmbreeScene(const Case& c, double magnitude);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  // A point or a length of the case in the scene's units (times the scene's power of two, rounded
  // to float).
  float to_scene(double value) const { return float(value * factor_); }
  // The power of two of to_scene() (1 inside Embree's range).
  double factor() const { return factor_; }
  glm::vec3 to_scene(const glm::dvec3& point) const {
    return {to_scene(point.x), to_scene(point.y), to_scene(point.z)};
  }
  std::uint32_t triangle_of_primitive(std::uint32_t primitive) const {
    return triangles_[primitive];
  }
  // `absent` when the triangle is not in the scene (or the index is out of range).
  std::uint32_t primitive_of_triangle(std::uint32_t triangle) const {
    return triangle < primitives_.size() ? primitives_[triangle] : absent;
  }

 private:
  double factor_ = 1.0;  // the power of two the case is multiplied by (1 inside Embree's range)
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::uint32_t> triangles_;   // by primID
  std::vector<std::uint32_t> primitives_;  // by triangle index
};

}  // namespace shadowcts
