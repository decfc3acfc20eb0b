#include "reference/stencil/view_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "shadowcts/float_rounding.h"

namespace shadowcts::stencil {
namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon();
constexpr double infinity = std::numeric_limits<double>::infinity();
// Relative slack for rounded depths and depth ratios: far above their rounding, far below any
// depth difference that saves work.
constexpr double depth_tolerance = 1e-9;

using Polygon = ViewGrid::Outline::Polygon;

// The x-range of the polygon's part within the band y0 <= y <= y1 (its extremes are corners inside
// the band or crossings of the band's edges); false when it misses the band. A cell of a row meets
// the (convex) polygon exactly when its x-range overlaps this: long thin quads seen at an angle
// cover far fewer cells than their boxes do, and are walked row by row, not box cell by box cell.
// The polygon's orientation, or 0 where its area is too small against its size to trust the
// sign (a sliver seen edge-on): such an outline contains every point.
void set_orientation(Polygon& p) {
  double area = 0.0, lo[2] = {infinity, infinity}, hi[2] = {-infinity, -infinity};
  for (int i = 0; i < p.n; ++i) {
    const int j = (i + 1) % p.n;
    area += (p.x[i] - p.x[0]) * (p.y[j] - p.y[0]) - (p.x[j] - p.x[0]) * (p.y[i] - p.y[0]);
    lo[0] = std::min(lo[0], p.x[i]), hi[0] = std::max(hi[0], p.x[i]);
    lo[1] = std::min(lo[1], p.y[i]), hi[1] = std::max(hi[1], p.y[i]);
  }
  const double size = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  p.orientation = std::fabs(area) > 1e-9 * size * size ? (area > 0.0 ? 1 : -1) : 0;
  for (int i = 0; i < p.n; ++i) {
    const int j = (i + 1) % p.n;
    p.nx[i] = double(p.orientation) * (p.y[i] - p.y[j]);
    p.ny[i] = double(p.orientation) * (p.x[j] - p.x[i]);
  }
}

bool x_range_in_band(const Polygon& p, double y0, double y1, double& x0, double& x1) {
  x0 = infinity, x1 = -infinity;
  for (int i = 0; i < p.n; ++i) {
    if (p.y[i] >= y0 && p.y[i] <= y1) x0 = std::min(x0, p.x[i]), x1 = std::max(x1, p.x[i]);
    const int j = (i + 1) % p.n;
    for (const double y : {y0, y1}) {
      if (!((p.y[i] < y && p.y[j] > y) || (p.y[i] > y && p.y[j] < y))) continue;
      const double x = p.x[i] + (y - p.y[i]) / (p.y[j] - p.y[i]) * (p.x[j] - p.x[i]);
      x0 = std::min(x0, x), x1 = std::max(x1, x);
    }
  }
  return x0 <= x1;
}

// A face triangle in camera coordinates (right, up, forward from the eye), clipped by planes
// through the eye and the clip-depth plane: 3 + 5 corners in exact arithmetic; rounded sides
// could add more, which `overflow` reports (the caller then keeps the whole face's range).
struct CameraPolygon {
  static constexpr int capacity = 16;
  glm::dvec3 q[capacity];
  int n = 0;
  bool overflow = false;
};

// Keeps the part where dot(normal, q) + offset >= 0.
void clip(CameraPolygon& polygon, const glm::dvec3& normal, double offset) {
  CameraPolygon out;
  out.overflow = polygon.overflow;
  const auto add = [&](const glm::dvec3& q) {
    if (out.n == CameraPolygon::capacity)
      out.overflow = true;
    else
      out.q[out.n++] = q;
  };
  for (int i = 0; i < polygon.n; ++i) {
    const glm::dvec3& a = polygon.q[i];
    const glm::dvec3& b = polygon.q[(i + 1) % polygon.n];
    const double side_a = glm::dot(normal, a) + offset, side_b = glm::dot(normal, b) + offset;
    if (side_a >= 0.0) add(a);
    if ((side_a >= 0.0) != (side_b >= 0.0)) add(a + (side_a / (side_a - side_b)) * (b - a));
  }
  polygon = out;
}

// The depth range of the triangle's part inside the cell's (widened) frustum beyond the clip
// depth; false when the rounded clipping leaves nothing or overflows (the caller then keeps the
// face's range). A long side quad spans a huge depth range, its part seen through one cell a
// small one: this is what lets a sample skip the quads crossed in front of it (z-fail) or behind
// it (z-pass).
bool depth_range_in_cell(const glm::dvec3 (&triangle)[3], const double lo[2], const double hi[2],
                         double clip_at, double& low, double& high) {
  CameraPolygon polygon;
  for (const glm::dvec3& q : triangle) polygon.q[polygon.n++] = q;
  clip(polygon, {0.0, 0.0, 1.0}, -clip_at);
  clip(polygon, {1.0, 0.0, -lo[0]}, 0.0);
  clip(polygon, {-1.0, 0.0, hi[0]}, 0.0);
  clip(polygon, {0.0, 1.0, -lo[1]}, 0.0);
  clip(polygon, {0.0, -1.0, hi[1]}, 0.0);
  if (polygon.n == 0 || polygon.overflow) return false;
  low = infinity, high = -infinity;
  for (int i = 0; i < polygon.n; ++i)
    low = std::min(low, polygon.q[i].z), high = std::max(high, polygon.q[i].z);
  return true;
}

using Range = tbb::blocked_range<std::size_t>;

struct Listing {
  std::uint32_t cell;
  float key;
  std::uint32_t face;
};

// The regular samples' projections: their box and depth range, and the largest |p - e| / depth.
struct SampleFrustum {
  double lo[2] = {infinity, infinity}, hi[2] = {-infinity, -infinity};
  double near = infinity, far = 0.0, slope = 0.0;
  std::size_t count = 0;
};

}  // namespace

