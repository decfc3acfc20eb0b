#include "reference/caster_reach.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "shadowcts/geometry/triangle_area.h"

namespace shadowcts {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Cells per side for n samples on one plane: about one sample per cell (the nearest power of two
// to sqrt(n), at most 2048: 16 MiB of floats). Finer grids drop more (gate_house.1M at 1080p: 78 %
// of the casters at 1024 cells a side, 72 % at 512) for a larger grid to fill.
int cells_for(std::size_t n) {
  const double side = std::sqrt(double(n));
  int cells = 1;
  while (cells < 2048 && 2.0 * double(cells) <= 1.5 * side) cells *= 2;
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
  const double f = (u - lo[side]) * scale[side];
  if (!(f > 0.0)) return 0;
  return f >= double(cells - 1) ? cells - 1 : int(f);  // truncation: floor of a positive value
}

void CasterReach::project(const Grid& g, const glm::dvec3& p, double uv[2], double& height) const {
  const int i = (g.axis + 1) % 3, j = (g.axis + 2) % 3;
  if (light_.directional) {
    // Along d onto the plane x_axis = 0: p + t d lands where p does (up to the rounding of the
    // ratios, bounded in may_reach). The height along the axis is exact.
    uv[0] = p[i] - p[g.axis] * ratio_[i];
    uv[1] = p[j] - p[g.axis] * ratio_[j];
    height = g.up * p[g.axis];
    return;
  }
  // Centrally from the light onto the face at distance 1: L + t (p - L), t > 0, lands where p
  // does. Each difference is one rounding of exact float values, which keeps its sign.
  const glm::dvec3 q = p - light_.position;
  const double m = g.sign * q[g.axis];
  uv[0] = q[i] / m;
  uv[1] = q[j] / m;
  // The exact coordinate, not m: the rounded difference m is monotone in it, so both order points
  // alike, and this one is exact.
  height = g.up * p[g.axis];
}

int CasterReach::face_of(const glm::dvec3& p) const {
  if (light_.directional) return 0;
  const glm::dvec3 q = p - light_.position;
  const int axis = dominant_axis(q);
  return 2 * axis + (q[axis] < 0.0 ? 1 : 0);
}

CasterReach::CasterReach(const HardShadowLight& light, std::span<const float> x,
                         std::span<const float> y, std::span<const float> z)
    : light_(light), keeps_all_(false) {
  const std::size_t n = x.size();
  const auto sample = [&](std::size_t s) { return glm::dvec3(x[s], y[s], z[s]); };
  // The grid of each possible face: a directional light has one (its dominant axis), a point
  // light the six faces of its cube (face 2 axis + 1 looks down the negative axis).
  Grid faces[6];
  for (int f = 0; f < 6; ++f) {
    faces[f].axis = f / 2;
    faces[f].sign = f % 2 == 0 ? 1.0 : -1.0;
    faces[f].up = -faces[f].sign;  // nearer to the point light is higher
  }
  if (light_.directional) {
    const int axis = dominant_axis(light_.direction);
    faces[0].axis = axis;
    faces[0].sign = faces[0].up = light_.direction[axis] > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) ratio_[i] = light_.direction[i] / light_.direction[axis];
  }

  // Per face: the samples' count and the box of their projections. Sums, minima and maxima:
  // the same for any partitioning.
  struct Boxes {
    std::size_t count[6] = {0, 0, 0, 0, 0, 0};
    double lo[6][2], hi[6][2];
    double bound = 0.0;
    bool at_light = false;
    Boxes() {
      for (int f = 0; f < 6; ++f) lo[f][0] = lo[f][1] = infinity, hi[f][0] = hi[f][1] = -infinity;
    }
  };
  const Boxes boxes = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 16384), Boxes(),
      [&](const tbb::blocked_range<std::size_t>& range, Boxes b) {
        double uv[2], height;
        for (std::size_t s = range.begin(); s != range.end(); ++s) {
          const glm::dvec3 p = sample(s);
          b.bound = std::max({b.bound, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
          if (!light_.directional && p == light_.position) {
            b.at_light = true;  // its segment is the light itself
            continue;
          }
          const int f = face_of(p);
          project(faces[f], p, uv, height);
          ++b.count[f];
          for (int k = 0; k < 2; ++k) {
            b.lo[f][k] = std::min(b.lo[f][k], uv[k]);
            b.hi[f][k] = std::max(b.hi[f][k], uv[k]);
          }
        }
        return b;
      },
      [](Boxes a, const Boxes& b) {
        for (int f = 0; f < 6; ++f) {
          a.count[f] += b.count[f];
          for (int k = 0; k < 2; ++k) {
            a.lo[f][k] = std::min(a.lo[f][k], b.lo[f][k]);
            a.hi[f][k] = std::max(a.hi[f][k], b.hi[f][k]);
          }
        }
        a.bound = std::max(a.bound, b.bound);
        a.at_light = a.at_light || b.at_light;
        return a;
      });
  sample_bound_ = boxes.bound;
  if (boxes.at_light) {
    keeps_all_ = true;
    return;
  }
  samples_ = n;
  for (int f = 0; f < 6; ++f) {
    grid_of_face_[f] = -1;
    if (boxes.count[f] == 0) continue;
    Grid g = faces[f];
    g.cells = cells_for(boxes.count[f]);
    for (int k = 0; k < 2; ++k) {
      g.lo[k] = boxes.lo[f][k];
      g.hi[k] = boxes.hi[f][k];
      const double scale = double(g.cells) / (g.hi[k] - g.lo[k]);
      g.scale[k] = std::isfinite(scale) ? scale : 0.0;  // one column or row when they coincide
    }
    g.lowest.assign(std::size_t(g.cells) * std::size_t(g.cells), float(infinity));
    grid_of_face_[f] = int(grids_.size());
    grids_.push_back(std::move(g));
  }
  // Each cell's lowest sample by atomic minima: the same for any order.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      double uv[2], height;
                      for (std::size_t s = range.begin(); s != range.end(); ++s) {
                        const glm::dvec3 p = sample(s);
                        Grid& g = grids_[std::size_t(grid_of(p))];
                        project(g, p, uv, height);
                        std::atomic_ref<float> lowest(
                            g.lowest[std::size_t(g.cell(1, uv[1])) * std::size_t(g.cells) +
                                     std::size_t(g.cell(0, uv[0]))]);
                        const float h = float(height);  // exact: a float coordinate
                        for (float now = lowest.load(std::memory_order_relaxed); h < now;)
                          if (lowest.compare_exchange_weak(now, h, std::memory_order_relaxed))
                            break;
                      }
                    });
  for (Grid& g : grids_) g.lowest_of_all = *std::min_element(g.lowest.begin(), g.lowest.end());
}

