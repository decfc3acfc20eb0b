#include "reference/caster_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowcts {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Cells per side for n samples on one plane: about one sample in four cells' worth of rows, a
// power of two, at most 1024 (8 MiB of doubles).
int cells_for(std::size_t n) {
  const double side = std::sqrt(double(n)) / 2.0;
  int cells = 1;
  while (cells < 1024 && double(cells) < side) cells *= 2;
  return cells;
}

int dominant_axis(const glm::dvec3& v) {
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(v[i]) > std::fabs(v[axis])) axis = i;
  return axis;
}

}  // namespace

int CasterReach::Grid::cell(int side, double u) const {
  // Monotone in u (a rounded difference, a rounded product by a positive scale, floor, clamp):
  // what lies between two values lands between their cells.
  const double f = std::floor((u - lo[side]) * scale[side]);
  if (!(f > 0.0)) return 0;
  return f >= double(cells - 1) ? cells - 1 : int(f);
}

void CasterReach::project(const Grid& g, const glm::dvec3& p, double uv[2], double& height) const {
  const int i = (g.axis + 1) % 3, j = (g.axis + 2) % 3;
  if (light_.directional) {
    // Along d onto the plane x_axis = 0: p + t d lands where p does (up to the rounding of the
    // ratios, bounded in may_reach). The height along the axis is exact.
    uv[0] = p[i] - p[g.axis] * ratio_[i];
    uv[1] = p[j] - p[g.axis] * ratio_[j];
    height = g.sign * p[g.axis];
    return;
  }
  // Centrally from the light onto the face at distance 1: L + t (p - L), t > 0, lands where p
  // does. Each difference is one rounding of exact float values, which keeps its sign.
  const glm::dvec3 q = p - light_.position;
  const double m = g.sign * q[g.axis];
  uv[0] = q[i] / m;
  uv[1] = q[j] / m;
  // Nearer to the light is higher. The exact coordinate, not m: the rounded difference m is
  // monotone in it, so both order points alike, and this one is exact.
  height = -g.sign * p[g.axis];
}

CasterReach::CasterReach(const HardShadowLight& light, std::span<const float> x,
                         std::span<const float> y, std::span<const float> z)
    : light_(light), keeps_all_(false) {
  const std::size_t n = x.size();
  const auto sample = [&](std::size_t s) { return glm::dvec3(x[s], y[s], z[s]); };
  for (std::size_t s = 0; s < n; ++s)
    sample_bound_ = std::max(
        {sample_bound_, std::fabs(double(x[s])), std::fabs(double(y[s])), std::fabs(double(z[s]))});

  // Which grid each sample belongs to: the light's dominant axis, or its own cube face.
  std::vector<int> face_of(light_.directional ? 0 : n);
  int face_index[6];
  std::fill(std::begin(face_index), std::end(face_index), -1);
  if (light_.directional) {
    const int axis = dominant_axis(light_.direction);
    Grid g;
    g.axis = axis;
    g.sign = light_.direction[axis] > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) ratio_[i] = light_.direction[i] / light_.direction[axis];
    if (n > 0) grids_.push_back(std::move(g));
  } else {
    for (std::size_t s = 0; s < n; ++s) {
      const glm::dvec3 q = sample(s) - light_.position;
      if (q == glm::dvec3(0.0)) {
        keeps_all_ = true;  // its segment is the light itself
        return;
      }
      const int axis = dominant_axis(q);
      const int face = 2 * axis + (q[axis] < 0.0 ? 1 : 0);
      if (face_index[face] < 0) {
        face_index[face] = int(grids_.size());
        Grid g;
        g.axis = axis;
        g.sign = q[axis] < 0.0 ? -1.0 : 1.0;
        grids_.push_back(std::move(g));
      }
      face_of[s] = face_index[face];
    }
  }

  // The box of each grid's projections, then its cells.
  std::vector<std::size_t> count(grids_.size(), 0);
  for (Grid& g : grids_) {
    g.lo[0] = g.lo[1] = infinity;
    g.hi[0] = g.hi[1] = -infinity;
  }
  double uv[2], height;
  for (std::size_t s = 0; s < n; ++s) {
    Grid& g = grids_[light_.directional ? 0 : std::size_t(face_of[s])];
    project(g, sample(s), uv, height);
    ++count[std::size_t(&g - grids_.data())];
    for (int k = 0; k < 2; ++k) {
      g.lo[k] = std::min(g.lo[k], uv[k]);
      g.hi[k] = std::max(g.hi[k], uv[k]);
    }
  }
  for (std::size_t f = 0; f < grids_.size(); ++f) {
    Grid& g = grids_[f];
    g.cells = cells_for(count[f]);
    for (int k = 0; k < 2; ++k) {
      const double scale = double(g.cells) / (g.hi[k] - g.lo[k]);
      g.scale[k] = std::isfinite(scale) ? scale : 0.0;  // one column or row when they coincide
    }
    g.lowest.assign(std::size_t(g.cells) * std::size_t(g.cells), infinity);
  }
  for (std::size_t s = 0; s < n; ++s) {
    Grid& g = grids_[light_.directional ? 0 : std::size_t(face_of[s])];
    project(g, sample(s), uv, height);
    double& lowest = g.lowest[std::size_t(g.cell(1, uv[1])) * std::size_t(g.cells) +
                              std::size_t(g.cell(0, uv[0]))];
    lowest = std::min(lowest, height);
  }
}

