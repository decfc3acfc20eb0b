#pragma once
// Which caster triangles can reach a sample: meet the shadow segment of some regular sample (from
// the sample to a point light, or the ray towards a directional light). A triangle that meets no
// such segment changes no answer of any hard-shadow algorithm, so dropping it is exact; engines
// cull shadow casters against their receivers for the same reason.
//
// Decided in light space. Every sample is projected along its segment onto a plane (directional:
// a coordinate plane, along the light's direction; point light: the six faces of a cube around
// the light, centrally) where all points of its segment land on one point. A grid over the
// samples' projections keeps, per cell, the lowest sample ("height": towards the light). A
// triangle can meet a segment only where its projection covers the sample's projection, and only
// at a point no lower than that sample, so it is kept iff its projected box (widened by a proven
// bound on the rounding of every projection) covers a cell whose lowest sample is no higher than
// its highest vertex. Everything else is dropped. The converse, samples_reached, finds the
// samples that no kept caster reaches: they are lit without a query.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {

class CasterReach {
 public:
  // Keeps every triangle (no samples to cull against).
  CasterReach() = default;
  // `x`, `y`, `z`: the positions of the regular samples (equal lengths). The light's values are
  // floats held exactly in doubles.
  CasterReach(const HardShadowLight& light, std::span<const float> x, std::span<const float> y,
              std::span<const float> z);

  // false only if no point of the closed triangle abc lies on any sample's segment. Thread-safe.
  bool may_reach(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const;

  // Per sample of `x`, `y`, `z`, which must be the samples it was built on, with its receiver
  // (an index into `triangles`, or no_receiver): 0 only if none of `casters` (indices into
  // `triangles`) shadows it under the receiver half-space rule, so that it is lit by them.
  // Deterministic for any thread count.
  std::vector<std::uint8_t> samples_reached(std::span<const Triangle> triangles,
                                            std::span<const std::uint32_t> casters,
                                            std::span<const float> x, std::span<const float> y,
                                            std::span<const float> z,
                                            std::span<const std::uint32_t> receivers) const;

  // The projection planes in use (1 for a directional light, up to 6 for a point light).
  std::size_t planes() const { return grids_.size(); }

 private:
  // One projection plane: the axis it is perpendicular to and its sign (point light: the cube
  // face whose outward normal is sign * e_axis; directional: the light's dominant axis), and a
  // grid over the box of its samples' projections.
  struct Grid {
    int axis = 0;
    double sign = 1.0;
    // A point's height (towards the light) is up * its coordinate on the axis: exact.
    double up = 1.0;
    double lo[2] = {0.0, 0.0}, hi[2] = {0.0, 0.0};
    double scale[2] = {0.0, 0.0};  // cells per unit
    int cells = 1;                 // per side
    std::vector<float> lowest;     // per cell: the lowest height of a sample there (+inf: none)
    float lowest_of_all = 0.0f;    // over every cell
    inline int cell(int side, double u) const;
  };
  // Where a triangle lands on a grid: nowhere it could meet a segment of the grid's samples
  // (behind the face, or with its top below `below`), across the face's plane (not projected),
  // or in the box [lo, hi] (rounding margins included) with its highest point at `top`.
  enum class Footprint { none, straddles, box };
  [[gnu::always_inline]] inline Footprint footprint(const Grid& g, const glm::dvec3 v[3],
                                                    double lo[2], double hi[2], double& top,
                                                    double below) const;
  // Projected coordinates and height of point p on grid g (directional or point light).
  inline void project(const Grid& g, const glm::dvec3& p, double uv[2], double& height) const;
  inline bool covers(const Grid& g, const double lo[2], const double hi[2], double top) const;
  int face_of(const glm::dvec3& p) const;  // directional: 0; point light: its cube face
  int grid_of(const glm::dvec3& p) const { return grid_of_face_[face_of(p)]; }

  HardShadowLight light_;
  double ratio_[3] = {0.0, 0.0, 0.0};  // directional: d_i / d_axis
  double sample_bound_ = 0.0;          // the largest absolute sample coordinate
  bool keeps_all_ = true;  // default-constructed, or a sample at the point light (no projection)
  std::vector<Grid> grids_;
  int grid_of_face_[6] = {-1, -1, -1, -1, -1, -1};
  std::size_t samples_ = 0;
};

}  // namespace shadowcts