bool CasterReach::covers(const Grid& g, const double lo[2], const double hi[2], double top) const {
  if (hi[0] < g.lo[0] || lo[0] > g.hi[0] || hi[1] < g.lo[1] || lo[1] > g.hi[1]) return false;
  const int x0 = g.cell(0, lo[0]), x1 = g.cell(0, hi[0]);
  const int y0 = g.cell(1, lo[1]), y1 = g.cell(1, hi[1]);
  for (int cy = y0; cy <= y1; ++cy) {
    const float* row = g.lowest.data() + std::size_t(cy) * std::size_t(g.cells);
    for (int cx = x0; cx <= x1; ++cx)
      if (row[cx] <= top) return true;
  }
  return false;
}

CasterReach::Footprint CasterReach::footprint(const Grid& g, const glm::dvec3 v[3], double lo[2],
                                              double hi[2], double& top, double below) const {
  if (!light_.directional) {
    // The triangle meets a segment of this face's samples only at points in front of the light
    // on this axis (the segment's points other than the light itself are). Signs are exact.
    int positive = 0, negative = 0;
    for (int i = 0; i < 3; ++i) {
      const double m = g.sign * (v[i][g.axis] - light_.position[g.axis]);
      positive += m > 0.0;
      negative += m < 0.0;
    }
    if (negative == 3) return Footprint::none;
    if (positive < 3) return Footprint::straddles;
  }
  // Exact: the triangle's highest point is a vertex.
  top = std::max({g.up * v[0][g.axis], g.up * v[1][g.axis], g.up * v[2][g.axis]});
  if (top < below) return Footprint::none;
  double uv[2], height;
  for (int k = 0; k < 2; ++k) lo[k] = infinity, hi[k] = -infinity;
  for (int i = 0; i < 3; ++i) {
    project(g, v[i], uv, height);
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], uv[k]);
      hi[k] = std::max(hi[k], uv[k]);
    }
  }
  // Directional: every projection here is within 3 B 2^-53 of the exact linear map with the
  // rounded ratios (B: the largest coordinate), and that map moves by at most 2 B 2^-53 along a
  // segment inside the bound: 2^-47 B covers a sample whose segment meets the triangle, 8 times
  // over. Point light: a quotient of two once-rounded differences is within 3.1 ulp of the exact
  // ratio: the vertices' by |value| 2^-51, the samples' (|value| <= 1 on their own face) by
  // 2^-51.
  double bound = sample_bound_;
  if (light_.directional)
    for (int i = 0; i < 3; ++i)
      bound = std::max({bound, std::fabs(v[i].x), std::fabs(v[i].y), std::fabs(v[i].z)});
  for (int k = 0; k < 2; ++k) {
    const double margin = light_.directional
                              ? bound * 0x1p-47
                              : (std::max(std::fabs(lo[k]), std::fabs(hi[k])) + 1.0) * 0x1p-49;
    lo[k] -= margin;
    hi[k] += margin;
  }
  return Footprint::box;
}

