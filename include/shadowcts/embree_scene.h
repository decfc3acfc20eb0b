#pragma once
// An Embree 3 scene over a case's triangles (robust mode): one triangle geometry (geomID 0)
// whose primID equals the index into Case::triangles.
#include <embree3/rtcore.h>

namespace shadowcts {

struct Case;

class EmbreeScene {
 public:
  enum class Contents { all_triangles };

  EmbreeScene(const Case& c, Contents contents);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  RTCDevice device() const { return device_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace shadowcts