bool CasterReach::covers(const Grid& g, const double lo[2], const double hi[2], double top) const {
  if (hi[0] < g.lo[0] || lo[0] > g.hi[0] || hi[1] < g.lo[1] || lo[1] > g.hi[1]) return false;
  const int x0 = g.cell(0, lo[0]), x1 = g.cell(0, hi[0]);
  const int y0 = g.cell(1, lo[1]), y1 = g.cell(1, hi[1]);
  for (int cy = y0; cy <= y1; ++cy) {
    const double* row = g.lowest.data() + std::size_t(cy) * std::size_t(g.cells);
    for (int cx = x0; cx <= x1; ++cx)
      if (row[cx] <= top) return true;
  }
  return false;
}

bool CasterReach::may_reach(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const {
  if (keeps_all_) return true;
  const glm::dvec3 v[3] = {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
  double uv[2], height;
  if (light_.directional) {
    if (grids_.empty()) return false;
    const Grid& g = grids_.front();
    double lo[2] = {infinity, infinity}, hi[2] = {-infinity, -infinity};
    double top = -infinity, bound = sample_bound_;
    for (const glm::dvec3& p : v) {
      project(g, p, uv, height);
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], uv[k]);
        hi[k] = std::max(hi[k], uv[k]);
      }
      top = std::max(top, height);  // exact: the triangle's highest point is a vertex
      bound = std::max({bound, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    }
    // Every projection here is within 3 B 2^-53 of the exact linear map with the rounded ratios
    // (B: the largest coordinate), and that map moves by at most 2 B 2^-53 along a segment
    // inside the bound: 2^-47 B covers a sample whose segment meets the triangle, 8 times over.
    const double margin = bound * 0x1p-47;
    for (int k = 0; k < 2; ++k) {
      lo[k] -= margin;
      hi[k] += margin;
    }
    return covers(g, lo, hi, top);
  }
  for (const Grid& g : grids_) {
    // The triangle meets a segment of this face's samples only at points in front of the light
    // on this axis (the segment's points other than the light itself are). Signs are exact.
    double m[3];
    int positive = 0, negative = 0;
    for (int k = 0; k < 3; ++k) {
      m[k] = g.sign * (v[k][g.axis] - light_.position[g.axis]);
      positive += m[k] > 0.0;
      negative += m[k] < 0.0;
    }
    if (negative == 3) continue;
    if (positive < 3) return true;  // reaches behind the face's plane: not projected
    double lo[2] = {infinity, infinity}, hi[2] = {-infinity, -infinity};
    double top = -infinity;
    for (const glm::dvec3& p : v) {
      project(g, p, uv, height);
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], uv[k]);
        hi[k] = std::max(hi[k], uv[k]);
      }
      top = std::max(top, height);
    }
    // A quotient of two once-rounded differences is within 3.1 ulp of the exact ratio: the
    // vertices' by |value| 2^-51, the samples' (|value| <= 1 on their own face) by 2^-51.
    for (int k = 0; k < 2; ++k) {
      const double margin = (std::max(std::fabs(lo[k]), std::fabs(hi[k])) + 1.0) * 0x1p-49;
      lo[k] -= margin;
      hi[k] += margin;
    }
    // The meeting point is no farther along the axis than the sample and no nearer than the
    // nearest vertex.
    if (covers(g, lo, hi, top)) return true;
  }
  return false;
}

}  // namespace shadowcts
