#pragma once
// Launch interface of the psv kernels: the descents of the batched TOP-tree build and the
// queries. Plain data only, so that the C++20 host side (the Algorithm) and the C++17 CUDA
// translation unit share it.
//
// The TOP tree is built in batches (reference/psv/top_tree_batches.h): the device descends every
// triangle of a batch in the tree as it stands, one thread per triangle, and the host commits
// the batch in insertion order, so the tree is the reference's node for node. It stays on the
// device as the flat node array of Mora 2016, section 3.6, each batch appending what the host
// committed; the query kernel then reads it.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/plane_filter.h"

namespace shadowcts {

inline constexpr std::uint32_t psv_no_node = std::numeric_limits<std::uint32_t>::max();

// reference/psv/top_tree.h's TopNode, byte for byte: the 32-byte node of the 2016 paper. Volume v
// is nodes 4v .. 4v + 3 (three edge planes, then the capping plane); the negative child of node
// 4v + k < 4v + 3 is the next node, that of the capping node the shadow leaf.
struct PsvDeviceNode {
  float plane[4];  // negative inside the volume
  std::uint32_t positive;
  std::uint32_t intersection;
  float wedge;  // bound on |plane| over the intersection subtree (per unit light distance)
  // Node 0 of a volume: its depth (float bits); node 1: ancestor link; node 2: triangle.
  std::uint32_t volume_word;
};
static_assert(sizeof(PsvDeviceNode) == 32, "the 2016 paper's node is 32 bytes");

// How the exact fallback of a plane test recomputes a volume's plane from its triangle: the
// vertex indices (0..2) of each edge plane and the orientation sign of each of the four planes.
struct PsvDeviceSource {
  std::uint8_t edge[3][2];
  std::int8_t orientation[4];
};

struct PsvDeviceTriangle {
  glm::vec3 v0, v1, v2;
};

enum class PsvDeviceQuery : std::uint32_t { stack, depth, stackless, hybrid };

// The largest stack a query thread holds (the paper's 32): a fixed array per thread.
inline constexpr std::uint32_t psv_max_stack_capacity = 32;

struct PsvQueryInput {
  std::vector<PsvDeviceNode> nodes;
  std::vector<PsvDeviceSource> sources;  // per volume
  std::uint32_t root = psv_no_node;
  // Every triangle of the case (Case::triangles order): the exact fallback reads a volume's
  // triangle, the receiver half-space rule a sample's receiver.
  std::vector<PsvDeviceTriangle> triangles;
  // Regular samples only, in the order the results come back.
  std::vector<glm::vec3> sample_positions;
  std::vector<std::uint32_t> sample_receivers;  // psv_no_node: no receiver
  bool directional_light = false;
  glm::dvec3 light{0.0};  // point light position, or the direction towards a directional light
  geometry::PlaneFilter filter;
  PsvDeviceQuery query = PsvDeviceQuery::hybrid;
  std::uint32_t stack_capacity = 12;  // <= psv_max_stack_capacity
};

struct PsvQueryResult {
  std::vector<std::uint8_t> shadowed;        // per input sample, 1 = shadowed
  std::vector<std::uint32_t> nodes_visited;  // per input sample
  // Sums and maxima over the samples (integers: independent of the launch and the schedule).
  std::uint64_t nodes_visited_total = 0;
  std::uint64_t nodes_visited_max = 0;
  std::uint64_t stack_high_water = 0;
  std::uint64_t stack_overflows = 0;
  std::uint64_t hybrid_switches = 0;
  std::uint64_t exact_plane_tests = 0;  // plane tests of the queries the float filter left open
};

// Where a triangle's descent stopped (reference/psv/top_tree_batches.h, Descent).
struct PsvDeviceDescent {
  std::uint32_t parent;
  std::uint32_t ancestor;
  std::uint8_t into_intersection;
  std::uint8_t dropped;
};

struct PsvDescentSetup {
  std::vector<PsvDeviceTriangle> triangles;  // every triangle of the case
  std::size_t node_capacity = 0;             // the most nodes the tree can grow to
  bool directional_light = false;
  glm::dvec3 light{0.0};
  geometry::PlaneFilter filter;
};

// The device half of the batched build: the triangles and the growing tree live on the device.
class PsvDescentSession {
 public:
  virtual ~PsvDescentSession() = default;
  // nodes[0, node_count) and sources[0, node_count / 4) are the whole tree as it stands (the
  // nodes are copied again, since new volumes hang below old nodes; of the sources only the new
  // ones). Then one thread per triangle of `batch` descends it from `root` (the reference's plane
  // tests, every vertex at every node) into out.
  virtual void descend(const PsvDeviceNode* nodes, const PsvDeviceSource* sources,
                       std::size_t node_count, std::uint32_t root,
                       const std::vector<std::uint32_t>& batch,
                       std::vector<PsvDeviceDescent>& out) = 0;
  // Plane tests of all descents so far that the float filter left open.
  virtual std::uint64_t exact_plane_tests() const = 0;
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
PsvQueryResult run_psv_query_kernel(PsvQueryInput input);
std::unique_ptr<PsvDescentSession> make_psv_descent_session(const PsvDescentSetup& setup);

// The same kernel source run by the CUDA-subset emulator on the host (gpu/emulator); throws
// shadowcts::emu::EmulatorError where a GPU would hang or race.
PsvQueryResult run_psv_query_kernel_emulated(PsvQueryInput input);
std::unique_ptr<PsvDescentSession> make_psv_descent_session_emulated(const PsvDescentSetup& setup);

}  // namespace shadowcts
