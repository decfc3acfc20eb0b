#pragma once
// The per-frame ternary metric tree of the simd `metric`, built in parallel and identical node
// for node to the reference's insertion build (reference/metric/metric_tree.h).
//
// Why a parallel build can give the same tree: the insertion build places element order[i] at
// node i, and an element's path depends only on the pivots of the nodes before it in the order.
// So the subtree of node i holds exactly the later elements whose path passes through it, in
// order, and its first one is the child's pivot: the tree is the recursive partition of the
// shuffled sequence by each pivot, with delta halved on every near step (Deves et al. 2018,
// section 5.3, rules 1 to 3). The subsequences are disjoint, so they are partitioned in
// parallel; every min and max is folded in the order the insertion build folds it.
#include <cstdint>
#include <vector>

#include "reference/metric/metric_tree.h"

namespace shadowcts::simd::metric {

// The same tree as shadowcts::metric::build_metric_tree_by_insertion for the same arguments.
shadowcts::metric::MetricTree build_metric_tree_by_insertion(
    const shadowcts::metric::LightFrame& frame,
    const std::vector<shadowcts::metric::LightSpaceElement>& elements,
    double initial_partition_distance, std::uint64_t seed);

}  // namespace shadowcts::simd::metric
