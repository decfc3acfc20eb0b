#include "reference/ptsv/hierarchy.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace shadowcts::ptsv {

ClusterHierarchy::ClusterHierarchy(const ClusterKeyLayout& layout,
                                   const std::vector<std::uint32_t>& keys,
                                   const ViewSamples& samples,
                                   const std::vector<double>& sample_reach)
    : layout_(layout) {
  if (sample_reach.size() != samples.samples.size())
    throw std::logic_error("ptsv: one reject reach per sample expected");
  const int leaves = leaf_level();
  levels_.resize(std::size_t(leaves) + 1);

  // Existing nodes of every level: the distinct key prefixes. The root (level 0) always exists.
  std::vector<std::uint32_t> sorted;
  for (std::uint32_t key : keys)
    if (key != no_key) sorted.push_back(key);
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  for (int l = leaves; l >= 0; --l) {
    HierarchyLevel& level = levels_[std::size_t(l)];
    const int shift = fanout_bits * (leaves - l);
    for (std::uint32_t key : sorted) {
      const std::uint32_t index = shift >= 32 ? 0u : key >> shift;
      if (level.index.empty() || level.index.back() != index) level.index.push_back(index);
    }
    if (l == 0 && level.index.empty()) level.index.push_back(0);
    level.child_mask.assign(level.index.size(), 0u);
    const glm::dvec3 empty_lo(std::numeric_limits<double>::infinity());
    level.bounds.assign(level.index.size(), WorldBox{empty_lo, -empty_lo});
    level.reject_reach.assign(level.index.size(), 0.0);
  }
  // Child masks: each existing node sets its bit in its parent (the paper's bottom-up pass).
  for (int l = leaves; l >= 1; --l)
    for (std::uint32_t index : levels_[std::size_t(l)].index) {
      const std::ptrdiff_t parent = find(l - 1, index >> fanout_bits);
      levels_[std::size_t(l - 1)].child_mask[std::size_t(parent)] |= 1u << (index & 31u);
    }
  // Explicit bounds and reject reach: every sample grows those of each node on its path.
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == no_key) continue;
    const glm::dvec3 p(samples.samples[i].position);
    for (int l = leaves; l >= 0; --l) {
      const int shift = fanout_bits * (leaves - l);
      const std::uint32_t index = shift >= 32 ? 0u : keys[i] >> shift;
      const std::size_t at = std::size_t(find(l, index));
      WorldBox& box = levels_[std::size_t(l)].bounds[at];
      box.lo = glm::min(box.lo, p);
      box.hi = glm::max(box.hi, p);
      double& reach = levels_[std::size_t(l)].reject_reach[at];
      reach = std::max(reach, sample_reach[i]);
    }
  }
  // Samples per 8x8 tile, for the leaf tests.
  const std::size_t tiles = std::size_t(layout_.tiles_x) * layout_.tiles_y;
  tile_offsets_.assign(tiles + 1, 0u);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == no_key) continue;
    const ViewSample& s = samples.samples[i];
    ++tile_offsets_[std::size_t(s.pixel_y / cluster_tile_size) * layout_.tiles_x +
                    s.pixel_x / cluster_tile_size + 1];
  }
  for (std::size_t t = 0; t < tiles; ++t) tile_offsets_[t + 1] += tile_offsets_[t];
  tile_samples_.resize(tile_offsets_.back());
  std::vector<std::uint32_t> fill(tile_offsets_.begin(), tile_offsets_.end() - 1);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == no_key) continue;
    const ViewSample& s = samples.samples[i];
    const std::size_t tile = std::size_t(s.pixel_y / cluster_tile_size) * layout_.tiles_x +
                             s.pixel_x / cluster_tile_size;
    tile_samples_[fill[tile]++] = std::uint32_t(i);
  }
}

std::ptrdiff_t ClusterHierarchy::find(int l, std::uint32_t index) const {
  const std::vector<std::uint32_t>& v = levels_[std::size_t(l)].index;
  const auto it = std::lower_bound(v.begin(), v.end(), index);
  if (it == v.end() || *it != index) return -1;
  return it - v.begin();
}

std::uint32_t ClusterHierarchy::child_mask(int l, std::uint32_t index) const {
  const std::ptrdiff_t at = find(l, index);
  return at < 0 ? 0u : levels_[std::size_t(l)].child_mask[std::size_t(at)];
}

void ClusterHierarchy::clear_children(int l, std::uint32_t index, std::uint32_t bits) {
  const std::ptrdiff_t at = find(l, index);
  if (at < 0) throw std::logic_error("ptsv: clearing children of a node that does not exist");
  levels_[std::size_t(l)].child_mask[std::size_t(at)] &= ~bits;
}

const WorldBox& ClusterHierarchy::bounds(int l, std::uint32_t index) const {
  const std::ptrdiff_t at = find(l, index);
  if (at < 0) throw std::logic_error("ptsv: bounds of a node that does not exist");
  return levels_[std::size_t(l)].bounds[std::size_t(at)];
}

const std::uint32_t* ClusterHierarchy::tile_begin(std::uint32_t tx, std::uint32_t ty) const {
  return tile_samples_.data() + tile_offsets_[std::size_t(ty) * layout_.tiles_x + tx];
}

const std::uint32_t* ClusterHierarchy::tile_end(std::uint32_t tx, std::uint32_t ty) const {
  return tile_samples_.data() + tile_offsets_[std::size_t(ty) * layout_.tiles_x + tx + 1];
}

bool ClusterHierarchy::path_intact(std::uint32_t key) const {
  const int leaves = leaf_level();
  for (int l = 0; l < leaves; ++l) {
    const int shift = fanout_bits * (leaves - l);
    const std::uint32_t index = shift >= 32 ? 0u : key >> shift;
    const std::uint32_t child = (key >> (fanout_bits * (leaves - l - 1))) & 31u;
    if ((child_mask(l, index) & (1u << child)) == 0) return false;
  }
  return true;
}

std::uint64_t ClusterHierarchy::node_count() const {
  std::uint64_t n = 0;
  for (const HierarchyLevel& level : levels_) n += level.index.size();
  return n;
}

}  // namespace shadowcts::ptsv
