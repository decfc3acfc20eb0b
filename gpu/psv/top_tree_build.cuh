#pragma once
// The descents of the batched TOP-tree build (reference/psv/top_tree_batches.h), written once
// (gpu/emulator/kernel.h): one thread per triangle of a batch descends the tree as it stood
// before the batch with the reference's plane tests, every vertex at every node (so the exact
// tests add up to the reference's). Threads only read the tree: no barrier, no shared memory.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "gpu/psv/plane_side.cuh"
#include "gpu/psv/psv_kernels.h"
#include "gpu/psv/top_tree.cuh"
#include "shadowcts/geometry/volume_location.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

constexpr int descent_threads_per_block = 128;

// reference/psv/top_tree_build.h, triangle_location.
__device__ inline int triangle_location(const PlaneSide& planes, std::uint32_t node,
                                        const PsvDeviceTriangle& t, std::uint32_t& exact_tests) {
  bool positive = false, negative = false, on = false;
  for (int i = 0; i < 3; ++i) {
    const int s = side(planes, node, triangle_vertex(t, i), exact_tests);
    positive = positive || s > 0;
    negative = negative || s < 0;
    on = on || s == 0;
  }
  return geometry::volume_location(positive, negative, on, is_capping_node(node));
}

__global__ void psv_descend(PlaneSide planes, std::uint32_t root, const std::uint32_t* batch,
                            std::uint32_t count, PsvDeviceDescent* out,
                            unsigned long long* exact_total) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  const PsvDeviceTriangle t = planes.triangles[batch[i]];
  PsvDeviceDescent d{psv_no_node, psv_no_node, 0, 0};
  std::uint32_t exact_tests = 0;
  for (std::uint32_t node = root; node != psv_no_node;) {
    const int location = triangle_location(planes, node, t, exact_tests);
    d.parent = node;
    if (location > 0) {
      d.into_intersection = 0;
      node = planes.nodes[node].positive;
    } else if (location < 0) {
      if (is_capping_node(node)) {
        d.dropped = 1;
        break;
      }
      node = node + 1;
    } else {
      d.into_intersection = 1;
      d.ancestor = node;
      node = planes.nodes[node].intersection;
    }
  }
  out[i] = d;
  if (exact_tests != 0) atomicAdd(exact_total, static_cast<unsigned long long>(exact_tests));
}

class DescentSession final : public PsvDescentSession {
 public:
  explicit DescentSession(const PsvDescentSetup& setup)
      : nodes_(setup.node_capacity),
        sources_(setup.node_capacity / nodes_per_volume),
        triangles_(setup.triangles.size()),
        exact_total_(1) {
    if (setup.node_capacity >= UINT32_MAX || setup.triangles.size() >= UINT32_MAX)
      throw std::length_error("psv build: more than 2^32 triangles or tree nodes");
    triangles_.upload(setup.triangles);
    exact_total_.zero();
    planes_.nodes = nodes_.data();
    planes_.sources = sources_.data();
    planes_.triangles = triangles_.data();
    planes_.directional = setup.directional_light;
    planes_.light = setup.light;
    planes_.filter = setup.filter;
    capacity_ = setup.node_capacity;
  }

  void descend(const PsvDeviceNode* nodes, const PsvDeviceSource* sources, std::size_t node_count,
               std::uint32_t root, const std::vector<std::uint32_t>& batch,
               std::vector<PsvDeviceDescent>& out) override {
    if (node_count > capacity_ || node_count % nodes_per_volume != 0 || node_count < uploaded_)
      throw std::invalid_argument("psv build: the tree only grows, within its capacity");
    // The commit links new volumes below old nodes, anywhere in the tree: all nodes again. The
    // sources never change once written: only the new ones.
    nodes_.upload(nodes, 0, node_count);
    sources_.upload(sources + uploaded_ / nodes_per_volume, uploaded_ / nodes_per_volume,
                    (node_count - uploaded_) / nodes_per_volume);
    uploaded_ = node_count;
    out.resize(batch.size());
    if (batch.empty()) return;
    if (batch.size() > batch_capacity_) {
      batch_ = std::make_unique<DeviceArray<std::uint32_t>>(batch.size());
      descents_ = std::make_unique<DeviceArray<PsvDeviceDescent>>(batch.size());
      batch_capacity_ = batch.size();
    }
    batch_->upload(batch.data(), 0, batch.size());
    const auto block_count = static_cast<unsigned>((batch.size() + descent_threads_per_block - 1) /
                                                   descent_threads_per_block);
    SHADOWCTS_LAUNCH(psv_descend, block_count, descent_threads_per_block, 0)
    (planes_, node_count == 0 ? psv_no_node : root, batch_->data(),
     static_cast<std::uint32_t>(batch.size()), descents_->data(), exact_total_.data());
    check(cudaGetLastError(), "psv_descend launch");
    check(cudaDeviceSynchronize(), "psv_descend");
    descents_->download(out.data(), batch.size());
  }

  std::uint64_t exact_plane_tests() const override {
    unsigned long long total = 0;
    exact_total_.download(&total);
    return total;
  }

 private:
  DeviceArray<PsvDeviceNode> nodes_;
  DeviceArray<PsvDeviceSource> sources_;
  DeviceArray<PsvDeviceTriangle> triangles_;
  DeviceArray<unsigned long long> exact_total_;
  std::unique_ptr<DeviceArray<std::uint32_t>> batch_;
  std::unique_ptr<DeviceArray<PsvDeviceDescent>> descents_;
  std::size_t batch_capacity_ = 0;
  std::size_t capacity_ = 0;
  std::size_t uploaded_ = 0;
  PlaneSide planes_{};
};

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