double sample_reach(const glm::dvec3& eye, const ViewSamples& samples) {
  double reach = 0.0;
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular)
      reach = std::max(reach, glm::length(glm::dvec3(s.position) - eye));
  return reach * (1.0 + depth_tolerance);
}

ViewGrid::ViewGrid(const Camera& camera, const ViewSamples& samples,
                   const std::vector<VolumeFace>& faces, const std::vector<CrossingReach>& reaches,
                   CountingMode mode)
    : mode_(mode), face_count_(std::uint32_t(faces.size())) {
  eye_ = glm::dvec3(camera.position);
  forward_ = glm::normalize(glm::dvec3(camera.target) - eye_);
  right_ = glm::cross(forward_, glm::dvec3(camera.up));
  if (glm::length(right_) == 0.0) right_ = glm::cross(forward_, glm::dvec3(1.0, 0.0, 0.0));
  if (glm::length(right_) == 0.0) right_ = glm::cross(forward_, glm::dvec3(0.0, 0.0, 1.0));
  right_ = glm::normalize(right_);
  up_ = glm::cross(right_, forward_);

  SampleFrustum frustum;
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const glm::dvec3 p(s.position);
    const glm::dvec3 q = project(p);
    if (!(q.z > 0.0)) continue;
    ++frustum.count;
    for (int k = 0; k < 2; ++k)
      frustum.lo[k] = std::min(frustum.lo[k], q[k]), frustum.hi[k] = std::max(frustum.hi[k], q[k]);
    frustum.near = std::min(frustum.near, q.z);
    frustum.far = std::max(frustum.far, q.z);
    frustum.slope = std::max(frustum.slope, glm::length(p - eye_) / q.z);
  }
  if (frustum.count == 0) {
    offsets_.assign(2, 0);
    for (std::uint32_t f = 0; f < face_count_; ++f)
      if (reaches[f].kind != CrossingReach::Kind::never) everywhere_.push_back(f);
    return;
  }
  // About 16 samples per cell, at most 256 cells per side.
  cells_ = std::uint32_t(std::clamp(std::sqrt(double(frustum.count) / 16.0), 1.0, 256.0));
  for (int k = 0; k < 2; ++k) {
    const double extent = std::max(frustum.hi[k] - frustum.lo[k], 1e-12);
    lo_[k] = frustum.lo[k];
    cell_size_[k] = extent / double(cells_);
  }
  // Projections are rounded; widen each face's box by far more than that error.
  const double base_margin[2] = {
      1e-7 * (std::fabs(frustum.lo[0]) + std::fabs(frustum.hi[0])) + 1e-9,
      1e-7 * (std::fabs(frustum.lo[1]) + std::fabs(frustum.hi[1])) + 1e-9};
  // z-fail's counted crossings lie at depth >= (1 - slack) * depth(p) >= near / 2 (max_slack =
  // 1/2). z-pass's lie between the eye and the sample: at depth >= near / 64 for faces farther
  // than `near_eye` from the eye (below), the others are listed everywhere; a small clip depth
  // keeps that set small (the volumes of casters next to the camera pass near the eye).
  const double clip_depth = mode == CountingMode::z_fail ? 0.5 * frustum.near : frustum.near / 64.0;
  const double clip_at = clip_depth * (1.0 - depth_tolerance);

  outlines_.resize(faces.size());
  tbb::enumerable_thread_specific<std::vector<Listing>> listings;
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> anywhere;
  tbb::parallel_for(Range(0, faces.size(), 1024), [&](const Range& range) {
    std::vector<Listing>& out = listings.local();
    std::vector<std::uint32_t>& out_anywhere = anywhere.local();
    std::vector<std::pair<std::uint32_t, double>> face_cells;  // cell, key
    for (std::size_t f = range.begin(); f != range.end(); ++f) {
      const CrossingReach& reach = reaches[f];
      if (reach.kind == CrossingReach::Kind::never) continue;
      if (reach.kind == CrossingReach::Kind::anywhere) {
        out_anywhere.push_back(std::uint32_t(f));
        continue;
      }
      const VolumeFace& face = faces[f];
      const int vertices = face.is_quad() ? 4 : 3;
      double depth[4], distance = 0.0;
      glm::dvec3 box_lo(infinity), box_hi(-infinity);
      bool finite = true;
      for (int i = 0; i < vertices; ++i) {
        const glm::dvec3 d = face.v[i] - eye_;
        depth[i] = glm::dot(d, forward_);
        distance = std::max(distance, glm::length(d));
        box_lo = glm::min(box_lo, face.v[i]), box_hi = glm::max(box_hi, face.v[i]);
        finite = finite && std::isfinite(depth[i]);
      }
      if (!finite || !std::isfinite(distance)) {
        out_anywhere.push_back(std::uint32_t(f));
        continue;
      }
      const double depth_error = depth_tolerance * distance;
      double lowest = infinity, highest = -infinity;
      for (int i = 0; i < vertices; ++i)
        lowest = std::min(lowest, depth[i]), highest = std::max(highest, depth[i]);
      // Listings with key <= key_bound(depth(p)) are read (ascending keys): z-pass needs a
      // crossing at depth <= (1 + slack) depth(p), z-fail at depth >= (1 - slack) depth(p).
      const auto key_of = [&](double low, double high) {
        if (mode_ == CountingMode::z_pass)
          return std::max(clip_at, low - depth_error) / (1.0 + reach.slack);
        return -(high + depth_error) / (1.0 - reach.slack);
      };
      if (mode_ == CountingMode::z_pass) {
        // A crossing at depth < clip_depth lies within this of the eye (t in [-slack, t0]).
        const double near_eye =
            std::max(reach.slack * frustum.far, clip_depth) * frustum.slope * (1.0 + 1e-6);
        const glm::dvec3 outside =
            glm::max(glm::dvec3(0.0), glm::max(box_lo - eye_, eye_ - box_hi));
        const double distance_lower =
            std::max(glm::length(outside) * (1.0 - 1e-6), reach.eye_distance);
        if (!(distance_lower > near_eye)) {
          out_anywhere.push_back(std::uint32_t(f));
          continue;
        }
      }
      const double face_key = key_of(lowest, highest);
      // Clipped corners are rounded too: a margin for errors of a few ulps of the farthest
      // vertex, magnified by the projection at the clip depth.
      const double magnified = distance / clip_at;
      const double margin_extra = 64.0 * epsilon * magnified * (1.0 + magnified);
      const double margin[2] = {base_margin[0] + margin_extra, base_margin[1] + margin_extra};
      face_cells.clear();
      outlines_[f].margin = std::max(margin[0], margin[1]);
      bool unbounded = false;
      for (int t = 0; t < (face.is_quad() ? 2 : 1) && !unbounded; ++t) {
        const int corner[3] = {0, t + 1, t + 2};
        glm::dvec3 camera_triangle[3];
        for (int i = 0; i < 3; ++i) {
          const glm::dvec3 d = face.v[corner[i]] - eye_;
          camera_triangle[i] = {glm::dot(d, right_), glm::dot(d, up_), depth[corner[i]]};
        }
        Polygon polygon;
        for (int i = 0; i < 3; ++i) {
          const int a = corner[i], b = corner[(i + 1) % 3];
          const auto add = [&](const glm::dvec3& v, double z) {
            const glm::dvec3 d = v - eye_;
            polygon.x[polygon.n] = glm::dot(d, right_) / z;
            polygon.y[polygon.n] = glm::dot(d, up_) / z;
            ++polygon.n;
          };
          if (depth[a] >= clip_at) add(face.v[a], depth[a]);
          if ((depth[a] >= clip_at) != (depth[b] >= clip_at)) {
            const double s = (clip_at - depth[a]) / (depth[b] - depth[a]);
            add(face.v[a] + s * (face.v[b] - face.v[a]), clip_at);
          }
        }
        if (polygon.n == 0) continue;
        set_orientation(polygon);
        outlines_[f].part[outlines_[f].parts++] = polygon;
        double p_lo[2] = {infinity, infinity}, p_hi[2] = {-infinity, -infinity};
        for (int i = 0; i < polygon.n; ++i) {
          p_lo[0] = std::min(p_lo[0], polygon.x[i]), p_hi[0] = std::max(p_hi[0], polygon.x[i]);
          p_lo[1] = std::min(p_lo[1], polygon.y[i]), p_hi[1] = std::max(p_hi[1], polygon.y[i]);
        }
        if (!std::isfinite(p_lo[0] + p_hi[0] + p_lo[1] + p_hi[1])) {
          unbounded = true;
          break;
        }
        const double last = double(cells_) - 1.0;
        const double first_row =
            std::max(std::floor((p_lo[1] - margin[1] - lo_[1]) / cell_size_[1]), 0.0);
        const double last_row =
            std::min(std::floor((p_hi[1] + margin[1] - lo_[1]) / cell_size_[1]), last);
        for (double row = first_row; row <= last_row; ++row) {
          const double band_lo = lo_[1] + row * cell_size_[1] - margin[1];
          const double band_hi = band_lo + cell_size_[1] + 2.0 * margin[1];
          double x0, x1;
          if (!x_range_in_band(polygon, band_lo, band_hi, x0, x1)) continue;
          const double first_column =
              std::max(std::floor((x0 - margin[0] - lo_[0]) / cell_size_[0]), 0.0);
          const double last_column =
              std::min(std::floor((x1 + margin[0] - lo_[0]) / cell_size_[0]), last);
          for (double column = first_column; column <= last_column; ++column) {
            const double cell_lo[2] = {lo_[0] + column * cell_size_[0] - margin[0], band_lo};
            const double cell_hi[2] = {cell_lo[0] + cell_size_[0] + 2.0 * margin[0], band_hi};
            double low = lowest, high = highest;
            double key = face_key;
            if (depth_range_in_cell(camera_triangle, cell_lo, cell_hi, clip_at, low, high))
              key = std::max(key, key_of(low, high));  // both bound the crossing's depth
            face_cells.push_back({std::uint32_t(row) * cells_ + std::uint32_t(column), key});
          }
        }
      }
      if (unbounded) {
        outlines_[f].parts = 0;
        out_anywhere.push_back(std::uint32_t(f));
        continue;
      }
      // A quad's two triangles in one cell: the smaller key reads the listing for both.
      std::sort(face_cells.begin(), face_cells.end());
      for (std::size_t k = 0; k < face_cells.size(); ++k) {
        if (k > 0 && face_cells[k].first == face_cells[k - 1].first) continue;
        out.push_back({face_cells[k].first, float_below(face_cells[k].second), std::uint32_t(f)});
      }
    }
  });

  const std::size_t cell_count = std::size_t(cells_) * cells_;
  std::vector<std::uint32_t> counts(cell_count + 1, 0);
  for (const std::vector<Listing>& part : listings)
    for (const Listing& l : part) ++counts[std::size_t(l.cell) + 1];
  offsets_.assign(counts.size(), 0);
  for (std::size_t i = 1; i < counts.size(); ++i) offsets_[i] = offsets_[i - 1] + counts[i];
  std::vector<std::pair<float, std::uint32_t>> sorted(offsets_.back());
  {
    std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::vector<Listing>& part : listings) {
      for (const Listing& l : part) sorted[fill[l.cell]++] = {l.key, l.face};
      std::vector<Listing>().swap(part);
    }
  }
  // Within a cell by key, then face: the same lists whatever the threads' partitioning.
  tbb::parallel_for(Range(0, cell_count, 64), [&](const Range& range) {
    for (std::size_t c = range.begin(); c != range.end(); ++c)
      std::sort(sorted.begin() + offsets_[c], sorted.begin() + offsets_[c + 1]);
  });
  keys_.resize(sorted.size());
  cell_faces_.resize(sorted.size());
  for (std::size_t k = 0; k < sorted.size(); ++k)
    keys_[k] = sorted[k].first, cell_faces_[k] = sorted[k].second;
  for (const std::vector<std::uint32_t>& part : anywhere)
    everywhere_.insert(everywhere_.end(), part.begin(), part.end());
  std::sort(everywhere_.begin(), everywhere_.end());
}

