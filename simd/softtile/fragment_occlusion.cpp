// Highway translation unit of the simd softtile's fragment setup (see fragment_occlusion.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/fragment_occlusion.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <limits>

#include "shadowcts/geometry/disk_reach.h"
#include "simd/lane_bits-inl.h"
#include "simd/softtile/disk_bitmask-inl.h"
#include "simd/softtile/fragment_occlusion.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

struct V3 {
  V x, y, z;
};

// glm::cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
HWY_INLINE V3 cross(const V3& a, const V3& b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(b.y, a.z)),
          hn::Sub(hn::Mul(a.z, b.x), hn::Mul(b.z, a.x)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(b.x, a.y))};
}

// glm::dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
HWY_INLINE V dot(const V3& a, const V3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}

// One vector of fragments against a triangle: where it is accepted (the fragment's receiver is
// not the triangle and the reference's triangle_edges() returns true) and its edge functions.
struct VectorEdges {
  M tested;    // the fragment's receiver is not the triangle
  M accepted;  // and triangle_edges() returns true
  V3 e[3];     // valid where accepted
};

// disk_reach() in lanes, its operations in its order.
HWY_INLINE V reach_lanes(D d, V height, V coordinates, float reach_per_height) {
  const V slack = hn::Add(hn::Mul(coordinates, hn::Set(d, 0x1p-18f)), hn::Set(d, 0x1p-120f));
  return hn::Add(hn::Mul(height, hn::Set(d, reach_per_height)), slack);
}

// The lanes whose x range [x0, x1] and y range [y0, y1] lie farther than `reach` from the
// triangle's box on some side: disk_reach.h's beside_disk, its operations in its order.
HWY_INLINE M beside_ranges(D d, V x0, V x1, V y0, V y1, V reach, const LightSpaceBox& box) {
  return hn::Or(hn::Or(hn::Gt(hn::Sub(x0, hn::Set(d, box.x1)), reach),
                       hn::Gt(hn::Sub(hn::Set(d, box.x0), x1), reach)),
                hn::Or(hn::Gt(hn::Sub(y0, hn::Set(d, box.y1)), reach),
                       hn::Gt(hn::Sub(hn::Set(d, box.y0), y1), reach)));
}

// The lanes where the triangle's box lies beside the fragment's disk.
HWY_INLINE M beside_lanes(D d, const FragmentArrays& f, std::size_t j, const LightSpaceBox& box) {
  const V px = hn::LoadU(d, f.x.data() + j), py = hn::LoadU(d, f.y.data() + j),
          pz = hn::LoadU(d, f.z.data() + j);
  const V height = hn::Sub(hn::Set(d, box.z1), pz);
  const V coordinates = hn::Add(hn::Add(hn::Abs(px), hn::Abs(py)), hn::Set(d, box.magnitude));
  const V reach = reach_lanes(d, height, coordinates, f.reach_per_height);
  return hn::And(hn::Gt(height, hn::Zero(d)), beside_ranges(d, px, px, py, py, reach, box));
}

// The lanes of fragments j.. that exist and whose receiver is not the triangle: the reference's
// pixel-triangle tests.
HWY_INLINE M tested_lanes(D d, const FragmentArrays& f, std::size_t j, std::uint32_t triangle) {
  const hn::RebindToUnsigned<D> du;
  return hn::And(
      hn::FirstN(d, f.size - j),
      hn::RebindMask(d, hn::Ne(hn::LoadU(du, f.receiver.data() + j), hn::Set(du, triangle))));
}

