#include "reference/closed_mesh_culling.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <span>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>

#include "reference/sample_access.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

// A uniform grid over some of the boxes, each cell listing the boxes that meet it (closed). A
// point's cell is found by comparing it with the cells' float bounds, so the boxes listed for it
// include every box that holds it.
class BoxGrid {
 public:
  BoxGrid(const MeshBoxes& boxes, const std::vector<std::uint32_t>& which) {
    for (const std::uint32_t m : which) {
      lo_ = glm::min(lo_, boxes.lo[m]);
      hi_ = glm::max(hi_, boxes.hi[m]);
    }
    for (int axis = 0; axis < 3; ++axis) {
      cells_[axis] = hi_[axis] > lo_[axis] ? per_axis : 1;
      // Ascending from lo to hi whatever the roundings (or an infinite width) do: the search
      // below needs sorted bounds.
      split_[axis][0] = lo_[axis];
      for (int i = 1; i < cells_[axis]; ++i) {
        float split = lo_[axis] + (hi_[axis] - lo_[axis]) * float(i) / float(cells_[axis]);
        if (!(split >= split_[axis][i - 1])) split = split_[axis][i - 1];
        split_[axis][i] = std::min(split, hi_[axis]);
      }
      split_[axis][cells_[axis]] = hi_[axis];
    }
    std::vector<std::uint32_t> count(per_axis * per_axis * per_axis + 1, 0);
    const auto for_each_cell = [&](std::uint32_t m, auto&& f) {
      int first[3], last[3];
      for (int axis = 0; axis < 3; ++axis) {
        first[axis] = last[axis] = -1;
        for (int i = 0; i < cells_[axis]; ++i)
          if (split_[axis][i] <= boxes.hi[m][axis] && boxes.lo[m][axis] <= split_[axis][i + 1]) {
            if (first[axis] < 0) first[axis] = i;
            last[axis] = i;
          }
      }
      for (int i = first[0]; i >= 0 && i <= last[0]; ++i)
        for (int j = first[1]; j >= 0 && j <= last[1]; ++j)
          for (int k = first[2]; k >= 0 && k <= last[2]; ++k) f(cell_index(i, j, k));
    };
    for (const std::uint32_t m : which)
      for_each_cell(m, [&](std::size_t cell) { ++count[cell + 1]; });
    for (std::size_t cell = 1; cell < count.size(); ++cell) count[cell] += count[cell - 1];
    first_.assign(count.begin(), count.end());
    listed_.resize(count.back());
    for (const std::uint32_t m : which)
      for_each_cell(m, [&](std::size_t cell) { listed_[count[cell]++] = m; });
  }

  // The boxes that may hold p: none outside the grid.
  std::span<const std::uint32_t> boxes_near(const glm::vec3& p) const {
    if (!(p.x >= lo_.x && p.x <= hi_.x && p.y >= lo_.y && p.y <= hi_.y && p.z >= lo_.z &&
          p.z <= hi_.z))
      return {};
    int index[3];
    for (int axis = 0; axis < 3; ++axis) {
      // Cell i holds [split i, split i + 1), the last one its upper split too.
      const float* inner = split_[axis] + 1;
      index[axis] = int(std::upper_bound(inner, inner + cells_[axis] - 1, p[axis]) - inner);
    }
    const std::size_t cell = cell_index(index[0], index[1], index[2]);
    return {listed_.data() + first_[cell], listed_.data() + first_[cell + 1]};
  }

 private:
  static constexpr int per_axis = 16;
  static std::size_t cell_index(int i, int j, int k) {
    return (std::size_t(i) * per_axis + std::size_t(j)) * per_axis + std::size_t(k);
  }
  glm::vec3 lo_{std::numeric_limits<float>::infinity()};
  glm::vec3 hi_{-std::numeric_limits<float>::infinity()};
  int cells_[3] = {1, 1, 1};
  float split_[3][per_axis + 1] = {};
  std::vector<std::uint32_t> first_, listed_;
};

}  // namespace

