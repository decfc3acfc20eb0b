#include "reference/stencil/view_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace shadowcts::stencil {
namespace {

// Whether the projected triangle (x[i], y[i]) meets the rectangle [lo, hi] (separating axes: the
// rectangle's two, tested by the caller's box, and the triangle's three edge normals). Long thin
// quads seen at an angle cover far fewer cells than their boxes do.
bool triangle_meets_rectangle(const double x[3], const double y[3], const double lo[2],
                              const double hi[2]) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double nx = y[j] - y[i], ny = x[i] - x[j];  // normal of edge i -> j
    const double side_k = nx * (x[k] - x[i]) + ny * (y[k] - y[i]);
    if (side_k == 0.0) continue;  // collapsed triangle: the box test decides
    // The rectangle corner farthest towards the triangle's side of the edge.
    const double cx = (nx * side_k > 0.0) ? hi[0] : lo[0];
    const double cy = (ny * side_k > 0.0) ? hi[1] : lo[1];
    const double side_corner = nx * (cx - x[i]) + ny * (cy - y[i]);
    if ((side_k > 0.0 && side_corner < 0.0) || (side_k < 0.0 && side_corner > 0.0)) return false;
  }
  return true;
}

}  // namespace

ViewGrid::ViewGrid(const Camera& camera, const ViewSamples& samples,
                   const std::vector<VolumeFace>& faces)
    : face_count_(std::uint32_t(faces.size())) {
  eye_ = glm::dvec3(camera.position);
  forward_ = glm::normalize(glm::dvec3(camera.target) - eye_);
  right_ = glm::cross(forward_, glm::dvec3(camera.up));
  if (glm::length(right_) == 0.0) right_ = glm::cross(forward_, glm::dvec3(1.0, 0.0, 0.0));
  if (glm::length(right_) == 0.0) right_ = glm::cross(forward_, glm::dvec3(0.0, 0.0, 1.0));
  right_ = glm::normalize(right_);
  up_ = glm::cross(right_, forward_);

  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  std::size_t regular = 0;
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const glm::dvec3 q = project(glm::dvec3(s.position));
    if (!(q.z > 0.0)) continue;
    ++regular;
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  }
  if (regular == 0) {
    offsets_.assign(2, 0);
    return;
  }
  // About 16 samples per cell, at most 256 cells per side.
  cells_ = std::uint32_t(std::clamp(std::sqrt(double(regular) / 16.0), 1.0, 256.0));
  for (int k = 0; k < 2; ++k) {
    const double extent = std::max(hi[k] - lo[k], 1e-12);
    lo_[k] = lo[k];
    cell_size_[k] = extent / double(cells_);
  }
  // Projections are rounded; widen each face's box by far more than that error.
  const double margin[2] = {1e-7 * (std::fabs(lo[0]) + std::fabs(hi[0])) + 1e-9,
                            1e-7 * (std::fabs(lo[1]) + std::fabs(hi[1])) + 1e-9};
  const double behind_tolerance = 1e-9 * std::max(1.0, glm::length(eye_));

  // Per face: the cells it is listed in (row-major ranges of the box, filtered by the shape).
  std::vector<std::vector<std::uint32_t>> face_cells(faces.size());
  std::vector<std::uint32_t> counts(std::size_t(cells_) * cells_ + 1, 0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const VolumeFace& face = faces[f];
    const int vertices = face.is_quad() ? 4 : 3;
    double px[4], py[4];
    double box_lo[2] = {std::numeric_limits<double>::infinity(),
                        std::numeric_limits<double>::infinity()};
    double box_hi[2] = {-box_lo[0], -box_lo[1]};
    int in_front = 0, behind = 0;
    for (int i = 0; i < vertices; ++i) {
      const glm::dvec3 d = face.v[i] - eye_;
      const double z = glm::dot(d, forward_);
      in_front += z > behind_tolerance;
      behind += z < -behind_tolerance;
      if (z > behind_tolerance) {
        px[i] = glm::dot(d, right_) / z, py[i] = glm::dot(d, up_) / z;
        box_lo[0] = std::min(box_lo[0], px[i]), box_hi[0] = std::max(box_hi[0], px[i]);
        box_lo[1] = std::min(box_lo[1], py[i]), box_hi[1] = std::max(box_hi[1], py[i]);
      }
    }
    if (behind == vertices) continue;
    if (in_front != vertices) {
      everywhere_.push_back(std::uint32_t(f));
      continue;
    }
    std::int64_t range[4];
    for (int k = 0; k < 2; ++k) {
      range[2 * k] = std::int64_t(std::floor((box_lo[k] - margin[k] - lo_[k]) / cell_size_[k]));
      range[2 * k + 1] = std::int64_t(std::floor((box_hi[k] + margin[k] - lo_[k]) / cell_size_[k]));
      range[2 * k] = std::max<std::int64_t>(range[2 * k], 0);
      range[2 * k + 1] = std::min<std::int64_t>(range[2 * k + 1], std::int64_t(cells_) - 1);
    }
    for (std::int64_t row = range[2]; row <= range[3]; ++row)
      for (std::int64_t column = range[0]; column <= range[1]; ++column) {
        const double cell_lo[2] = {lo_[0] + double(column) * cell_size_[0] - margin[0],
                                   lo_[1] + double(row) * cell_size_[1] - margin[1]};
        const double cell_hi[2] = {cell_lo[0] + cell_size_[0] + 2.0 * margin[0],
                                   cell_lo[1] + cell_size_[1] + 2.0 * margin[1]};
        const double tx[3] = {px[0], px[1], px[2]}, ty[3] = {py[0], py[1], py[2]};
        bool meets = triangle_meets_rectangle(tx, ty, cell_lo, cell_hi);
        if (!meets && vertices == 4) {
          const double qx[3] = {px[0], px[2], px[3]}, qy[3] = {py[0], py[2], py[3]};
          meets = triangle_meets_rectangle(qx, qy, cell_lo, cell_hi);
        }
        if (!meets) continue;
        const auto cell = std::uint32_t(row * std::int64_t(cells_) + column);
        face_cells[f].push_back(cell);
        ++counts[std::size_t(cell) + 1];
      }
  }
  offsets_.assign(counts.size(), 0);
  for (std::size_t i = 1; i < counts.size(); ++i) offsets_[i] = offsets_[i - 1] + counts[i];
  cell_faces_.resize(offsets_.back());
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::uint32_t cell : face_cells[f]) cell_faces_[fill[cell]++] = std::uint32_t(f);
}

glm::dvec3 ViewGrid::project(const glm::dvec3& world) const {
  const glm::dvec3 d = world - eye_;
  const double z = glm::dot(d, forward_);
  return {glm::dot(d, right_) / z, glm::dot(d, up_) / z, z};
}

std::int64_t ViewGrid::cell_of(const glm::dvec3& world) const {
  const glm::dvec3 q = project(world);
  if (!(q.z > 0.0) || offsets_.size() < 2 || cells_ == 0) return -1;
  std::int64_t index[2];
  for (int k = 0; k < 2; ++k) {
    index[k] = std::int64_t(std::floor((q[k] - lo_[k]) / cell_size_[k]));
    index[k] = std::clamp<std::int64_t>(index[k], 0, std::int64_t(cells_) - 1);
  }
  return index[1] * std::int64_t(cells_) + index[0];
}

}  // namespace shadowcts::stencil
