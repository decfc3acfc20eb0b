#pragma once
// Software depth rasterizer for one light view: clips each caster triangle to the view (near
// plane and a one-texel guard band around the map), snaps the vertices to 1/256 texel, and
// fills texel centres by integer edge functions with the top-left fill rule (a centre exactly
// on an edge belongs to the triangle only if the edge is a top or a left edge, so two triangles
// sharing an edge never both cover it and never both miss it). Depth is the view-space forward
// distance, interpolated perspective-correctly (1/z is linear in raster space), and the map
// keeps the minimum.
#include <cstdint>
#include <vector>

#include "reference/shadowmap/depth_map.h"
#include "reference/shadowmap/light_view.h"
#include "shadowcts/case.h"

namespace shadowcts::shadowmap {

struct RasterCounters {
  std::uint64_t triangles_rasterized = 0;  // casters with a non-empty clipped polygon
  std::uint64_t texels_written = 0;        // depth-test passes (stores into the kept texels)
};

// Rasterizes `casters` into the texels `map` keeps (reset by the caller to the view's
// resolution). Parallel over bands of rows with oneTBB; every band processes the triangles in the
// given order, so the map and the counters do not depend on the number of threads.
RasterCounters rasterize_depth(const LightView& view, const std::vector<Triangle>& casters,
                               DepthMap& map);

}  // namespace shadowcts::shadowmap
