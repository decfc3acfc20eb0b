#pragma once
// Traversal of the shadow volumes through the cluster hierarchy (the reference's traversal.h and
// two_pass.h define it: Sintorn 2014, Algorithm 1), spread over oneTBB node by node.
//
// The reference processes volumes one after another and shares the hierarchy's child masks: a
// trivially accepted child is cleared and no later volume tests it. Whether volume v tests child
// c of node n therefore depends only on the visits to n by earlier volumes (only a visit to n
// changes n's mask), and every volume visits n at most once. So the traversal runs level by level
// over nodes instead of volumes: a node's visitors, in volume order, are the reference's visits
// to it (its two-pass job queue, at the job level); its child verdicts are computed for all
// visitors in parallel against its mask at the start of the level (in Highway lanes, one child
// per lane), then one ordered pass applies the accepts exactly as the sequence of the reference
// does and hands each refined child its visitors in the same order. The counters are the
// reference's, for any thread count; the samples' shadow bits are set by atomic OR.
#include <cstdint>
#include <vector>

#include "reference/ptsv/counters.h"
#include "reference/ptsv/node_test.h"
#include "simd/ptsv/hierarchy.h"
#include "simd/ptsv/receiver_rule.h"
#include "simd/ptsv/triangle_setup.h"

namespace shadowcts::simd::ptsv {

struct TraversalConfig {
  bool implicit_cells = false;  // else explicit boxes
  bool extra_planes = false;
  int job_level = -1;  // two-pass: the level whose visits are the jobs (counted); -1: one pass
};

struct TraversalInputs {
  const Hierarchy* hierarchy = nullptr;
  const PackedVolumes* volumes = nullptr;
  const ReceiverRule* rule = nullptr;
  const Case* source = nullptr;
  const PreparedScene* scene = nullptr;
  TraversalConfig config;
  ref::NodeTolerances tolerances;
};

// Every volume of inputs.volumes->order through the hierarchy, then the final pass (samples in a
// trivially accepted node). shadowed: per view sample, ORed into.
void traverse(const TraversalInputs& inputs, std::vector<std::uint8_t>& shadowed,
              ref::TraversalCounters& counters);

}  // namespace shadowcts::simd::ptsv
