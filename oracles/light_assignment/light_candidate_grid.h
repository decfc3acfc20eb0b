#pragma once
// The oracle's spatial index over lights: a uniform grid over the box of the view samples, each
// cell listing every light whose sphere, grown by the band's reach, may touch the cell. A point
// query returns a superset of the lights that may contain the point or a band move of it; the
// exact predicates decide. Independent of the reference algorithms' light BVH on purpose.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "oracles/light_assignment/light_volume_predicates.h"

namespace shadowcts {

class LightCandidateGrid {
 public:
  // `low`/`high`: a box holding every query point. Lights whose grown sphere misses it are left
  // out; lights covering more than max_cells_per_light cells are kept in one list that every
  // query returns.
  LightCandidateGrid(const std::vector<ExactLightVolume>& lights, const glm::dvec3& low,
                     const glm::dvec3& high, double reach);

  // The candidates for p (inside the box given at construction), appended to `out` in ascending
  // light order.
  void candidates(const glm::dvec3& p, std::vector<std::uint32_t>& out) const;

  std::uint64_t cells() const { return cell_offsets_.size() - 1; }
  std::uint64_t entries() const { return cell_lights_.size(); }
  std::uint64_t everywhere_lights() const { return everywhere_.size(); }

  static constexpr std::uint64_t max_cells_per_light = 4096;

 private:
  glm::ivec3 cell_of(const glm::dvec3& p) const;

  glm::dvec3 origin_{0.0};
  glm::dvec3 cell_size_{1.0};
  glm::ivec3 dims_{1};
  std::vector<std::uint64_t> cell_offsets_{0, 0};
  std::vector<std::uint32_t> cell_lights_;
  std::vector<std::uint32_t> everywhere_;
};

}  // namespace shadowcts
