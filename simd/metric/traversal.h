#pragma once
// Packet traversal of the ternary metric tree (Deves et al. 2018, section 5.4) for the simd
// `metric`: the samples of an 8 x 8 (or 4 x 4, 4 x 2) pixel tile walk the tree together, one
// Highway lane per sample for the node tests, one stack of (node, lane mask) entries. A lane's
// entries are pushed and popped in the order its own depth-first walk would push and pop them, so
// every per-sample counter is the reference's (reference/metric/traversal.h).
//
// Exactness: the node tests decide in lanes only where the decision is certain. A node is first
// tested in float (16 lanes per AVX-512 vector: cones and arcs of a point light, disks and 2D
// capsules of a directional one), which hands a lane to the double test where it lies within
// 2^-16 (of an angle, or of S in the plane) of a threshold; the double test hands it to the
// reference's scalar pivot_distance where a comparison lies within 2^-40 of its threshold. The
// angle test needs no atan2: for an angle theta = atan2(s, c) with s >= 0 and a threshold T in [0,
// pi], sign(theta - T) is the sign of s cos T - c sin T. The triangles of a candidate cluster are
// filtered in float lanes: a triangle is skipped only where the line of the ray certainly misses it
// (two float edge functions of the reference's own float ray-space vertices certainly of opposite
// signs, beyond the rounding of the transform); every other one is decided by the reference's own
// triangle_blocks_sample. A directional light's lanes whose line passes outside a cluster's plane
// bounds (NodeCluster::plane_low, plane_high) by the margin skip its triangles altogether, their
// tests counted as the reference counts them; so do the lanes whose receiver's supporting plane
// holds the whole cluster (NodeCluster::plane, ClusterPlanes), by the receiver half-space rule.
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/metric/clustering.h"
#include "reference/metric/counters.h"
#include "reference/metric/traversal.h"
#include "shadowcts/huge_pages.h"
#include "shadowcts/prepared_scene.h"
#include "simd/metric/cluster_planes.h"

namespace shadowcts::simd::metric {

// The caster triangles of each cluster in groups of 16 slots (a cluster's last group padded with
// zeros), a group holding the 9 coordinate vectors of its slots side by side: the filter of a
// cluster reads adjacent whole cache lines, not two straddled lines in each of 9 distant arrays.
// Corner k of the triangle in slot j of group g is (xyz[0][k][j], xyz[1][k][j], xyz[2][k][j]).
// Light-independent: part of the per-model precomputation.
struct alignas(64) TriangleGroup {
  float xyz[3][3][16];
};

struct ClusterTriangles {
  HugePageVector<TriangleGroup> groups;  // cluster k's from first_groups(...)[k] on
  std::vector<std::uint32_t> slot_of;    // per caster triangle: its slot (finds a receiver in O(1))
  ClusterPlanes planes;
};

// Per cluster, its first group in ClusterTriangles::groups; one more entry for the end.
std::vector<std::uint32_t> first_groups(const shadowcts::metric::Clustering& clustering);

ClusterTriangles cluster_triangles_soa(const CasterArrays& casters,
                                       const shadowcts::metric::Clustering& clustering);

// Thresholds of a node, in the order of PacketNode::threshold.
enum Threshold : int { inside = 0, overlap_low, overlap_high, far_side, near_side, thresholds };

enum class NodeKind : std::uint8_t {
  point_cone,         // point light, point centre: an angle to a direction
  arc_cone,           // point light, arc centre
  disk,               // directional, point centre: a distance in the plane
  capsule_2d,         // directional, segment centre
  covers_everything,  // decided per lane by the reference
};

// One tree node with what the lanes compare against, precomputed per frame. The hot fields of a
// point-light node fill its first three cache lines; nodes are stored in the order of a
// near-first depth-first walk, so that a walk mostly reads forward.
struct alignas(64) PacketNode {
  double light_distance = 0.0;
  double pivot_light_distance = 0.0;
  std::uint32_t child[3] = {0, 0, 0};  // indices into the packet nodes
  std::uint32_t pivot = 0;
  NodeKind kind = NodeKind::point_cone;
  std::uint8_t has_child[3] = {0, 0, 0};
  double a[3] = {0, 0, 0};
  // Point light: theta <= threshold + radius iff s cos - c sin <= 0 for theta = atan2(s, c);
  // (cos, sin) = (+-2, 0) where the shifted threshold lies outside [0, pi] (every angle is then
  // above, or below, unless s = 0, which the reference decides).
  double cos_t[thresholds] = {}, sin_t[thresholds] = {};
  double radius = 0.0;
  double segment_length_squared = 0.0;  // capsule_2d: |b - a|^2
  double b[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
  // The reference's thresholds of the pivot distance: 0, overlap_min - slack,
  // overlap_max + slack, delta - slack, delta + slack.
  double threshold[thresholds] = {};
};

// What a lane reads on every visit of a node, in float, two cache lines: the light-distance
// bounds and the centre and thresholds of PacketNode. A float lane decides only where its
// comparison is certain (evaluate_in_float and evaluate_planar_in_float in traversal.cpp say
// why); every other lane, and every lane of a node in_float leaves at 0, takes the double
// PacketNode.
struct alignas(128) FastNode {
  // Floats below and above the doubles (light distances are compared in double by the reference).
  float light_distance_low = 0, light_distance_high = 0;
  float a[3] = {0, 0, 0};
  // Cones: cos and sin of each threshold as PacketNode's; disk and capsule_2d: cos_t and sin_t
  // hold the squares of threshold + radius -+ the planar window (evaluate_planar_in_float).
  float cos_t[thresholds] = {}, sin_t[thresholds] = {};
  // 1: point_cone, 2: arc_cone, 3: disk, 4: capsule_2d: the lanes are decided in float first.
  std::uint8_t in_float = 0;
  std::uint8_t needed = 0;     // bit k: threshold k decides something
  std::uint8_t has_child = 0;  // bit c: TreeChild c exists
  std::uint8_t squared = 0;    // point_cone with every needed cos T >= 0: tested without a root
  // Second line: read once a lane goes on.
  alignas(64) float pivot_light_distance_low = 0;  // alignas binds per declarator: one each
  float pivot_light_distance_high = 0;
  std::uint32_t child[3] = {0, 0, 0};             // indices into the packet nodes
  float b[3] = {0, 0, 0}, normal[3] = {0, 0, 0};  // as PacketNode's
  float segment_length_squared = 0;               // capsule_2d
};
static_assert(sizeof(FastNode) == 128, "two cache lines");

// The pivot cluster of a node as section 5.4 step 2 reads it: its slots and its slabs, widened by
// the margin exactly as segment_meets_slabs widens them.
struct alignas(32) NodeCluster {
  // Directional light: where the cluster's caster triangles lie seen along the light, as bounds of
  // x, y, x + y and x - y of their vertices in the light's plane (LightFrame::plane_x, plane_y),
  // widened by cluster_miss_margin (twice that along the diagonals). A line towards the light
  // from a point outside them misses every triangle (lanes_missing_cluster in traversal.cpp says
  // why). (-inf, +inf) for a point light and where a vertex is not finite: never outside.
  float plane_low[4] = {}, plane_high[4] = {};
  glm::dvec3 slab_normal{0.0};
  double low = 0.0, high = 0.0;
  std::uint32_t begin = 0, end = 0;  // slots in cluster order
  std::uint32_t group = 0;           // its first ClusterTriangles group
  std::uint32_t plane = no_plane;    // ClusterPlanes::of_cluster
};

// An array of trivially destructible records that the code filling it constructs (in parallel):
// a std::vector would first value-initialise every record on one thread, touching some 30 MB of
// fresh pages at 1M triangles serially before the parallel fill writes them again.
template <class T>
class FilledArray {
  static_assert(std::is_trivially_destructible_v<T>);

