// A Highway TU of the simd ptsv (the other: triangle_setup.cpp): child-bound and sample tests in
// lanes, and the level-by-level traversal around them (compiled once per target, dispatched once
// per run).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/ptsv/traversal.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/ptsv/node_test.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/huge_pages.h"
#include "shadowcts/phase_progress.h"
#include "simd/lane_bits-inl.h"
#include "simd/ptsv/traversal.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::ptsv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

// What the progress line counts the visits of (static strings: phase_progress keeps the pointer).
inline const char* level_name(int level) {
  static constexpr const char* names[] = {
      "hierarchy level 0",  "hierarchy level 1",  "hierarchy level 2",  "hierarchy level 3",
      "hierarchy level 4",  "hierarchy level 5",  "hierarchy level 6",  "hierarchy level 7",
      "hierarchy level 8",  "hierarchy level 9",  "hierarchy level 10", "hierarchy level 11",
      "hierarchy level 12", "hierarchy level 13", "hierarchy level 14", "hierarchy level 15"};
  return level >= 0 && level < int(std::size(names)) ? names[level] : "a hierarchy level";
}

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

// Child verdicts of one visit, bit r = the child of rank r (children in key order).
struct Verdicts {
  std::uint32_t accept, refine, reject, cull;
};

// plane.at(x) as the reference evaluates it: ((nx (x - ax) + ny (y - ay)) + nz (z - az)) + shift,
// separate multiplies and adds (no FMA).
HWY_INLINE V plane_at(const V& nx, const V& ny, const V& nz, const V& ax, const V& ay, const V& az,
                      const V& shift, const V& x, const V& y, const V& z) {
  return hn::Add(hn::Add(hn::Add(hn::Mul(nx, hn::Sub(x, ax)), hn::Mul(ny, hn::Sub(y, ay))),
                         hn::Mul(nz, hn::Sub(z, az))),
                 shift);
}

struct PlaneLanes {
  V nx, ny, nz, ax, ay, az, shift;
};

// Plane k of the volume: 0-3 the edges and the triangle (shift 0), 4 + m culling plane m.
HWY_INLINE PlaneLanes plane_lanes(D d, const PackedVolume& vol, int k) {
  if (k < 4) {
    const int v = PackedVolume::anchor[k];
    return {hn::Set(d, vol.normal[k][0]),
            hn::Set(d, vol.normal[k][1]),
            hn::Set(d, vol.normal[k][2]),
            hn::Set(d, vol.vertex(v, 0)),
            hn::Set(d, vol.vertex(v, 1)),
            hn::Set(d, vol.vertex(v, 2)),
            hn::Zero(d)};
  }
  const int m = k - 4;
  return {hn::Set(d, vol.extra[m][0]),  hn::Set(d, vol.extra[m][1]),  hn::Set(d, vol.extra[m][2]),
          hn::Set(d, vol.vertex(m, 0)), hn::Set(d, vol.vertex(m, 1)), hn::Set(d, vol.vertex(m, 2)),
          hn::Set(d, vol.extra[m][3])};
}

HWY_INLINE const double* plane_normal(const PackedVolume& vol, int k) {
  return k < 4 ? vol.normal[k] : vol.extra[k - 4];
}

// The cache lines the lane tests read from a volume.
HWY_INLINE void prefetch(const PackedVolume& vol) {
  const char* p = reinterpret_cast<const char*>(&vol);
  for (std::size_t line = 0; line < sizeof(PackedVolume); line += 64) __builtin_prefetch(p + line);
}

// A node's visitors [begin, end) in the ordered pass and the scatter (Engine::run).
struct Segment {
  static constexpr std::uint32_t alone = ~0u;
  std::uint32_t node, begin, end;
  std::uint32_t mask;   // a split node's mask before the segment's first visitor
  std::uint32_t split;  // its entry in the level's per-segment child counts, or alone
};
// Small enough that the 20k-triangle test fixtures split their top nodes too; a segment's own
// work (an OR pass and 32 counts) is small against 4096 visits.
constexpr std::uint32_t segment_visits = 4096;

