#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/soft_shadow/band_sensitivity.h"
#include "oracles/soft_shadow/exact_disk_union.h"
#include "oracles/soft_shadow/light_cone_bvh.h"
#include "oracles/soft_shadow/sun_disk_projection.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

struct SampleResult {
  double fraction = 1.0;
  double sensitivity = 0.0;
  std::uint32_t candidates = 0;
  bool fast_path = false;
};

// The projections of the casters the sample's light cone reaches (the union's input), and with
// `sensitivity` its band sensitivity. One query serves both: triangles within `move` of the cone
// are the band's candidates, and those the cone itself reaches (angle <= a) are the fraction's.
std::vector<DiskPolygon> cone_projections(const Case& c, const SunDiskFrame& frame,
                                          const LightConeBvh& casters, const ViewSample& sample,
                                          double move, double* sensitivity) {
  const glm::dvec3 p(sample.position);
  const LightCone cone{p, frame.direction, frame.angular_radius};
  std::vector<DiskPolygon> projections;
  casters.visit(cone, move, [&](std::uint32_t index) {
    if (index == sample.receiver) return;
    const Triangle& t = c.triangles[index];
    const std::array<glm::dvec3, 3> v{glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
    const std::array<glm::dvec3, 3> w{v[0] - p, v[1] - p, v[2] - p};
    const double angle = angle_to_triangle(frame.direction, w);
    if (angle <= frame.angular_radius) {
      const DiskPolygon projection = project_triangle(frame, p, v, FrontProjection::vertices, 2.0);
      if (projection.count > 0) projections.push_back(projection);
    }
    if (sensitivity && *sensitivity < 1.0)
      *sensitivity =
          std::min(1.0, *sensitivity + caster_band_sensitivity(frame, p, v, angle, move));
  });
  return projections;
}

SampleResult exact_sample(const Case& c, const SunDiskFrame& frame, const LightConeBvh& casters,
                          const ViewSample& sample, double move) {
  SampleResult result;
  const std::vector<DiskPolygon> projections =
      cone_projections(c, frame, casters, sample, move, &result.sensitivity);
  result.candidates = std::uint32_t(projections.size());
  const CoveredDiskArea covered = covered_disk_area(projections);
  result.fast_path = covered.fast_path;
  result.fraction = std::clamp(1.0 - covered.area / std::numbers::pi, 0.0, 1.0);
  return result;
}

}  // namespace

SoftShadowTruth exact_soft_shadow_oracle(const Case& c, const ViewSamples& samples) {
  const SunDiskFrame frame = sun_disk_frame(c);
  check_receivers(c, samples);
  const std::size_t n = samples.samples.size();

  SoftShadowTruth truth;
  truth.method =
      "exact: CGAL General_polygon_set_2, circle-segment traits over exact rationals (projected "
      "coordinates rounded to double), area by Green's theorem; candidates from a conservative "
      "light-cone BVH";
  truth.exact = true;
  truth.eps_rel = c.parameters.eps_rel;
  truth.tau = c.parameters.eps_rel * c.scale();
  truth.visible_fraction.assign(n, 1.0);
  truth.error_bound.assign(n, 0.0);
  truth.band_sensitivity.assign(n, 0.0);
  truth.robust.assign(n, 0);
  truth.compared.assign(n, 0);
  // Every band move p + 2^-j tau u, |u|_inf <= 1, lies within this Euclidean distance.
  const double move = std::sqrt(3.0) * truth.tau;

  std::atomic<std::uint64_t> candidates{0}, fast_paths{0};
  run_with_thread_limit(c.parameters.threads, [&] {
    const LightConeBvh casters(c);
    phase_progress::begin(n, "view samples");
    // Each sample is computed on its own: the result does not depend on the partitioning.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::uint64_t local_candidates = 0, local_fast = 0;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const ViewSample& sample = samples.samples[i];
                          if (sample.sample_class != SampleClass::regular) continue;
                          const SampleResult r = exact_sample(c, frame, casters, sample, move);
                          truth.visible_fraction[i] = r.fraction;
                          truth.band_sensitivity[i] = r.sensitivity;
                          truth.compared[i] = 1;
                          truth.robust[i] = r.sensitivity <= soft_robust_sensitivity ? 1 : 0;
                          local_candidates += r.candidates;
                          local_fast += r.fast_path ? 1 : 0;
                        }
                        candidates += local_candidates;
                        fast_paths += local_fast;
                        phase_progress::advance(range.size());
                      });
  });
  truth.candidate_triangles = candidates.load();
  truth.fast_path_samples = fast_paths.load();
  return truth;
}

ExactSoftShadowWork estimate_exact_soft_shadow_work(const Case& c, const ViewSamples& samples,
                                                    std::uint32_t stride) {
  const SunDiskFrame frame = sun_disk_frame(c);
  stride = std::max<std::uint32_t>(stride, 1);
  std::vector<std::uint32_t> visited;  // every stride-th regular sample, in sample order
  std::uint64_t regular = 0;
  for (std::uint32_t i = 0; i < samples.samples.size(); ++i)
    if (samples.samples[i].sample_class == SampleClass::regular && regular++ % stride == 0)
      visited.push_back(i);
  std::vector<std::uint64_t> projections(visited.size(), 0);
  run_with_thread_limit(c.parameters.threads, [&] {
    const LightConeBvh casters(c);
    tbb::parallel_for(std::size_t(0), visited.size(), [&](std::size_t i) {
      projections[i] =
          cone_projections(c, frame, casters, samples.samples[visited[i]], 0.0, nullptr).size();
    });
  });
  ExactSoftShadowWork work;
  for (const std::uint64_t k : projections) {
    work.projections += stride * k;
    work.squared_projections += double(stride) * double(k) * double(k);
  }
  return work;
}

}  // namespace shadowcts
