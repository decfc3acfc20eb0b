#include "reference/psv/rule_culling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "reference/closed_mesh_culling.h"
#include "reference/sample_access.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts::psv {
namespace {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
};

bool overlap(const Box& a, const Box& b) {
  for (int i = 0; i < 3; ++i)
    if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return false;
  return true;
}

// The receiver's orientation det[b - a, c - a, x - a] (a point) or det[b - a, c - a, x] (a
// direction) in double, and a bound on its error: every entry and product rounds once or twice,
// (7 + 56 eps) eps of the permanent bounds it (Shewchuk's orient3d, stage A); 2^-48 has room.
struct Orientation {
  glm::dvec3 a, normal, permanent_normal;
  void value(const glm::dvec3& w, double& f, double& error) const {
    f = glm::dot(normal, w);
    error = 0x1p-48 * glm::dot(permanent_normal, glm::abs(w));
  }
};

Orientation receiver_orientation(const Triangle& r) {
  Orientation o;
  o.a = glm::dvec3(r.v0);
  const glm::dvec3 u = glm::dvec3(r.v1) - o.a, v = glm::dvec3(r.v2) - o.a;
  const glm::dvec3 au = glm::abs(u), av = glm::abs(v);
  o.normal = glm::cross(u, v);
  o.permanent_normal = {au.y * av.z + au.z * av.y, au.z * av.x + au.x * av.z,
                        au.x * av.y + au.y * av.x};
  return o;
}

template <class Samples>
std::vector<bool> clear_of_segment_starts(const Case& c, const Samples& samples,
                                          const HardShadowLight& light, std::vector<bool> safe) {
  if (std::find(safe.begin(), safe.end(), true) == safe.end()) return safe;
  // The safe meshes' boxes (an empty mesh's is empty and meets nothing).
  std::vector<Box> boxes(safe.size());
  run_with_thread_limit(c.parameters.threads, [&] {
    const MeshBoxes mesh = mesh_boxes(c);
    for (std::size_t m = 0; m < std::min(safe.size(), mesh.lo.size()); ++m)
      if (safe[m]) boxes[m] = {glm::dvec3(mesh.lo[m]), glm::dvec3(mesh.hi[m])};
  });
  // Samples in parallel, each range switching off in its own copy the meshes whose boxes meet a
  // segment start's box; a mesh stays safe only where no range switched it off.
  const std::vector<char> initially(safe.begin(), safe.end());
  std::vector<std::uint32_t> candidates;  // the meshes safe so far: most are not
  for (std::size_t m = 0; m < safe.size(); ++m)
    if (safe[m]) candidates.push_back(std::uint32_t(m));
  tbb::combinable<std::vector<char>> still_safe([&] { return initially; });
  std::atomic<bool> none_safe{false};  // a directional light's p* may lie anywhere on its ray
  run_with_thread_limit(c.parameters.threads, [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, samples.size(), 4096),
        [&](const tbb::blocked_range<std::size_t>& range) {
          std::vector<char>& mine = still_safe.local();
          const auto switch_off_meeting = [&](const Box& start) {
            for (const std::uint32_t m : candidates)
              if (mine[m] && overlap(start, boxes[m])) mine[m] = 0;
          };
          for (std::size_t i = range.begin(); i != range.end() && !none_safe.load(); ++i) {
            if (!samples.regular(i) || samples.receiver(i) >= c.triangles.size()) continue;
            const Triangle& r = c.triangles[samples.receiver(i)];
            const Orientation o = receiver_orientation(r);
            const glm::dvec3 p(samples.position(i));
            double f_light = 0.0, e_light = 0.0, f_p = 0.0, e_p = 0.0;
            o.value(light.directional ? light.direction : light.position - o.a, f_light, e_light);
            if (!(std::fabs(f_light) > e_light)) {
              // The light's side is not clear in double: decide exactly whether the rule applies.
              const geometry::ReceiverHalfSpace h = geometry::receiver_half_space(
                  glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2), light.directional,
                  light.directional ? light.direction : light.position);
              if (!h.has_plane || h.light_side == 0) continue;  // no rule, or nothing counts
              if (light.directional) {
                none_safe = true;  // p* anywhere on the ray
                break;
              }
              switch_off_meeting({glm::min(p, light.position), glm::max(p, light.position)});
              continue;
            }
            // f oriented positive on the light's side: p* = p where f(p) > 0 (p lies outside the
            // boxes already), else the segment's crossing of the plane, at t* = -f(p) / (f(L) -
            // f(p)) <= -f(p) / f(L) along L - p (a point light) or -f(p) / Df along d
            // (directional).
            const double side = f_light > 0.0 ? 1.0 : -1.0;
            o.value(p - o.a, f_p, e_p);
            const double below = -side * f_p + e_p;  // >= -f(p)
            if (!(below > 0.0)) continue;
            const glm::dvec3 towards = light.directional ? light.direction : light.position - p;
            const double t = below / (std::fabs(f_light) - e_light) * (1.0 + 0x1p-50);
            const double reach = light.directional ? t : std::min(t, 1.0);
            const glm::dvec3 q = p + reach * towards;
            // The box of p and q holds the segment from p to p*; the margin covers q's roundings.
            const glm::dvec3 margin = 0x1p-48 * (glm::abs(p) + glm::abs(q) + glm::abs(towards));
            switch_off_meeting({glm::min(p, q) - margin, glm::max(p, q) + margin});
          }
        });
  });
  if (none_safe) return std::vector<bool>(safe.size(), false);
  still_safe.combine_each([&](const std::vector<char>& mine) {
    for (std::size_t m = 0; m < safe.size(); ++m) safe[m] = safe[m] && mine[m] != 0;
  });
  return safe;
}

}  // namespace

std::vector<bool> culling_clear_of_segment_starts(const Case& c, const ViewSamples& samples,
                                                  const HardShadowLight& light,
                                                  std::vector<bool> safe) {
  return clear_of_segment_starts(c, ViewSampleAccess{samples}, light, std::move(safe));
}

std::vector<bool> culling_clear_of_segment_starts(const Case& c, const RegularSamples& samples,
                                                  const HardShadowLight& light,
                                                  std::vector<bool> safe) {
  return clear_of_segment_starts(c, RegularSampleAccess{samples}, light, std::move(safe));
}

}  // namespace shadowcts::psv