 public:
  FilledArray() = default;
  explicit FilledArray(std::size_t size)
      : data_(static_cast<T*>(::operator new(size * sizeof(T), std::align_val_t(alignof(T))))),
        size_(size) {}
  FilledArray(FilledArray&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}
  FilledArray& operator=(FilledArray&& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    return *this;
  }
  FilledArray(const FilledArray&) = delete;
  FilledArray& operator=(const FilledArray&) = delete;
  ~FilledArray() {
    if (data_ != nullptr) ::operator delete(data_, std::align_val_t(alignof(T)));
  }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T* data() const { return data_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

inline constexpr double default_decision_window = 0x1p-40;

struct PacketNodes {
  // Half-width of the band around a threshold where a lane hands its decision to the reference:
  // an angle, or a multiple of S in the plane. 2^-40 lies far above the error of s cos T - c sin T
  // (a few 2^-53) and of the reference's atan2, subtraction and threshold sums (a few ulp of
  // numbers below 8), and, in the plane, of any order of evaluation. Tests widen it to send many
  // lanes to the reference. The float nodes' limits are built for it.
  double decision_window = default_decision_window;
  FilledArray<PacketNode> nodes;  // doubles: the certain decisions in double, then the reference
  FilledArray<FastNode> fast;     // same order
  FilledArray<NodeCluster> clusters;
};

// The plane bounds of each node's cluster (NodeCluster::plane_low, plane_high) are taken from
// `triangles`, the caster triangles of the same clustering.
PacketNodes packet_nodes(const shadowcts::metric::TraversalScene& scene,
                         const ClusterTriangles& triangles,
                         double decision_window = default_decision_window);

// The width in pixels of the image tiles of `packet` (8, 16 or 64) samples: 8 x 8 tiles for 64,
// 4 wide for the smaller packets.
constexpr std::uint32_t tile_width_of(std::uint32_t packet) {
  return packet >= 64 ? 8 : 4;
}

// The regular samples grouped into image tiles of `packet` samples (tile_width_of(packet) pixels
// wide).
struct SampleTiles {
  std::uint32_t packet = 64;
  std::vector<std::uint32_t> begin{0};  // tile k holds samples[begin[k] .. begin[k + 1])
  // Indices into RegularSamples; written by the bands in parallel, unzeroed: a vector's serial
  // zeroing (and first touch of 4 MB) was a few ms inside the timed query at 1080p.
  FilledArray<std::uint32_t> samples;
  std::size_t size() const { return begin.size() - 1; }
};

SampleTiles sample_tiles(const RegularSamples& samples, std::uint32_t width, std::uint32_t packet);

struct PacketTraversal {
  const shadowcts::metric::TraversalScene* scene = nullptr;  // the reference's, for its decisions
  const PacketNodes* nodes = nullptr;
  const ClusterTriangles* triangles = nullptr;
  const PreparedScene* prepared = nullptr;
  const SampleTiles* tiles = nullptr;
};

// Answers the samples of tiles [tile_begin, tile_end): shadowed[v] for the view sample v
// (ViewSamples::samples) of each of their regular samples, and adds the work to `counters`.
// Dispatched to the best Highway target of the CPU.
void traverse_tiles(const PacketTraversal& traversal, std::size_t tile_begin, std::size_t tile_end,
                    std::uint8_t* shadowed, shadowcts::metric::TraversalCounters& counters);

// The Highway target traverse_tiles dispatches to now (tests force others).
std::int64_t traversal_target();

}  // namespace shadowcts::simd::metric
