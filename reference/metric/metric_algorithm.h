#pragma once
// Reference `metric`: clustered hard shadows through a ternary metric tree over the clusters'
// cones and capsule-cones (Deves et al., "Scalable Real-Time Shadows using Clustering and Metric
// Trees", EGPGV 2018). The pipeline is in metric_shadows.h.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "metric", backend "reference"; variants "capsules" (default: spheres and capsules, insertion
// build), "spheres", "median" (median build) and "capsules16" (16 triangles per cluster).
std::unique_ptr<Algorithm> make_metric();

}  // namespace shadowcts