class Engine {
 public:
  Engine(const TraversalInputs& in, std::uint8_t* shadowed)
      : in_(in),
        h_(*in.hierarchy),
        vols_(*in.volumes),
        shadowed_(shadowed),
        culling_(in.config.extra_planes) {}

  // ref::classify_node for the children [first, first + count) of level `level` that `live` names,
  // bounded by implicit cells (their 8 corners). Its verdict is the same whichever plane is tested
  // first, so the lanes stop at the first plane that rejects all of them.
  Verdicts test_children_implicit(const PackedVolume& vol, int level, std::uint32_t first,
                                  std::uint32_t count, std::uint32_t live) const {
    const D d;
    const std::uint32_t lanes = std::uint32_t(hn::Lanes(d));
    const Level& L = h_.levels[std::size_t(level)];
    const ref::NodeTolerances& tol = in_.tolerances;
    const V rounding = hn::Set(d, tol.rounding);
    const std::uint32_t culling = culling_ ? vol.extra_mask : 0u;
    // 64-bit words, not a Verdicts: the accumulators live on the stack (the corner pointers take
    // the registers), and 32-bit fields or-ed there were read back with 64-bit loads into the
    // return registers, a failed store forward on every visit (12 % of this function's samples).
    std::uint64_t reject = 0, accept = 0, cull = 0, refine = 0;
    for (std::uint32_t base = 0; base < count; base += lanes) {
      const std::uint32_t lanes_mask = lanes >= 32 ? ~0u : ((1u << lanes) - 1u);
      const std::uint32_t wanted = (live >> base) & lanes_mask;
      if (wanted == 0) continue;
      const std::size_t at = first + base;
      V high[4];  // the largest corner value, kept from the reject pass
      // The lowest and highest value of plane k over the cells' corners.
      const auto range = [&](int k, V& low, V& hi) {
        const PlaneLanes p = plane_lanes(d, vol, k);
        for (std::size_t c = 0; c < 8; ++c) {
          const V value = plane_at(p.nx, p.ny, p.nz, p.ax, p.ay, p.az, p.shift,
                                   hn::LoadU(d, L.corner[c * 3 + 0].data() + at),
                                   hn::LoadU(d, L.corner[c * 3 + 1].data() + at),
                                   hn::LoadU(d, L.corner[c * 3 + 2].data() + at));
          low = c == 0 ? value : hn::Min(low, value);
          hi = c == 0 ? value : hn::Max(hi, value);
        }
      };
      std::uint32_t rej = 0;
      for (int k = 0; k < 4 && rej != wanted; ++k) {
        V low = hn::Zero(d);
        high[k] = hn::Zero(d);
        range(k, low, high[k]);
        rej |= lane_bits(d, hn::Gt(low, rounding)) & wanted;
      }
      reject |= rej << base;
      if (rej == wanted) continue;
      // Accepted: every corner inside all four planes (each plane's highest value is known: the
      // reject pass ran all four), by the rounding (the triangle plane also by the accept bias
      // and by the reject reach of the node's samples).
      std::uint32_t acc = wanted & ~rej;
      for (int k = 0; k < 4 && acc != 0; ++k) {
        if (k < 3) {
          acc &= lane_bits(d, hn::Lt(high[k], hn::Set(d, -tol.rounding)));
        } else {
          const V reach_inside = hn::Neg(hn::Add(rounding, hn::LoadU(d, L.reach.data() + at)));
          acc &=
              lane_bits(d, hn::And(hn::Lt(high[k], hn::Set(d, -(tol.rounding + tol.accept_bias))),
                                   hn::Lt(high[k], reach_inside)));
        }
      }
      accept |= acc << base;
      const std::uint32_t rest = wanted & ~rej & ~acc;
      std::uint32_t cul = 0;
      for (std::uint32_t planes = culling; planes != 0 && cul != rest; planes &= planes - 1) {
        V low = hn::Zero(d), unused = hn::Zero(d);
        range(4 + std::countr_zero(planes), low, unused);
        cul |= lane_bits(d, hn::Gt(low, rounding)) & rest;
      }
      cull |= cul << base;
      refine |= (rest & ~cul) << base;
    }
    return Verdicts{std::uint32_t(accept), std::uint32_t(refine), std::uint32_t(reject),
                    std::uint32_t(cull)};
  }

