#pragma once
// Screen-space binning of the volume faces with a depth bound per listing: the software
// counterpart of rasterizing them into the stencil buffer with a depth test. Every sample's
// counting line starts at the eye, so a face can only be crossed by samples whose direction from
// the eye falls inside the face's projection, and only at the depths crossing_reach.h allows:
// before the sample for z-pass, beyond it for z-fail (within the face's slack). A face is listed in
// the cells of a grid over the samples' projections that its (conservatively widened) projection,
// clipped to the depths a counted crossing can have, overlaps; each cell's list is sorted by the
// depth bound, so a sample reads only the prefix of faces that can reach its depth. Faces without a
// proven bound (crossing_reach.h: anywhere) are listed everywhere, never-counted ones nowhere.
//
// Why depth and clipping: a face reaching behind the eye's plane (the volumes of casters near the
// camera, extruded past it) has no bounded projection, and a long side quad covers much of the
// screen; listing those for every sample made gate_house.1M at 1080p take over 20 minutes.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/stencil/crossing_reach.h"
#include "reference/stencil/shadow_volume.h"
#include "reference/stencil/volume_counting.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::stencil {

// The largest |p - e| over the regular samples: crossing_reach's sample_reach.
double sample_reach(const glm::dvec3& eye, const ViewSamples& samples);

class ViewGrid {
 public:
  // `reaches[f]` is crossing_reach of faces[f] for `mode` and the camera's eye.
  ViewGrid(const Camera& camera, const ViewSamples& samples, const std::vector<VolumeFace>& faces,
           const std::vector<CrossingReach>& reaches, CountingMode mode);

  // Every face whose crossing count can be non-zero for `sample`, a regular sample of the grid's
  // view samples: its cell's listings that reach its depth, then the faces listed everywhere.
  // Samples behind the eye's plane (not from this camera) get every face.
  template <class Visit>
  void for_each_candidate(const glm::dvec3& sample, Visit visit) const {
    const glm::dvec3 q = project(sample);
    const std::int64_t cell = cell_of(q);
    if (cell < 0) {
      for (std::uint32_t f = 0; f < face_count_; ++f) visit(f);
      return;
    }
    const float bound = key_bound(q.z);
    const auto end = offsets_[std::size_t(cell) + 1];
    for (std::uint32_t k = offsets_[std::size_t(cell)]; k < end && keys_[k] <= bound; ++k)
      if (outlines_[cell_faces_[k]].may_contain(q.x, q.y)) visit(cell_faces_[k]);
    for (std::uint32_t f : everywhere_) visit(f);
  }

  // A listed face's projection (clipped as binned), widened by its margin: a sample whose line
  // crosses the face projects into it. Checking it costs a few multiplications, the exact
  // crossing test far more, and a cell lists many thin quads that miss most of its samples.
  struct Outline {
    struct Polygon {
      double x[4] = {}, y[4] = {};
      int n = 0;
      int orientation = 0;            // sign of the area; 0: too thin to tell, contains everything
      double nx[4] = {}, ny[4] = {};  // edge i's normal towards the inside, set with orientation
    };
    Polygon part[2];  // a quad's two triangles
    int parts = 0;
    double margin = 0.0;
    bool may_contain(double x, double y) const;
  };

  std::size_t listings() const { return cell_faces_.size(); }
  std::size_t everywhere() const { return everywhere_.size(); }

 private:
  glm::dvec3 project(const glm::dvec3& world) const;  // (x/z, y/z, z)
  std::int64_t cell_of(const glm::dvec3& projected) const;
  // Listings with key <= key_bound(depth) reach a sample at that depth.
  float key_bound(double depth) const;

  CountingMode mode_;
  glm::dvec3 eye_, right_, up_, forward_;
  double lo_[2] = {0, 0}, cell_size_[2] = {1, 1};
  std::uint32_t cells_ = 1;  // per side
  std::uint32_t face_count_ = 0;
  std::vector<std::uint32_t> offsets_, cell_faces_, everywhere_;
  std::vector<float> keys_;        // per listing, ascending within a cell
  std::vector<Outline> outlines_;  // per face (listed ones)
};

}  // namespace shadowcts::stencil