// kRotated false: every fragment's grid is unrotated (cos 1, sin 0), and h is (x, y, tz) without
// the rotation's products. c x - s y is then x except that -0 - (+-0) may give +0 where x is -0,
// and likewise for y; a value that differs only in the sign of a zero changes no comparison and no
// division here or in the rasterization (e.x = 0 is handled apart), so the decisions, counts and
// masks are the reference's; only triangle_edges(), whose edges are diffed bit for bit, keeps the
// products.
template <bool kRotated = true>
HWY_INLINE VectorEdges vector_edges(D d, const FragmentArrays& f, std::size_t j,
                                    const std::array<glm::vec3, 3>& light_space,
                                    const LightSpaceBox& box, std::uint32_t triangle) {
  const V zero = hn::Zero(d);
  const V inverse_scale = hn::Set(d, f.inverse_scale);
  VectorEdges out;
  out.tested = tested_lanes(d, f, j, triangle);
  out.accepted = hn::AndNot(beside_lanes(d, f, j, box), out.tested);
  if (hn::AllFalse(d, out.accepted)) return out;
  const V px = hn::LoadU(d, f.x.data() + j), py = hn::LoadU(d, f.y.data() + j),
          pz = hn::LoadU(d, f.z.data() + j);
  V3 h[3];
  M any_front = hn::Lt(zero, zero);  // all false
  for (int i = 0; i < 3; ++i) {
    const V tx = hn::Sub(hn::Set(d, light_space[i].x), px);
    const V ty = hn::Sub(hn::Set(d, light_space[i].y), py);
    const V tz = hn::Sub(hn::Set(d, light_space[i].z), pz);
    const V x = hn::Mul(tx, inverse_scale), y = hn::Mul(ty, inverse_scale);
    if constexpr (kRotated) {
      // Rotating the triangle by the angle rotates the grid by its opposite: the disk is round.
      const V c = hn::LoadU(d, f.cos_rotation.data() + j),
              s = hn::LoadU(d, f.sin_rotation.data() + j);
      h[i] = {hn::Sub(hn::Mul(c, x), hn::Mul(s, y)), hn::Add(hn::Mul(s, x), hn::Mul(c, y)), tz};
    } else {
      h[i] = {x, y, tz};
    }
    any_front = hn::Or(any_front, hn::Gt(tz, zero));
  }
  const V det = dot(h[0], cross(h[1], h[2]));
  // det != 0 and finite: |det| < inf is false for NaN and for infinities.
  out.accepted =
      hn::And(hn::And(out.accepted, any_front),
              hn::And(hn::Ne(det, zero),
                      hn::Lt(hn::Abs(det), hn::Set(d, std::numeric_limits<float>::infinity()))));
  if (hn::AllFalse(d, out.accepted)) return out;
  const V sign = hn::IfThenElse(hn::Gt(det, zero), hn::Set(d, 1.0f), hn::Set(d, -1.0f));
  for (int i = 0; i < 3; ++i) {
    const V3 edge = cross(h[i], h[(i + 1) % 3]);
    out.e[i] = {hn::Mul(sign, edge.x), hn::Mul(sign, edge.y), hn::Mul(sign, edge.z)};
    // The disk lies entirely outside this edge.
    const M outside =
        hn::And(hn::Lt(out.e[i].z, zero),
                hn::Gt(hn::Mul(out.e[i].z, out.e[i].z),
                       hn::Add(hn::Mul(out.e[i].x, out.e[i].x), hn::Mul(out.e[i].y, out.e[i].y))));
    out.accepted = hn::AndNot(outside, out.accepted);
  }
  return out;
}

std::size_t TriangleEdges(const FragmentArrays& f, const std::array<glm::vec3, 3>& light_space,
                          std::uint32_t triangle, std::uint64_t* accepted, float* edges,
                          std::size_t stride) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  // Lanes fill whole bytes of the bit rows (at least 8 float lanes on every target but SCALAR,
  // whose single lane writes one bit of a byte at a time).
  auto* bytes = reinterpret_cast<std::uint8_t*>(accepted);
  std::fill(bytes, bytes + 8 * f.words(), std::uint8_t(0));
  std::size_t tests = 0;
  const LightSpaceBox box = light_space_box(&light_space[0].x);
  for (std::size_t j = 0; j < f.size; j += lanes) {
    const VectorEdges v = vector_edges(d, f, j, light_space, box, triangle);
    tests += hn::CountTrue(d, v.tested);
    if (hn::AllFalse(d, v.accepted)) continue;
    for (int i = 0; i < 3; ++i) {
      hn::StoreU(v.e[i].x, d, edges + (3 * i + 0) * stride + j);
      hn::StoreU(v.e[i].y, d, edges + (3 * i + 1) * stride + j);
      hn::StoreU(v.e[i].z, d, edges + (3 * i + 2) * stride + j);
    }
    if (lanes >= 8) {
      hn::StoreMaskBits(d, v.accepted, bytes + j / 8);
    } else {
      std::uint8_t bits = 0;
      hn::StoreMaskBits(d, v.accepted, &bits);
      bytes[j / 8] |= std::uint8_t(bits << (j % 8));
    }
  }
  return tests;
}