bool CasterReach::may_reach(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const {
  if (keeps_all_) return true;
  const glm::dvec3 v[3] = {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
  double lo[2], hi[2], top;
  for (const Grid& g : grids_) {
    // Below every sample of the plane (farther from the light): nothing to project.
    switch (footprint(g, v, lo, hi, top, g.lowest_of_all)) {
      case Footprint::none:
        break;
      case Footprint::straddles:
        return true;  // reaches behind the face's plane: not projected
      case Footprint::box:
        // The meeting point is no lower than the sample and no higher than the triangle's top.
        if (covers(g, lo, hi, top)) return true;
        break;
    }
  }
  return false;
}

std::vector<std::uint8_t> CasterReach::samples_reached(
    std::span<const Triangle> triangles, std::span<const std::uint32_t> casters,
    std::span<const float> x, std::span<const float> y, std::span<const float> z,
    std::span<const std::uint32_t> receivers) const {
  const std::size_t n = x.size();
  if (keeps_all_) return std::vector<std::uint8_t>(n, 1);
  if (n != samples_) throw std::invalid_argument("CasterReach: not the samples it was built on");
  // Per plane, a pyramid of the highest caster over each cell: level l has cells >> l a side. A
  // caster raises the cells of the coarsest level that holds its box in 4 x 4 of them (at most 16
  // cells, whatever its size); the levels are then pushed down into the finest, which a sample
  // reads. Heights are float coordinates and maxima: exact, and the same for any order.
  struct Pyramid {
    std::vector<std::vector<float>> levels;
    std::unique_ptr<std::atomic<bool>[]> used;  // per level: some caster raised a cell there
    std::atomic<bool> open{false};  // a caster straddles the face's plane: every sample reached
  };
  std::vector<Pyramid> pyramids(grids_.size());
  for (std::size_t f = 0; f < grids_.size(); ++f) {
    for (int side = grids_[f].cells; side >= 1; side /= 2)
      pyramids[f].levels.emplace_back(std::size_t(side) * std::size_t(side), -INFINITY);
    pyramids[f].used = std::make_unique<std::atomic<bool>[]>(pyramids[f].levels.size());
  }
  // In index order, whatever the casters' order: neighbouring triangles share cells.
  std::vector<std::uint8_t> is_caster(triangles.size(), 0);
  for (const std::uint32_t t : casters) is_caster[t] = 1;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& range) {
        double lo[2], hi[2], top;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          if (!is_caster[i]) continue;
          const Triangle& t = triangles[i];
          const glm::dvec3 v[3] = {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
          for (std::size_t f = 0; f < grids_.size(); ++f) {
            const Grid& g = grids_[f];
            Pyramid& pyramid = pyramids[f];
            if (pyramid.open.load(std::memory_order_relaxed)) continue;
            const Footprint where = footprint(g, v, lo, hi, top, -infinity);
            if (where == Footprint::straddles) pyramid.open = true;
            if (where != Footprint::box || hi[0] < g.lo[0] || lo[0] > g.hi[0] || hi[1] < g.lo[1] ||
                lo[1] > g.hi[1])
              continue;
            const int x0 = g.cell(0, lo[0]), x1 = g.cell(0, hi[0]);
            const int y0 = g.cell(1, lo[1]), y1 = g.cell(1, hi[1]);
            int l = 0;
            while ((x1 >> l) - (x0 >> l) > 3 || (y1 >> l) - (y0 >> l) > 3) ++l;
            const std::size_t side = std::size_t(g.cells >> l);
            std::vector<float>& cells = pyramid.levels[std::size_t(l)];
            if (!pyramid.used[l].load(std::memory_order_relaxed)) pyramid.used[l] = true;
            const float h = float(top);
            for (int cy = y0 >> l; cy <= y1 >> l; ++cy)
              for (int cx = x0 >> l; cx <= x1 >> l; ++cx) {
                std::atomic_ref<float> highest(cells[std::size_t(cy) * side + std::size_t(cx)]);
                for (float now = highest.load(std::memory_order_relaxed); h > now;)
                  if (highest.compare_exchange_weak(now, h, std::memory_order_relaxed)) break;
              }
          }
        }
      });
  for (std::size_t f = 0; f < grids_.size(); ++f) {
    Pyramid& pyramid = pyramids[f];
    std::size_t top_used = 0;
    for (std::size_t l = 0; l < pyramid.levels.size(); ++l)
      if (pyramid.used[l].load(std::memory_order_relaxed)) top_used = l;
    for (std::size_t l = top_used; l-- > 0;) {
      const std::size_t side = std::size_t(grids_[f].cells >> l);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, side, 64),
                        [&](const tbb::blocked_range<std::size_t>& rows) {
                          for (std::size_t cy = rows.begin(); cy != rows.end(); ++cy)
                            for (std::size_t cx = 0; cx < side; ++cx) {
                              float& cell = pyramid.levels[l][cy * side + cx];
                              cell = std::max(
                                  cell, pyramid.levels[l + 1][(cy / 2) * (side / 2) + cx / 2]);
                            }
                        });
    }
  }
  std::vector<std::uint8_t> reached(n, 0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 16384),
      [&](const tbb::blocked_range<std::size_t>& range) {
        double uv[2], height;
        std::uint32_t last_receiver = no_receiver;
        const Grid* last_grid = nullptr;
        double plane = -infinity;
        for (std::size_t s = range.begin(); s != range.end(); ++s) {
          const glm::dvec3 p(x[s], y[s], z[s]);
          const std::size_t f = std::size_t(grid_of(p));
          if (pyramids[f].open) {
            reached[s] = 1;
            continue;
          }
          const Grid& g = grids_[f];
          project(g, p, uv, height);
          // The receiver half-space rule counts only points strictly on the light's side of the
          // receiver's plane. Where that plane lies across the grid's axis (every vertex at one
          // height; not of zero area, which has no plane and voids the rule) with the light
          // higher, those points are higher than the plane: a caster must rise above it, and a
          // coplanar floor never does. Neighbouring samples mostly share their receiver.
          if (receivers[s] != last_receiver || &g != last_grid) {
            last_receiver = receivers[s];
            last_grid = &g;
            plane = -infinity;
            if (last_receiver < triangles.size()) {
              const Triangle& r = triangles[last_receiver];
              const double h_plane = g.up * double(r.v0[g.axis]);
              const double h_light = light_.directional ? infinity : g.up * light_.position[g.axis];
              if (r.v0[g.axis] == r.v1[g.axis] && r.v1[g.axis] == r.v2[g.axis] &&
                  h_plane < h_light && !triangle_has_zero_area(r.v0, r.v1, r.v2))
                plane = h_plane;
            }
          }
          const float highest =
              pyramids[f].levels.front()[std::size_t(g.cell(1, uv[1])) * std::size_t(g.cells) +
                                         std::size_t(g.cell(0, uv[0]))];
          // Some caster over the cell reaches as high as the sample, and above its plane.
          reached[s] = double(highest) >= height && double(highest) > plane ? 1 : 0;
        }
      });
  return reached;
}

}  // namespace shadowcts