bool ViewGrid::Outline::may_contain(double x, double y) const {
  if (parts == 0) return true;  // not binned (everywhere, or never listed)
  for (int k = 0; k < parts; ++k) {
    const Polygon& p = part[k];
    if (p.orientation == 0) return true;
    bool inside = true;
    for (int i = 0; i < p.n && inside; ++i) {
      // The point may lie up to `margin` (per axis) outside the edge, plus the rounding of this
      // expression.
      const double nx = p.nx[i], ny = p.ny[i];
      const double dx = x - p.x[i], dy = y - p.y[i];
      const double side = nx * dx + ny * dy;
      const double tolerance = margin * (std::fabs(nx) + std::fabs(ny)) +
                               8.0 * epsilon * (std::fabs(nx * dx) + std::fabs(ny * dy));
      inside = side >= -tolerance;
    }
    if (inside) return true;
  }
  return false;
}

glm::dvec3 ViewGrid::project(const glm::dvec3& world) const {
  const glm::dvec3 d = world - eye_;
  const double z = glm::dot(d, forward_);
  return {glm::dot(d, right_) / z, glm::dot(d, up_) / z, z};
}

std::int64_t ViewGrid::cell_of(const glm::dvec3& q) const {
  if (!(q.z > 0.0) || offsets_.size() < 2 || cells_ == 0) return -1;
  std::int64_t index[2];
  for (int k = 0; k < 2; ++k) {
    const double at = std::floor((q[k] - lo_[k]) / cell_size_[k]);
    index[k] = std::int64_t(std::clamp(at, 0.0, double(cells_) - 1.0));
  }
  return index[1] * std::int64_t(cells_) + index[0];
}

float ViewGrid::key_bound(double depth) const {
  if (mode_ == CountingMode::z_pass) return float_above(depth * (1.0 + depth_tolerance));
  return float_above(-depth * (1.0 - depth_tolerance));
}

}  // namespace shadowcts::stencil