// The blocks first..first + lanes that a fragment of may accept the triangle, as mask bits: the
// triangle's highest vertex lies above the block's lowest fragment (a fragment's tz = v.z - p.z
// rounds to a positive value only where v.z > p.z, and a NaN never does), and its box does not
// lie beside the disk reach at the block's bounds (beside_disk() with the height to the block's
// lowest z and its largest |x| + |y|: each operation rounds monotonically, so that reach is at
// least every fragment's, and every fragment lies within the block's x and y ranges).
HWY_INLINE std::uint64_t blocks_in_reach(D d, const FragmentArrays& f, std::size_t first,
                                         const LightSpaceBox& box) {
  const V z1 = hn::Set(d, box.z1);
  const V lowest = hn::LoadU(d, f.block_lowest_z.data() + first);
  const V height = hn::Sub(z1, lowest);
  const V coordinates =
      hn::Add(hn::LoadU(d, f.block_coordinates.data() + first), hn::Set(d, box.magnitude));
  const V reach = reach_lanes(d, height, coordinates, f.reach_per_height);
  const M beside = beside_ranges(
      d, hn::LoadU(d, f.block_x0.data() + first), hn::LoadU(d, f.block_x1.data() + first),
      hn::LoadU(d, f.block_y0.data() + first), hn::LoadU(d, f.block_y1.data() + first), reach, box);
  return lane_bits(d, hn::AndNot(beside, hn::Gt(z1, lowest)));
}

template <bool kRotated>
HWY_INLINE void occlude_vector(D d, const FragmentArrays& f, std::size_t j,
                               const std::array<glm::vec3, 3>& light_space,
                               const LightSpaceBox& box, std::uint32_t triangle,
                               const DiskRaster::Setup& raster, DiskRows* masks,
                               std::uint64_t* rasterized) {
  const VectorEdges v = vector_edges<kRotated>(d, f, j, light_space, box, triangle);
  if (hn::AllFalse(d, v.accepted)) return;
  HWY_ALIGN float lane_edges[9][HWY_MAX_BYTES / sizeof(float)];
  for (int i = 0; i < 3; ++i) {
    hn::Store(v.e[i].x, d, lane_edges[3 * i + 0]);
    hn::Store(v.e[i].y, d, lane_edges[3 * i + 1]);
    hn::Store(v.e[i].z, d, lane_edges[3 * i + 2]);
  }
  for (std::uint64_t bits = lane_bits(d, v.accepted); bits != 0; bits &= bits - 1) {
    const std::size_t lane = std::size_t(__builtin_ctzll(bits));
    glm::vec3 e[3];
    for (int i = 0; i < 3; ++i)
      e[i] = {lane_edges[3 * i][lane], lane_edges[3 * i + 1][lane], lane_edges[3 * i + 2][lane]};
    ClearTriangleRows(raster, e, 1, masks[j + lane].bits.data());
    ++rasterized[j + lane];
  }
}

// How many fragments lie on `triangle`: one pass over the distinct receivers in lanes (a binary
// search's unpredictable branches took 6 % of the query at foliage.100k).
HWY_INLINE std::size_t fragments_on(const FragmentArrays& f, std::uint32_t triangle) {
  const hn::ScalableTag<std::uint32_t> du;
  const auto wanted = hn::Set(du, triangle);
  auto sum = hn::Zero(du);
  for (std::size_t i = 0; i < f.receiver_ids.size(); i += hn::Lanes(du))
    sum = hn::Add(sum, hn::IfThenElseZero(hn::Eq(hn::LoadU(du, f.receiver_ids.data() + i), wanted),
                                          hn::LoadU(du, f.receiver_counts.data() + i)));
  return hn::GetLane(hn::SumOfLanes(du, sum));
}

template <bool kRotated>
HWY_INLINE std::size_t occlude(const FragmentArrays& f, const std::array<glm::vec3, 3>& light_space,
                               std::uint32_t triangle, const DiskRaster::Setup& raster,
                               DiskRows* masks, std::uint64_t* rasterized) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  const LightSpaceBox box = light_space_box(&light_space[0].x);
  if (lanes > fragment_block) {
    for (std::size_t j = 0; j < f.size; j += lanes)
      occlude_vector<kRotated>(d, f, j, light_space, box, triangle, raster, masks, rasterized);
  } else {
    // The blocks in reach, `lanes` blocks at a time; a block is one vector of fragments or more.
    for (std::size_t first = 0; first < f.blocks(); first += lanes)
      for (std::uint64_t bits = blocks_in_reach(d, f, first, box); bits != 0; bits &= bits - 1) {
        const std::size_t block = first + std::size_t(__builtin_ctzll(bits));
        const std::size_t end = std::min(f.size, (block + 1) * fragment_block);
        for (std::size_t j = block * fragment_block; j < end; j += lanes)
          occlude_vector<kRotated>(d, f, j, light_space, box, triangle, raster, masks, rasterized);
      }
  }
  return f.size - fragments_on(f, triangle);
}

