#include "gpu/psv/psv_shadows.h"

#include <cstddef>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <utility>

#include "shadowcts/phase_clock.h"

namespace shadowcts::gpu_psv {
namespace {

PsvDeviceQuery device_query(psv::QueryKind kind) {
  switch (kind) {
    case psv::QueryKind::stack:
      return PsvDeviceQuery::stack;
    case psv::QueryKind::depth:
      return PsvDeviceQuery::depth;
    case psv::QueryKind::stackless:
      return PsvDeviceQuery::stackless;
    case psv::QueryKind::hybrid:
      return PsvDeviceQuery::hybrid;
  }
  throw std::invalid_argument("psv: unknown query kind");
}

static_assert(sizeof(PsvDeviceNode) == sizeof(psv::TopNode) &&
              offsetof(psv::TopNode, positive) == offsetof(PsvDeviceNode, positive) &&
              offsetof(psv::TopNode, volume_word) == offsetof(PsvDeviceNode, volume_word));
static_assert(sizeof(PsvDeviceSource) == sizeof(psv::VolumeSource) &&
              offsetof(psv::VolumeSource, orientation) == offsetof(PsvDeviceSource, orientation));

// The device's descents: the tree's nodes and sources go up byte for byte (the layouts agree), and
// the commit's resumed descents run on the host with the reference's plane tests.
class DeviceDescents final : public psv::DescentEngine {
 public:
  // `exact_tests`: the device's exact plane tests so far, kept up to date batch by batch.
  DeviceDescents(const Case& c, const psv::PlaneSide& planes,
                 std::unique_ptr<PsvDescentSession> session, std::uint64_t& exact_tests)
      : c_(c), planes_(planes), session_(std::move(session)), exact_tests_(exact_tests) {}

  void descend_batch(const psv::TopTree& tree, const std::vector<std::uint32_t>& triangles,
                     std::vector<psv::Descent>& out, psv::BatchVolumes& volumes) override {
    session_->descend(reinterpret_cast<const PsvDeviceNode*>(tree.nodes.data()),
                      reinterpret_cast<const PsvDeviceSource*>(tree.sources.data()),
                      tree.nodes.size(), tree.root, triangles, descents_);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const PsvDeviceDescent& d = descents_[i];
      out[i] = {d.parent, d.ancestor, d.into_intersection != 0, d.dropped != 0};
    }
    exact_tests_ = session_->exact_plane_tests();
    psv::make_batch_volumes(planes_, triangles, out, volumes);
  }

  void resume(const psv::TopTree& tree, std::uint32_t node, std::uint32_t triangle,
              psv::Descent& d) override {
    while (node != psv::no_node)
      node = psv::descend_step(tree, planes_, node, c_.triangles[triangle], d);
  }

 private:
  const Case& c_;
  const psv::PlaneSide& planes_;
  std::unique_ptr<PsvDescentSession> session_;
  std::uint64_t& exact_tests_;
  std::vector<PsvDeviceDescent> descents_;
};

}  // namespace

psv::PsvBuild build_psv_on_device(const Case& c, const ViewSamples& samples, std::uint64_t seed,
                                  DescentSessionMaker make_session, psv::BatchWork& work,
                                  std::uint64_t& device_exact_tests) {
  device_exact_tests = 0;
  return psv::build_psv_in_batches(
      c, samples, seed,
      [&](const psv::PlaneSide& planes) {
        PsvDescentSetup setup;
        setup.triangles.reserve(c.triangles.size());
        for (const Triangle& t : c.triangles) setup.triangles.push_back({t.v0, t.v1, t.v2});
        setup.node_capacity = c.triangles.size() * psv::nodes_per_volume;
        setup.directional_light = planes.light().directional;
        setup.light =
            planes.light().directional ? planes.light().direction : planes.light().position;
        setup.filter = planes.filter();
        return std::make_unique<DeviceDescents>(c, planes, make_session(setup), device_exact_tests);
      },
      work);
}

