#pragma once
// Cluster keys of the simd ptsv (the reference's cluster_keys.h defines them): the same layout and
// the same per-sample key, computed for the regular samples in parallel.
#include <cstdint>
#include <string>
#include <vector>

#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd::ptsv {

namespace ref = ::shadowcts::ptsv;

// key[i] is the key of regular sample i (PreparedScene::samples order). On the first sample the
// layout cannot hold, problem is the reference's message for it and key is empty.
struct ClusterKeys {
  std::vector<std::uint32_t> key;
  std::string problem;
};
ClusterKeys assign_cluster_keys(const ref::ClusterKeyLayout& layout, const ref::ViewFrame& frame,
                                const PreparedScene& scene, bool require_pixel_wedge);

// The keys spread over every view sample (ref::no_key for the others), as the reference holds them.
std::vector<std::uint32_t> keys_per_view_sample(const PreparedScene& scene,
                                                const std::vector<std::uint32_t>& key);

}  // namespace shadowcts::simd::ptsv
