#include "reference/shadowmap/rasterizer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shadowcts/phase_progress.h"

namespace shadowcts::shadowmap {
namespace {

constexpr int subpixel_bits = 8;  // like GPUs: vertices snap to 1/256 texel
constexpr std::int64_t subpixel = std::int64_t(1) << subpixel_bits;
constexpr std::uint32_t band_rows = 32;

// A convex polygon in view space during clipping: a triangle clipped by five planes has at most
// eight vertices.
struct ClipPolygon {
  std::array<glm::dvec3, 9> v;
  int size = 0;
};

// Keeps the part of `in` where f(v) >= 0 (Sutherland-Hodgman).
template <class PlaneFunction>
ClipPolygon clip(const ClipPolygon& in, PlaneFunction f) {
  ClipPolygon out;
  for (int i = 0; i < in.size; ++i) {
    const glm::dvec3& a = in.v[i];
    const glm::dvec3& b = in.v[(i + 1) % in.size];
    const double fa = f(a), fb = f(b);
    if (fa >= 0.0) out.v[out.size++] = a;
    if ((fa >= 0.0) != (fb >= 0.0)) out.v[out.size++] = a + (fa / (fa - fb)) * (b - a);
  }
  return out;
}

// A snapped triangle ready for filling, with positive area and its texel bounds.
struct RasterTriangle {
  std::int64_t x[3], y[3];
  double attribute[3];  // 1/z (perspective) or z (orthographic) at each vertex
  std::int64_t area;    // twice the signed area, > 0
  bool top_left[3];     // edge i runs from vertex i to vertex (i + 1) % 3
  std::int32_t column_min, column_max, row_min, row_max;
};

std::int64_t edge_function(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by,
                           std::int64_t px, std::int64_t py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Texel index range whose centres (i * 256 + 128) lie in [lo, hi] (fixed point).
std::int32_t first_centre(std::int64_t lo) {
  const std::int64_t shifted = lo - subpixel / 2;
  return std::int32_t(shifted >= 0 ? (shifted + subpixel - 1) / subpixel
                                   : -((-shifted) / subpixel));
}
std::int32_t last_centre(std::int64_t hi) {
  const std::int64_t shifted = hi - subpixel / 2;
  return std::int32_t(shifted >= 0 ? shifted / subpixel : -((-shifted + subpixel - 1) / subpixel));
}

// Clips one caster and appends its fan triangles; returns whether anything is left to fill.
bool set_up_triangle(const LightView& view, const Triangle& t, std::vector<RasterTriangle>& out) {
  ClipPolygon polygon;
  polygon.v[0] = view.to_view(glm::dvec3(t.v0));
  polygon.v[1] = view.to_view(glm::dvec3(t.v1));
  polygon.v[2] = view.to_view(glm::dvec3(t.v2));
  polygon.size = 3;
  // One texel of guard band: clip edges then lie outside every texel centre of the map.
  const double guard = 1.0 + 2.0 / double(view.resolution);
  if (view.perspective) {
    polygon = clip(polygon, [&](const glm::dvec3& v) { return v.z - view.near; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return guard * v.z - v.x; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return guard * v.z + v.x; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return guard * v.z - v.y; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return guard * v.z + v.y; });
  } else {
    const double h = guard * view.half_extent;
    polygon = clip(polygon, [&](const glm::dvec3& v) { return h - v.x; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return h + v.x; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return h - v.y; });
    polygon = clip(polygon, [&](const glm::dvec3& v) { return h + v.y; });
  }
  if (polygon.size < 3) return false;

  std::array<std::int64_t, 9> sx{}, sy{};
  std::array<double, 9> attribute{};
  for (int i = 0; i < polygon.size; ++i) {
    const glm::dvec2 r = view.to_raster(polygon.v[i]);
    sx[i] = std::llround(r.x * double(subpixel));
    sy[i] = std::llround(r.y * double(subpixel));
    attribute[i] = view.perspective ? 1.0 / polygon.v[i].z : polygon.v[i].z;
  }
  const std::int32_t n = std::int32_t(view.resolution);
  bool any = false;
  for (int k = 1; k + 1 < polygon.size; ++k) {
    RasterTriangle r;
    int index[3] = {0, k, k + 1};
    std::int64_t area = edge_function(sx[0], sy[0], sx[k], sy[k], sx[k + 1], sy[k + 1]);
    if (area == 0) continue;  // collapsed by snapping: covers no texel centre
    if (area < 0) std::swap(index[1], index[2]), area = -area;
    for (int i = 0; i < 3; ++i) {
      r.x[i] = sx[index[i]], r.y[i] = sy[index[i]], r.attribute[i] = attribute[index[i]];
    }
    r.area = area;
    for (int i = 0; i < 3; ++i) {
      const std::int64_t dx = r.x[(i + 1) % 3] - r.x[i], dy = r.y[(i + 1) % 3] - r.y[i];
      // With positive area (x right, y down) the interior is where every edge function is > 0:
      // a top edge is horizontal with the interior below it (dx > 0), a left edge has the
      // interior on its right (dy < 0).
      r.top_left[i] = (dy == 0 && dx > 0) || dy < 0;
    }
    r.column_min = std::max(0, first_centre(std::min({r.x[0], r.x[1], r.x[2]})));
    r.column_max = std::min(n - 1, last_centre(std::max({r.x[0], r.x[1], r.x[2]})));
    r.row_min = std::max(0, first_centre(std::min({r.y[0], r.y[1], r.y[2]})));
    r.row_max = std::min(n - 1, last_centre(std::max({r.y[0], r.y[1], r.y[2]})));
    if (r.column_min > r.column_max || r.row_min > r.row_max) continue;
    out.push_back(r);
    any = true;
  }
  return any;
}

// Fills the kept texels of rows [row_begin, row_end) of one triangle; returns the number of depth
// writes. Edge functions are integers: e at column c is e at column_min plus (c - column_min)
// steps exactly, whichever texels are kept.
std::uint64_t fill(const RasterTriangle& r, bool perspective, std::int32_t row_begin,
                   std::int32_t row_end, DepthMap& map) {
  const std::int32_t rows_lo = std::max(r.row_min, row_begin);
  const std::int32_t rows_hi = std::min(r.row_max, row_end - 1);
  if (rows_lo > rows_hi) return 0;
  std::uint64_t written = 0;
  const std::int64_t px0 = std::int64_t(r.column_min) * subpixel + subpixel / 2;
  const double inverse_area = 1.0 / double(r.area);
  const auto column_min = std::uint32_t(r.column_min), column_max = std::uint32_t(r.column_max);
  for (std::int32_t row = rows_lo; row <= rows_hi; ++row) {
    const auto first = map.column.begin() + map.row_start[std::size_t(row)];
    const auto last = map.column.begin() + map.row_start[std::size_t(row) + 1];
    auto kept = std::lower_bound(first, last, column_min);
    if (kept == last || *kept > column_max) continue;
    const std::int64_t py = std::int64_t(row) * subpixel + subpixel / 2;
    std::int64_t e0[3], step[3];
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      // Integer edge function with the fill rule folded in: inside iff e >= 0.
      e0[i] = edge_function(r.x[i], r.y[i], r.x[j], r.y[j], px0, py) - (r.top_left[i] ? 0 : 1);
      step[i] = -(r.y[j] - r.y[i]) * subpixel;
    }
    for (; kept != last && *kept <= column_max; ++kept) {
      const auto steps = std::int64_t(*kept - column_min);
      std::int64_t e[3];
      for (int i = 0; i < 3; ++i) e[i] = e0[i] + steps * step[i];
      if ((e[0] | e[1] | e[2]) < 0) continue;
      // Edge i is opposite vertex (i + 2) % 3; undo the fill-rule offset for the weights.
      const double w2 = double(e[0] + (r.top_left[0] ? 0 : 1)) * inverse_area;
      const double w0 = double(e[1] + (r.top_left[1] ? 0 : 1)) * inverse_area;
      const double w1 = double(e[2] + (r.top_left[2] ? 0 : 1)) * inverse_area;
      const double a = w0 * r.attribute[0] + w1 * r.attribute[1] + w2 * r.attribute[2];
      const float depth = float(perspective ? 1.0 / a : a);
      float& stored = map.depth[std::size_t(kept - map.column.begin())];
      if (depth < stored) {
        stored = depth;
        ++written;
      }
    }
  }
  return written;
}

}  // namespace

RasterCounters rasterize_depth(const LightView& view, const std::vector<Triangle>& casters,
                               DepthMap& map) {
  RasterCounters counters;
  // Set-up per caster in parallel, gathered in caster order.
  std::vector<std::vector<RasterTriangle>> per_caster(casters.size());
  std::atomic<std::uint64_t> rasterized{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, casters.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::uint64_t count = 0;
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        count += set_up_triangle(view, casters[i], per_caster[i]);
                      rasterized += count;
                    });
  std::vector<RasterTriangle> triangles;
  for (const auto& list : per_caster) triangles.insert(triangles.end(), list.begin(), list.end());
  per_caster.clear();
  counters.triangles_rasterized = rasterized.load();

  // Bands own disjoint rows, so they write disjoint texels; the minimum does not depend on the
  // order anyway, and each band's write count is that of a fixed triangle order.
  const std::uint32_t bands = (view.resolution + band_rows - 1) / band_rows;
  std::atomic<std::uint64_t> written{0};
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, bands, 1),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      std::uint64_t count = 0;
                      for (std::uint32_t b = range.begin(); b != range.end(); ++b) {
                        const auto row_begin = std::int32_t(b * band_rows);
                        const auto row_end =
                            std::int32_t(std::min(view.resolution, (b + 1) * band_rows));
                        const bool any_kept = map.row_start[std::size_t(row_begin)] !=
                                              map.row_start[std::size_t(row_end)];
                        for (const RasterTriangle& r : triangles)
                          if (any_kept && r.row_max >= row_begin && r.row_min < row_end)
                            count += fill(r, view.perspective, row_begin, row_end, map);
                        phase_progress::advance(std::uint64_t(row_end - row_begin));
                      }
                      written += count;
                    });
  counters.texels_written = written.load();
  return counters;
}

}  // namespace shadowcts::shadowmap
