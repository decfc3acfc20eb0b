#pragma once
// The per-fragment disk bitmask of the post: one 32-bit word per scanline, a set bit meaning "this
// cell of the sun disk is lit". Column 0 is the most significant used bit, so shifting a full row
// right by n clears the n leftmost cells: the post's shift trick. Cells are sampled at their
// centres over [-1, 1]^2 (disk space; the disk is the unit disk).
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/softtile/softtile_variant.h"

namespace shadowcts::softtile {

class DiskBitmask {
 public:
  static constexpr int max_rows = 31;

  // The lit disk of the variant: for the 16 x 16 grid the post's literal mask (208 cells), for
  // N x 31 rows every cell whose centre lies in the closed unit disk.
  explicit DiskBitmask(const Variant& variant);

  int rows() const { return rows_; }
  int columns() const { return columns_; }
  std::uint32_t row(int r) const { return bits_[r]; }
  // Cells of the disk (lit when nothing occludes).
  int disk_cells() const { return disk_cells_; }
  int lit_cells() const;

  // Clears the cells inside the triangle given by its three edge functions: a cell centre (X, Y)
  // is inside when edge.x X + edge.y Y + edge.z >= 0 for all three (ties: the cell left of an edge
  // crossing exactly at its centre counts as outside when the inside is to the left). Per
  // scanline: each edge's crossing, a shifted full row for its outside cells, OR over the edges,
  // AND into the row.
  void clear_triangle(const std::array<glm::vec3, 3>& edges);

 private:
  int rows_, columns_;
  std::uint32_t full_row_;
  int disk_cells_ = 0;
  std::array<std::uint32_t, max_rows> bits_{};
};

}  // namespace shadowcts::softtile
