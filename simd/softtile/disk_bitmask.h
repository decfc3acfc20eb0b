#pragma once
// The simd port of the reference's disk bitmask rasterization (reference/softtile/disk_bitmask.h):
// rows of the mask in lanes, one triangle's three edge functions broadcast per vector. Every lane
// computes its scanline's edge crossings with the reference's float operations in the
// reference's order (y e.y + e.z, -offset / e.x, (X* + 1) columns / 2 - 0.5, ceil), so the masks
// are the reference's bit for bit. disk_bitmask.cpp is the one Highway translation unit of the
// simd softtile (compiled once per target by foreach_target, dispatched at run time).
#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/softtile/softtile_variant.h"

namespace shadowcts::simd::softtile {

// Rows padded to the widest vector (16 lanes): rows past the variant's stay 0.
inline constexpr int padded_rows = 32;

struct alignas(64) DiskRows {
  std::array<std::uint32_t, padded_rows> bits{};
  int lit_cells() const;
};

// What the rasterization of one variant reads: the scanline centres and the lit disk.
class DiskRaster {
 public:
  explicit DiskRaster(const shadowcts::softtile::Variant& variant);

  int rows() const { return rows_; }
  int columns() const { return columns_; }
  const DiskRows& empty_disk() const { return empty_; }
  int disk_cells() const { return disk_cells_; }

  // Clears from `mask` each of the `count` triangles whose edge functions are edges[3 i],
  // edges[3 i + 1], edges[3 i + 2] (as DiskBitmask::clear_triangle, one after the other).
  void clear_triangles(const glm::vec3* edges, std::size_t count, DiskRows& mask) const;

  // For the kernels (disk_bitmask-inl.h).
  struct Setup {
    alignas(64) float y[padded_rows];  // scanline centres, the reference's float expression
    std::uint32_t full_row;
    int rows, columns;
    float half_columns;
  };

  const Setup& setup() const { return setup_; }

 private:
  int rows_, columns_, disk_cells_;
  DiskRows empty_;
  Setup setup_;
};

}  // namespace shadowcts::simd::softtile
