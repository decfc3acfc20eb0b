#include "reference/closed_mesh_culling.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>

#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

struct MeshBoxes {
  std::vector<glm::vec3> lo, hi;
  explicit MeshBoxes(std::size_t n)
      : lo(n, glm::vec3(std::numeric_limits<float>::infinity())),
        hi(n, glm::vec3(-std::numeric_limits<float>::infinity())) {}
  // Float comparisons of float coordinates are exact: "inside the box" is decided exactly.
  bool holds(std::size_t m, const glm::vec3& p) const {
    return p.x >= lo[m].x && p.x <= hi[m].x && p.y >= lo[m].y && p.y <= hi[m].y && p.z >= lo[m].z &&
           p.z <= hi[m].z;
  }
};

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

}  // namespace

std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples) {
  const std::size_t n = c.meshes.size();
  std::vector<bool> safe(n, false);
  bool any_closed_caster = false;
  for (const Mesh& m : c.meshes) any_closed_caster = any_closed_caster || (m.closed && m.caster);
  if (!any_closed_caster) return safe;

  std::vector<std::uint8_t> holds_sample(n, 0);
  run_with_thread_limit(c.parameters.threads, [&] {
    const MeshBoxes boxes = mesh_boxes(c);
    const auto is_regular = [&](const ViewSample& s) {
      return s.sample_class == SampleClass::regular;
    };
    // A visible mesh's box holds its own samples, as a rule: one test per sample finds most
    // meshes that hold one. Setting a flag to 1 from any thread gives the same flags.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, samples.samples.size(), 8192),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const ViewSample& s = samples.samples[i];
            if (!is_regular(s) || s.receiver >= c.triangles.size()) continue;
            const std::uint32_t m = c.triangles[s.receiver].mesh;
            if (m < n && boxes.holds(m, s.position))
              std::atomic_ref<std::uint8_t>(holds_sample[m]).store(1, std::memory_order_relaxed);
          }
        });
    // The closed casters left: each sample is tested against the boxes that span its x. The box
    // ends split the x axis into slots, each listing the boxes that overlap it (closed). Scanning
    // every sample for every closed mesh took half a second on a million-triangle scene.
    std::vector<std::size_t> open;
    std::vector<float> ends;
    for (std::size_t m = 0; m < n; ++m) {
      if (!c.meshes[m].closed || !c.meshes[m].caster || holds_sample[m]) continue;
      if (c.light && c.light->kind == ShadowLightKind::point && boxes.holds(m, c.light->position))
        continue;
      open.push_back(m);
      ends.push_back(boxes.lo[m].x);
      ends.push_back(boxes.hi[m].x);
    }
    if (open.empty()) return;
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    // Slot j: x in [ends[j - 1], ends[j]), without a bound below for j = 0 (no box there) or
    // above for the last (the boxes that end at the last end).
    std::vector<std::vector<std::uint32_t>> slot_boxes(ends.size() + 1);
    for (std::size_t j = 1; j <= ends.size(); ++j) {
      const float upper = j < ends.size() ? ends[j] : std::numeric_limits<float>::infinity();
      for (const std::size_t m : open)
        if (boxes.lo[m].x <= upper && boxes.hi[m].x >= ends[j - 1])
          slot_boxes[j].push_back(std::uint32_t(m));
    }
    for (const std::size_t m : open) holds_sample[m] = 2;  // until a sample lies in its box
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, samples.samples.size(), 8192),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const ViewSample& s = samples.samples[i];
            if (!is_regular(s)) continue;
            const std::size_t j = std::size_t(
                std::upper_bound(ends.begin(), ends.end(), s.position.x) - ends.begin());
            for (const std::uint32_t m : slot_boxes[j]) {
              std::atomic_ref<std::uint8_t> flag(holds_sample[m]);
              if (flag.load(std::memory_order_relaxed) == 2 && boxes.holds(m, s.position))
                flag.store(1, std::memory_order_relaxed);
            }
          }
        });
  });
  for (std::size_t m = 0; m < n; ++m) safe[m] = holds_sample[m] == 2;
  return safe;
}

}  // namespace shadowcts