PsvQueryInput psv_query_input(const Case& c, const ViewSamples& samples, const psv::PsvBuild& build,
                              const psv::PsvOptions& options,
                              std::vector<std::size_t>& regular_samples) {
  static_assert(sizeof(PsvDeviceNode) == sizeof(psv::TopNode));
  PsvQueryInput input;
  const psv::TopTree& tree = build.tree;
  input.nodes.resize(tree.nodes.size());
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const psv::TopNode& n = tree.nodes[i];
    PsvDeviceNode& d = input.nodes[i];
    for (int k = 0; k < 4; ++k) d.plane[k] = n.plane[std::size_t(k)];
    d.positive = n.positive;
    d.intersection = n.intersection;
    d.wedge = n.wedge;
    d.volume_word = n.volume_word;
  }
  input.sources.resize(tree.sources.size());
  for (std::size_t v = 0; v < tree.sources.size(); ++v) {
    const psv::VolumeSource& s = tree.sources[v];
    PsvDeviceSource& d = input.sources[v];
    for (std::size_t k = 0; k < 3; ++k) {
      d.edge[k][0] = s.edge[k][0];
      d.edge[k][1] = s.edge[k][1];
    }
    for (std::size_t k = 0; k < 4; ++k) d.orientation[k] = s.orientation[k];
  }
  input.root = tree.root;
  input.triangles.reserve(c.triangles.size());
  for (const Triangle& t : c.triangles) input.triangles.push_back({t.v0, t.v1, t.v2});
  for (std::size_t i = 0, rank = 0; i < samples.samples.size(); ++i) {
    const ViewSample& sample = samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    if (!build.reached[rank++]) continue;  // lit: no inserted triangle can reach it
    regular_samples.push_back(i);
    input.sample_positions.push_back(sample.position);
    input.sample_receivers.push_back(sample.receiver);  // no_receiver is psv_no_node
  }
  input.directional_light = build.light.directional;
  input.light = build.light.directional ? build.light.direction : build.light.position;
  input.filter = build.planes->filter();
  input.query = device_query(options.query);
  input.stack_capacity = options.stack_capacity;
  if (options.stack_capacity > psv_max_stack_capacity)
    throw std::invalid_argument("psv: the device stack holds at most 32 nodes");
  return input;
}

psv::PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples,
                                const psv::PsvOptions& options, QueryKernel kernel,
                                DescentSessionMaker make_session) {
  static_assert(no_receiver == psv_no_node);
  PhaseClock clock;
  psv::BatchWork work;
  std::uint64_t device_exact_tests = 0;
  const psv::PsvBuild build =
      build_psv_on_device(c, samples, options.seed, make_session, work, device_exact_tests);
  // The build's exact plane tests (the device's and the host's), before any query adds to them.
  const std::uint64_t build_exact_tests = device_exact_tests + build.planes->exact_fallbacks();
  std::vector<std::size_t> regular_samples;
  PsvQueryInput input = psv_query_input(c, samples, build, options, regular_samples);
  clock.lap(build_phase);

  // The kernel frees each staging array once it has its own copy (on the device, or in the
  // emulator's memory).
  const PsvQueryResult queried = kernel(std::move(input));
  psv::PsvResult result;
  result.shadowed.assign(samples.samples.size(), 0);
  result.nodes_visited.assign(samples.samples.size(), 0);
  for (std::size_t i = 0; i < regular_samples.size(); ++i) {
    result.shadowed[regular_samples[i]] = queried.shadowed[i];
    result.nodes_visited[regular_samples[i]] = queried.nodes_visited[i];
  }
  clock.lap(query_phase);
  result.phase_ms = clock.times();
  psv::PsvQueryTotals totals;
  totals.queries = regular_samples.size();
  totals.nodes_visited_total = queried.nodes_visited_total;
  totals.nodes_visited_max = queried.nodes_visited_max;
  totals.stack_high_water = queried.stack_high_water;
  totals.stack_overflows = queried.stack_overflows;
  totals.hybrid_switches = queried.hybrid_switches;
  result.counters =
      psv::psv_counters(build, totals, options, build_exact_tests + queried.exact_plane_tests);
  return result;
}

}  // namespace shadowcts::gpu_psv
