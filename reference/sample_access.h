#pragma once
// The regular samples as shared culling tests read them, from either form a backend holds: every
// view sample (the reference's), or the prepared scene's compacted arrays (the ports', a
// twentieth of the bytes). Both give the same samples in the same order.
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct ViewSampleAccess {
  const ViewSamples& samples;
  std::size_t size() const { return samples.samples.size(); }
  bool regular(std::size_t i) const {
    return samples.samples[i].sample_class == SampleClass::regular;
  }
  glm::vec3 position(std::size_t i) const { return samples.samples[i].position; }
  std::uint32_t receiver(std::size_t i) const { return samples.samples[i].receiver; }
};

struct RegularSampleAccess {
  const RegularSamples& samples;
  std::size_t size() const { return samples.size(); }
  bool regular(std::size_t) const { return true; }
  glm::vec3 position(std::size_t i) const { return samples.position(i); }
  std::uint32_t receiver(std::size_t i) const { return samples.receiver[i]; }
};

}  // namespace shadowcts
