#pragma once
// What the ptsv ports' structure diffs compare against: the reference's cluster keys and
// hierarchy for a case and variant, and the first difference of a port's keys or of one of its
// levels (index, child mask, explicit bounds bit for bit, reject reach) from them.
#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::port_test {

struct PtsvReferenceStructures {
  std::string problem;  // the reference refused the samples: no keys, no hierarchy
  std::vector<std::uint32_t> key;
  std::optional<ptsv::ClusterHierarchy> hierarchy;
};

inline PtsvReferenceStructures ptsv_reference_structures(const Case& c, const ViewSamples& samples,
                                                         const std::string& variant) {
  const ptsv::ViewFrame frame = ptsv::make_view_frame(c.camera, samples.width, samples.height);
  const ptsv::ClusterKeyLayout layout =
      ptsv::make_cluster_key_layout(c.camera, samples.width, samples.height).layout;
  ptsv::ClusterKeys keys = ptsv::assign_cluster_keys(layout, frame, samples, variant == "implicit");
  PtsvReferenceStructures out;
  if (!keys.problem.empty()) {
    out.problem = "reference keys: " + keys.problem;
    return out;
  }
  const ptsv::ReceiverRule rule(c, samples);
  out.hierarchy.emplace(layout, keys.key, samples, rule.reject_reach());
  out.key = std::move(keys.key);
  return out;
}

inline std::string ptsv_key_difference(const std::vector<std::uint32_t>& port,
                                       const std::vector<std::uint32_t>& reference) {
  if (port.size() != reference.size())
    return std::to_string(port.size()) + " keys, reference " + std::to_string(reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i)
    if (port[i] != reference[i])
      return "key of view sample " + std::to_string(i) + ": " + std::to_string(port[i]) +
             " != reference " + std::to_string(reference[i]);
  return "";
}

// One node of a port's level, as the reference's HierarchyLevel holds it.
struct PtsvNode {
  std::uint32_t index = 0, child_mask = 0;
  double lo[3] = {}, hi[3] = {};
  double reach = 0.0;
};

// Level l of a port with `nodes` nodes, node n read by node_at(n), against the reference's.
template <class NodeAt>
std::string ptsv_level_difference(int l, std::size_t nodes, const ptsv::HierarchyLevel& reference,
                                  NodeAt&& node_at) {
  const auto same_bits = [](double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
  };
  if (nodes != reference.index.size())
    return "level " + std::to_string(l) + ": " + std::to_string(nodes) + " nodes, reference " +
           std::to_string(reference.index.size());
  for (std::size_t n = 0; n < nodes; ++n) {
    const PtsvNode p = node_at(n);
    const std::string node = "level " + std::to_string(l) + " node " + std::to_string(n) + " ";
    if (p.index != reference.index[n]) return node + "index";
    if (p.child_mask != reference.child_mask[n]) return node + "child mask";
    for (int k = 0; k < 3; ++k)
      if (!same_bits(p.lo[k], reference.bounds[n].lo[k]) ||
          !same_bits(p.hi[k], reference.bounds[n].hi[k]))
        return node + "bounds, axis " + std::to_string(k);
    if (!same_bits(p.reach, reference.reject_reach[n])) return node + "reject reach";
  }
  return "";
}

}  // namespace shadowcts::port_test