  // The same for explicit bounds, with each plane's lanes and corner choice set up once per
  // visit instead of once per group of children (measured: about a tenth less time in the node
  // tests).
  Verdicts test_children_explicit(const PackedVolume& vol, int level, std::uint32_t first,
                                  std::uint32_t count, std::uint32_t live) const {
    const D d;
    const std::uint32_t lanes = std::uint32_t(hn::Lanes(d));
    const Level& L = h_.levels[std::size_t(level)];
    const ref::NodeTolerances& tol = in_.tolerances;
    const V rounding = hn::Set(d, tol.rounding);
    const V inside_edge = hn::Set(d, -tol.rounding);
    const V inside_triangle = hn::Set(d, -(tol.rounding + tol.accept_bias));
    const std::uint32_t culling = culling_ ? vol.extra_mask : 0u;
    PlaneLanes p[4];
    // Per plane and axis: the reject point's coordinate array, then the accept point's.
    const double* corner[4][2][3];
    for (int k = 0; k < 4; ++k) {
      p[k] = plane_lanes(d, vol, k);
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const bool positive = vol.normal[k][axis] >= 0.0;
        corner[k][0][axis] = (positive ? L.lo[axis] : L.hi[axis]).data() + first;
        corner[k][1][axis] = (positive ? L.hi[axis] : L.lo[axis]).data() + first;
      }
    }
    const auto value = [&](const PlaneLanes& q, const double* const* at, std::size_t base) {
      return plane_at(q.nx, q.ny, q.nz, q.ax, q.ay, q.az, q.shift, hn::LoadU(d, at[0] + base),
                      hn::LoadU(d, at[1] + base), hn::LoadU(d, at[2] + base));
    };
    std::uint64_t reject = 0, accept = 0, cull = 0, refine = 0;  // as in test_children_implicit
    for (std::uint32_t base = 0; base < count; base += lanes) {
      const std::uint32_t lanes_mask = lanes >= 32 ? ~0u : ((1u << lanes) - 1u);
      const std::uint32_t wanted = (live >> base) & lanes_mask;
      if (wanted == 0) continue;
      std::uint32_t rej = 0;
      for (int k = 0; k < 4 && rej != wanted; ++k)
        rej |= lane_bits(d, hn::Gt(value(p[k], corner[k][0], base), rounding)) & wanted;
      reject |= rej << base;
      if (rej == wanted) continue;
      std::uint32_t acc = wanted & ~rej;
      for (int k = 0; k < 3 && acc != 0; ++k)
        acc &= lane_bits(d, hn::Lt(value(p[k], corner[k][1], base), inside_edge));
      if (acc != 0) {
        const V high = value(p[3], corner[3][1], base);
        const V reach_inside =
            hn::Neg(hn::Add(rounding, hn::LoadU(d, L.reach.data() + first + base)));
        acc &= lane_bits(d, hn::And(hn::Lt(high, inside_triangle), hn::Lt(high, reach_inside)));
      }
      accept |= acc << base;
      const std::uint32_t rest = wanted & ~rej & ~acc;
      std::uint32_t cul = 0;
      for (std::uint32_t planes = culling; planes != 0 && cul != rest; planes &= planes - 1) {
        const int k = 4 + std::countr_zero(planes);
        const PlaneLanes q = plane_lanes(d, vol, k);
        const double* at[3];
        for (std::size_t axis = 0; axis < 3; ++axis)
          at[axis] = (plane_normal(vol, k)[axis] >= 0.0 ? L.lo[axis] : L.hi[axis]).data() + first;
        cul |= lane_bits(d, hn::Gt(value(q, at, base), rounding)) & rest;
      }
      cull |= cul << base;
      refine |= (rest & ~cul) << base;
    }
    return Verdicts{std::uint32_t(accept), std::uint32_t(refine), std::uint32_t(reject),
                    std::uint32_t(cull)};
  }

  // TESTVIEWSAMPLES: every sample of the leaf's tile against the volume.
  void test_samples(const PackedVolume& vol, std::uint32_t leaf) const {
    const D d;
    const std::uint32_t lanes = std::uint32_t(hn::Lanes(d));
    const std::uint32_t tile = h_.leaf_tile[leaf];
    const std::uint32_t begin = h_.tile_offsets[tile], end = h_.tile_offsets[tile + 1];
    // The planes' lanes once per tile (up to 8 groups of samples), not once per group.
    PlaneLanes planes[4];
    V factor[4];
    for (int k = 0; k < 4; ++k) {
      planes[k] = plane_lanes(d, vol, k);
      factor[k] = hn::Set(d, 0x1p-44 * (1.0 + double(vol.condition[k])));
    }
    // Built only for a sample within rounding of a plane (rare; it is large to initialize).
    std::optional<ref::ShadowVolume> exact;
    for (std::uint32_t base = begin; base < end; base += lanes) {
      const std::uint32_t n = std::min(lanes, end - base);
      const V x = hn::LoadU(d, h_.tile_pos[0].data() + base);
      const V y = hn::LoadU(d, h_.tile_pos[1].data() + base);
      const V z = hn::LoadU(d, h_.tile_pos[2].data() + base);
      const std::uint32_t all = (n >= 32 ? 0u : (1u << n)) - 1u;
      std::uint32_t outside = 0, unsure[4] = {0, 0, 0, 0};
      for (int k = 0; k < 4 && (outside & all) != all; ++k) {
        // ref::outside_plane: the value against its rounding bound.
        const PlaneLanes& p = planes[k];
        const V ox = hn::Sub(x, p.ax), oy = hn::Sub(y, p.ay), oz = hn::Sub(z, p.az);
        const V value = hn::Add(
            hn::Add(hn::Add(hn::Mul(p.nx, ox), hn::Mul(p.ny, oy)), hn::Mul(p.nz, oz)), p.shift);
        const V bound = hn::Mul(factor[k], hn::Add(hn::Add(hn::Abs(ox), hn::Abs(oy)), hn::Abs(oz)));
        const std::uint32_t out_k = lane_bits(d, hn::Gt(value, bound));
        const std::uint32_t in_k = lane_bits(d, hn::Lt(value, hn::Neg(bound)));
        outside |= out_k;
        unsure[k] = ~(out_k | in_k);
      }
      std::uint32_t candidates = ~outside & all;
      while (candidates != 0) {
        const std::uint32_t j = std::uint32_t(std::countr_zero(candidates));
        candidates &= candidates - 1;
        const std::uint32_t s = h_.tile_sample[base + j];
        const std::uint32_t receiver = in_.scene->samples.receiver[s];
        if (receiver == vol.triangle) continue;  // its own receiver never shadows it
        const glm::vec3 position(float(h_.tile_pos[0][base + j]), float(h_.tile_pos[1][base + j]),
                                 float(h_.tile_pos[2][base + j]));
        bool inside = true;
        for (int k = 0; k < 4 && inside; ++k) {
          if (((unsure[k] >> j) & 1u) == 0) continue;
          if (!exact) vol.exact_volume(exact.emplace(), vols_.directional, vols_.light);
          inside = !ref::outside_plane_exactly(*exact, k, position);
        }
        if (!inside) continue;
        std::atomic_ref<std::uint8_t> bit(shadowed_[in_.scene->samples.index[s]]);
        if (bit.load(std::memory_order_relaxed) != 0) continue;
        // ref::ReceiverRule::caster_counts, on the same inputs.
        const Triangle& t = in_.source->triangles[vol.triangle];
        if (geometry::caster_counts(in_.rule->half_space(receiver), glm::dvec3(position),
                                    glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)))
          bit.fetch_or(1, std::memory_order_relaxed);
      }
    }
  }

  void run(ref::TraversalCounters& counters) {
    const int leaves = h_.leaf_level();
    std::vector<std::vector<std::uint32_t>> live(std::size_t(leaves) + 1);
    for (int l = 0; l <= leaves; ++l) {
      const Level& L = h_.levels[std::size_t(l)];
      live[std::size_t(l)].resize(L.size());
      for (std::size_t p = 0; p < L.size(); ++p) {
        const int count = std::popcount(L.child_mask[p]);
        live[std::size_t(l)][p] = count >= 32 ? ~0u : ((1u << count) - 1u);
      }
    }
    // Visitors of level 0: every volume, in order.
    std::vector<std::uint32_t> offsets = {0, std::uint32_t(vols_.order.size())};
    HugePageVector<std::uint32_t> visitors(vols_.order.begin(), vols_.order.end());
    // Per visit of a level; reused from level to level (every entry is written before it is read).
    HugePageVector<Verdicts> verdicts;
    HugePageVector<std::uint32_t> remaining;
    std::atomic<std::uint64_t> node_tests{0}, sample_tests{0}, accepts{0}, rejects{0}, culls{0};
    for (int l = 0; l <= leaves; ++l) {
      const Level& L = h_.levels[std::size_t(l)];
      const std::uint64_t visits = offsets.back();
      counters.nodes_visited += visits;
      if (l == in_.config.job_level) {
        counters.first_pass_jobs += visits;
        counters.second_pass_jobs += visits;
      }
      // Breadth first: a level's visits are known when it starts, not the next level's.
      if (visits != 0) phase_progress::begin(visits, "volume visits", level_name(l));
      if (l == leaves) {
        std::uint64_t tests = 0;
        for (std::size_t p = 0; p < L.size(); ++p) {
          const std::uint32_t tile = h_.leaf_tile[p];
          tests += std::uint64_t(h_.tile_offsets[tile + 1] - h_.tile_offsets[tile]) *
                   (offsets[p + 1] - offsets[p]);
        }
        sample_tests += tests;
        // One flat range over all visits (a leaf has 5 to 50 visitors on average, too few for a
        // task of its own); a range finds its first leaf by bisection.
        tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(visits), 32),
                          [&](const tbb::blocked_range<std::uint32_t>& v) {
                            std::size_t p = std::size_t(std::upper_bound(offsets.begin(),
                                                                         offsets.end(), v.begin()) -
                                                        offsets.begin()) -
                                            1;
                            for (std::uint32_t i = v.begin(); i != v.end(); ++i) {
                              while (offsets[p + 1] <= i) ++p;
                              if (i + 4 < v.end()) prefetch(vols_.slot[visitors[i + 4]]);
                              test_samples(vols_.slot[visitors[i]], std::uint32_t(p));
                            }
                            phase_progress::advance(v.size());
                          });
        break;
      }
      const Level& below = h_.levels[std::size_t(l) + 1];
      verdicts.resize(std::max<std::size_t>(verdicts.size(), visits));
      remaining.resize(std::max<std::size_t>(remaining.size(), visits));
      std::vector<std::uint32_t> child_count(below.size() + 1, 0u);
      std::vector<std::uint32_t>& level_live = live[std::size_t(l)];
      // Speculative: every visitor against its node's mask at the start of the level, in one
      // flat range over all visits (a node has few visitors below the top levels); a range finds
      // its first node by bisection.
      tbb::parallel_for(
          tbb::blocked_range<std::uint32_t>(0, std::uint32_t(visits), 128),
          [&](const tbb::blocked_range<std::uint32_t>& v) {
            std::size_t p =
                std::size_t(std::upper_bound(offsets.begin(), offsets.end(), v.begin()) -
                            offsets.begin()) -
                1;
            for (std::uint32_t i = v.begin(); i != v.end(); ++i) {
              while (offsets[p + 1] <= i) ++p;
              const std::uint32_t start = level_live[p];
              // The next volumes' planes, ahead of their tests.
              if (i + 8 < v.end()) prefetch(vols_.slot[visitors[i + 8]]);
              const std::uint32_t first = L.first_child[p];
              const std::uint32_t count = std::uint32_t(std::popcount(L.child_mask[p]));
              verdicts[i] =
                  start == 0 ? Verdicts{0, 0, 0, 0}
                  : in_.config.implicit_cells
                      ? test_children_implicit(vols_.slot[visitors[i]], l + 1, first, count, start)
                      : test_children_explicit(vols_.slot[visitors[i]], l + 1, first, count, start);
            }
            phase_progress::advance(v.size());
          });
      // The ordered pass and the scatter, node by node; a node with more than segment_visits
      // visitors (a handful of top nodes have a million each) in segments on several threads.
      // Every visitor sees the node's start mask less the accepts of the visitors before it, an
      // OR over them: one pass over each segment's accepts gives every segment its start mask.
      std::vector<Segment> segments;
      std::vector<std::array<std::uint32_t, 32>> split;  // per split segment, by child rank
      for (std::uint32_t p = 0; p < L.size(); ++p) {
        const std::uint32_t b = offsets[p], e = offsets[p + 1];
        if (e - b <= segment_visits) {
          if (b != e) segments.push_back({p, b, e, 0, Segment::alone});
          continue;
        }
        for (std::uint32_t at = b; at < e; at += segment_visits) {
          segments.push_back(
              {p, at, std::min(e, at + segment_visits), 0, std::uint32_t(split.size())});
          split.emplace_back();
        }
      }
      if (!split.empty()) {
        tbb::parallel_for(std::size_t(0), segments.size(), [&](std::size_t k) {
          Segment& g = segments[k];
          if (g.split == Segment::alone) return;
          std::uint32_t accepted = 0;
          for (std::uint32_t i = g.begin; i < g.end; ++i) accepted |= verdicts[i].accept;
          g.mask = accepted;
        });
        std::uint32_t earlier = 0;  // the accepts of the node's earlier segments
        for (Segment& g : segments) {
          if (g.split == Segment::alone) continue;
          if (g.begin == offsets[g.node]) earlier = 0;
          const std::uint32_t accepted = g.mask;
          g.mask = level_live[g.node] & ~earlier;
          earlier |= accepted;
          if (g.end == offsets[g.node + 1]) level_live[g.node] &= ~earlier;
        }
      }
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 1),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          std::uint64_t tests = 0, acc = 0, rej = 0, cul = 0;
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                            const Segment& g = segments[k];
                            const bool alone = g.split == Segment::alone;
                            // A node in one segment counts its children's visitors in place (no
                            // other task has them); a split one per segment, summed below.
                            std::uint32_t* count = alone
                                                       ? child_count.data() + L.first_child[g.node]
                                                       : split[g.split].data();
                            // In volume order: what each visitor tests is what its predecessors
                            // left.
                            std::uint32_t mask = alone ? level_live[g.node] : g.mask;
                            for (std::uint32_t i = g.begin; i < g.end; ++i) {
                              const Verdicts& v = verdicts[i];
                              tests += std::uint64_t(std::popcount(mask));
                              acc += std::uint64_t(std::popcount(v.accept & mask));
                              rej += std::uint64_t(std::popcount(v.reject & mask));
                              cul += std::uint64_t(std::popcount(v.cull & mask));
                              const std::uint32_t rem = v.refine & mask;
                              mask &= ~v.accept;
                              remaining[i] = rem;
                              for (std::uint32_t bits = rem; bits != 0; bits &= bits - 1)
                                ++count[std::countr_zero(bits)];
                            }
                            if (alone) level_live[g.node] = mask;
                          }
                          node_tests += tests;
                          accepts += acc;
                          rejects += rej;
                          culls += cul;
                        });
      for (const Segment& g : segments)
        if (g.split != Segment::alone)
          for (std::uint32_t rank = 0; rank < std::uint32_t(std::popcount(L.child_mask[g.node]));
               ++rank)
            child_count[L.first_child[g.node] + rank] += split[g.split][rank];
      // The next level's visitors, grouped by child, in volume order within each.
      std::vector<std::uint32_t> next_offsets(below.size() + 1, 0u);
      for (std::size_t c = 0; c < below.size(); ++c)
        next_offsets[c + 1] = next_offsets[c] + child_count[c];
      // A split segment's first slot per child: after the node's earlier segments.
      std::array<std::uint32_t, 32> next_slot{};
      for (const Segment& g : segments) {
        if (g.split == Segment::alone) continue;
        const std::uint32_t first = L.first_child[g.node];
        for (std::uint32_t rank = 0; rank < 32; ++rank) {
          if (g.begin == offsets[g.node])
            next_slot[rank] = first + rank < below.size() ? next_offsets[first + rank] : 0;
          const std::uint32_t here = split[g.split][rank];
          split[g.split][rank] = next_slot[rank];
          next_slot[rank] += here;
        }
      }
      HugePageVector<std::uint32_t> next_visitors(next_offsets.back());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 16),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                            const Segment& g = segments[k];
                            std::array<std::uint32_t, 32> cursor{};
                            if (g.split != Segment::alone) {
                              cursor = split[g.split];
                            } else {
                              const std::uint32_t first = L.first_child[g.node];
                              for (std::uint32_t rank = 0; rank < 32 && first + rank < below.size();
                                   ++rank)
                                cursor[rank] = next_offsets[first + rank];
                            }
                            for (std::uint32_t i = g.begin; i < g.end; ++i)
                              for (std::uint32_t bits = remaining[i]; bits != 0; bits &= bits - 1)
                                next_visitors[cursor[std::countr_zero(bits)]++] = visitors[i];
                          }
                        });
      offsets.swap(next_offsets);
      visitors.swap(next_visitors);
    }
    counters.node_tests += node_tests.load();
    counters.sample_tests += sample_tests.load();
    counters.trivial_accepts += accepts.load();
    counters.trivial_rejects += rejects.load();
    counters.culling_plane_rejects += culls.load();

    // The final pass: samples below a cleared bit lie in a trivially accepted node.
    std::vector<std::uint8_t> intact(1, 1);
    for (int l = 1; l <= leaves; ++l) {
      const Level& L = h_.levels[std::size_t(l)];
      const Level& above = h_.levels[std::size_t(l) - 1];
      std::vector<std::uint8_t> next(L.size());
      for (std::size_t c = 0; c < L.size(); ++c) {
        const std::uint32_t p = L.parent[c];
        const std::uint32_t rank = std::uint32_t(c) - above.first_child[p];
        next[c] = intact[p] && ((live[std::size_t(l) - 1][p] >> rank) & 1u);
      }
      intact.swap(next);
    }
    const RegularSamples& samples = in_.scene->samples;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 8192),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t s = r.begin(); s != r.end(); ++s)
                          if (!intact[h_.leaf_of_sample[s]]) shadowed_[samples.index[s]] = 1;
                      });
  }

 private:
  const TraversalInputs& in_;
  const Hierarchy& h_;
  const PackedVolumes& vols_;
  std::uint8_t* shadowed_;
  bool culling_;
};

void RunTraversal(const TraversalInputs& inputs, std::uint8_t* shadowed,
                  ref::TraversalCounters* counters) {
  Engine(inputs, shadowed).run(*counters);
}

}  // namespace shadowcts::simd::ptsv::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::ptsv {

HWY_EXPORT(RunTraversal);

void traverse(const TraversalInputs& inputs, std::vector<std::uint8_t>& shadowed,
              ref::TraversalCounters& counters) {
  HWY_DYNAMIC_DISPATCH(RunTraversal)(inputs, shadowed.data(), &counters);
}

}  // namespace shadowcts::simd::ptsv
#endif
