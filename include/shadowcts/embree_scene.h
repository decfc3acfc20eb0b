#pragma once
// An Embree 3 scene in robust mode over a chosen subset of a case's triangles: one triangle
// geometry (geomID 0), with maps between Embree's primID and the index into Case::triangles.
#include <cstdint>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>

namespace shadowcts {

struct Case;

class EmbreeScene {
 public:
  static constexpr std::uint32_t absent = std::numeric_limits<std::uint32_t>::max();

  // `triangles`: indices into c.triangles, in primID order. `occluded_filter`, if given, is the
  // geometry's occlusion filter function. Throws std::runtime_error when Embree fails.
  EmbreeScene(const Case& c, std::vector<std::uint32_t> triangles,
              RTCFilterFunctionN occluded_filter = nullptr);
  // Every triangle of the case; primID == triangle index.
  explicit EmbreeScene(const Case& c);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  std::uint32_t triangle_of_primitive(std::uint32_t primitive) const {
    return triangles_[primitive];
  }
  // `absent` when the triangle is not in the scene (or the index is out of range).
  std::uint32_t primitive_of_triangle(std::uint32_t triangle) const {
    return triangle < primitives_.size() ? primitives_[triangle] : absent;
  }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::uint32_t> triangles_;   // by primID
  std::vector<std::uint32_t> primitives_;  // by triangle index
};

}  // namespace shadowcts