std::size_t OccludeFragments(const FragmentArrays& f, const std::array<glm::vec3, 3>& light_space,
                             std::uint32_t triangle, const DiskRaster::Setup& raster,
                             DiskRows* masks, std::uint64_t* rasterized) {
  return f.rotated ? occlude<true>(f, light_space, triangle, raster, masks, rasterized)
                   : occlude<false>(f, light_space, triangle, raster, masks, rasterized);
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd::softtile
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::softtile {

HWY_EXPORT(TriangleEdges);
HWY_EXPORT(OccludeFragments);

void FragmentArrays::assign(const std::vector<shadowcts::softtile::FragmentSetup>& fragments,
                            const std::vector<std::uint32_t>& receivers) {
  size = fragments.size();
  const std::size_t padded = (size + fragment_padding - 1) / fragment_padding * fragment_padding;
  for (std::vector<float>* v : {&x, &y, &z, &cos_rotation, &sin_rotation}) v->assign(padded, 0.0f);
  receiver.assign(padded, 0u);
  for (std::size_t j = 0; j < size; ++j) {
    receiver[j] = receivers[j];
    x[j] = fragments[j].position.x;
    y[j] = fragments[j].position.y;
    z[j] = fragments[j].position.z;
    cos_rotation[j] = fragments[j].cos_rotation;
    sin_rotation[j] = fragments[j].sin_rotation;
  }
  if (size != 0) {
    inverse_scale = fragments[0].inverse_scale;
    reach_per_height = fragments[0].reach_per_height;
  }
  rotated = false;
  for (std::size_t j = 0; j < size; ++j)
    rotated = rotated || cos_rotation[j] != 1.0f || sin_rotation[j] != 0.0f;
  // Sorted in place, then each run of equal receivers kept once with its length.
  receiver_ids.assign(receiver.begin(), receiver.begin() + std::ptrdiff_t(size));
  std::sort(receiver_ids.begin(), receiver_ids.end());
  receiver_counts.clear();
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < size; ++k) {
    if (distinct == 0 || receiver_ids[distinct - 1] != receiver_ids[k]) {
      receiver_ids[distinct++] = receiver_ids[k];
      receiver_counts.push_back(0);
    }
    ++receiver_counts.back();
  }
  const std::size_t padded_ids = (distinct + 15) / 16 * 16;
  receiver_ids.resize(padded_ids, 0u);
  receiver_counts.resize(padded_ids, 0u);
  // Padded for whole vectors of blocks (16 lanes at most) with blocks below every triangle.
  const std::size_t blocks = (this->blocks() + 15) / 16 * 16;
  constexpr float infinity = std::numeric_limits<float>::infinity();
  block_lowest_z.assign(blocks, infinity);
  block_x0.assign(blocks, infinity);
  block_y0.assign(blocks, infinity);
  block_x1.assign(blocks, -infinity);
  block_y1.assign(blocks, -infinity);
  block_coordinates.assign(blocks, 0.0f);
  for (std::size_t j = 0; j < size; ++j) {
    const std::size_t b = j / fragment_block;
    // Comparisons that a NaN fails leave the bounds alone.
    if (z[j] < block_lowest_z[b]) block_lowest_z[b] = z[j];
    if (x[j] < block_x0[b]) block_x0[b] = x[j];
    if (x[j] > block_x1[b]) block_x1[b] = x[j];
    if (y[j] < block_y0[b]) block_y0[b] = y[j];
    if (y[j] > block_y1[b]) block_y1[b] = y[j];
    const float coordinates = float_magnitude(x[j]) + float_magnitude(y[j]);
    if (coordinates > block_coordinates[b]) block_coordinates[b] = coordinates;
  }
}

std::size_t triangle_edges(const FragmentArrays& fragments,
                           const std::array<glm::vec3, 3>& light_space, std::uint32_t triangle,
                           std::uint64_t* accepted, float* edges, std::size_t stride) {
  return HWY_DYNAMIC_DISPATCH(TriangleEdges)(fragments, light_space, triangle, accepted, edges,
                                             stride);
}

std::size_t occlude_fragments(const FragmentArrays& fragments,
                              const std::array<glm::vec3, 3>& light_space, std::uint32_t triangle,
                              const DiskRaster& raster, DiskRows* masks,
                              std::uint64_t* rasterized) {
  return HWY_DYNAMIC_DISPATCH(OccludeFragments)(fragments, light_space, triangle, raster.setup(),
                                                masks, rasterized);
}

}  // namespace shadowcts::simd::softtile
#endif  // HWY_ONCE
