#pragma once
// Screen-space binning of the volume faces, the software counterpart of rasterizing them into the
// stencil buffer: every sample's counting line starts at the eye, so a face can only be crossed by
// samples whose direction from the eye falls inside the face's projection. Faces are listed in the
// cells of a grid over the samples' projections that their (conservatively widened) projected box
// overlaps; faces reaching behind the eye's plane are listed everywhere, faces entirely behind it
// nowhere (the lines only run forward from the eye).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/stencil/shadow_volume.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::stencil {

class ViewGrid {
 public:
  ViewGrid(const Camera& camera, const ViewSamples& samples, const std::vector<VolumeFace>& faces);

  // Faces to test for a sample: its cell's list, then the list of faces seen everywhere. Samples
  // behind the eye's plane (not from this camera) get every face.
  template <class Visit>
  void for_each_candidate(const glm::dvec3& sample, Visit visit) const {
    const std::int64_t cell = cell_of(sample);
    if (cell < 0) {
      for (std::uint32_t f = 0; f < face_count_; ++f) visit(f);
      return;
    }
    for (std::uint32_t k = offsets_[std::size_t(cell)]; k < offsets_[std::size_t(cell) + 1]; ++k)
      visit(cell_faces_[k]);
    for (std::uint32_t f : everywhere_) visit(f);
  }

 private:
  glm::dvec3 project(const glm::dvec3& world) const;  // (x/z, y/z, z)
  std::int64_t cell_of(const glm::dvec3& world) const;

  glm::dvec3 eye_, right_, up_, forward_;
  double lo_[2] = {0, 0}, cell_size_[2] = {1, 1};
  std::uint32_t cells_ = 1;  // per side
  std::uint32_t face_count_ = 0;
  std::vector<std::uint32_t> offsets_, cell_faces_, everywhere_;
};

}  // namespace shadowcts::stencil