MeshBoxes::MeshBoxes(std::size_t n)
    : lo(n, glm::vec3(std::numeric_limits<float>::infinity())),
      hi(n, glm::vec3(-std::numeric_limits<float>::infinity())) {}

// Per thread, then merged: the minimum and maximum of floats do not depend on the order.
MeshBoxes mesh_boxes(const Case& c) {
  const std::size_t n = c.meshes.size();
  tbb::combinable<MeshBoxes> partial([n] { return MeshBoxes(n); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.triangles.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      MeshBoxes& b = partial.local();
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Triangle& t = c.triangles[i];
                        if (t.mesh >= n) continue;
                        for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
                          b.lo[t.mesh] = glm::min(b.lo[t.mesh], v);
                          b.hi[t.mesh] = glm::max(b.hi[t.mesh], v);
                        }
                      }
                    });
  MeshBoxes boxes(n);
  partial.combine_each([&](const MeshBoxes& b) {
    for (std::size_t m = 0; m < n; ++m) {
      boxes.lo[m] = glm::min(boxes.lo[m], b.lo[m]);
      boxes.hi[m] = glm::max(boxes.hi[m], b.hi[m]);
    }
  });
  return boxes;
}

namespace {

template <class Samples>
std::vector<bool> safe_meshes(const Case& c, const Samples& samples) {
  const std::size_t n = c.meshes.size();
  std::vector<bool> safe(n, false);
  bool any_closed_caster = false;
  for (const Mesh& m : c.meshes) any_closed_caster = any_closed_caster || (m.closed && m.caster);
  if (!any_closed_caster) return safe;

  std::vector<std::uint8_t> holds_sample(n, 0);
  run_with_thread_limit(c.parameters.threads, [&] {
    const MeshBoxes boxes = mesh_boxes(c);
    // A visible mesh's box holds its own samples, as a rule: one test per sample finds most
    // meshes that hold one. Setting a flag to 1 from any thread gives the same flags.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, samples.size(), 8192),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            if (!samples.regular(i) || samples.receiver(i) >= c.triangles.size()) continue;
            const std::uint32_t m = c.triangles[samples.receiver(i)].mesh;
            if (m < n && boxes.holds(m, samples.position(i)))
              std::atomic_ref<std::uint8_t>(holds_sample[m]).store(1, std::memory_order_relaxed);
          }
        });
    // The closed casters left: each sample is tested against the boxes that meet its cell of a
    // grid over them. Scanning every sample for every closed mesh took half a second on a
    // million-triangle scene.
    std::vector<std::uint32_t> open;
    for (std::size_t m = 0; m < n; ++m) {
      if (!c.meshes[m].closed || !c.meshes[m].caster || holds_sample[m]) continue;
      if (c.light && c.light->kind == ShadowLightKind::point && boxes.holds(m, c.light->position))
        continue;
      open.push_back(std::uint32_t(m));
    }
    if (open.empty()) return;
    const BoxGrid grid(boxes, open);
    for (const std::uint32_t m : open) holds_sample[m] = 2;  // until a sample lies in its box
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 8192),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          if (!samples.regular(i)) continue;
                          const glm::vec3 p = samples.position(i);
                          for (const std::uint32_t m : grid.boxes_near(p)) {
                            std::atomic_ref<std::uint8_t> flag(holds_sample[m]);
                            if (flag.load(std::memory_order_relaxed) == 2 && boxes.holds(m, p))
                              flag.store(1, std::memory_order_relaxed);
                          }
                        }
                      });
  });
  for (std::size_t m = 0; m < n; ++m) safe[m] = holds_sample[m] == 2;
  return safe;
}

}  // namespace

std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples) {
  return safe_meshes(c, ViewSampleAccess{samples});
}

std::vector<bool> meshes_safe_for_face_culling(const Case& c, const RegularSamples& samples) {
  return safe_meshes(c, RegularSampleAccess{samples});
}

}  // namespace shadowcts
