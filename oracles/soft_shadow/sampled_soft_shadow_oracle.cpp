#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/exact_segment_triangle.h"
#include "oracles/soft_shadow/band_sensitivity.h"
#include "oracles/soft_shadow/light_cone_bvh.h"
#include "oracles/soft_shadow/sun_disk_projection.h"
#include "shadowcts/embree_scene.h"
#include "shadowcts/errors.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

// Handed through rtcOccluded1 to the filter, which casts the context pointer back.
struct ReceiverContext {
  RTCIntersectContext context;  // first member
  unsigned receiver_primitive;
};

// The receiver never shadows its own sample.
void ignore_receiver(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const ReceiverContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1 &&
        RTCHitN_primID(args->hit, args->N, i) == context->receiver_primitive)
      args->valid[i] = 0;
}

std::vector<std::uint32_t> casters_of(const Case& c) {
  std::vector<std::uint32_t> casters;
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (oracle_casts_shadow(c, i)) casters.push_back(std::uint32_t(i));
  return casters;
}

// Shirley and Chiu's concentric map: equal-area from [0, 1]^2 onto the unit disk.
glm::dvec2 concentric_disk(double u, double v) {
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  double r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = (std::numbers::pi / 4.0) * (b / a);
  } else {
    r = b;
    phi = std::numbers::pi / 2.0 - (std::numbers::pi / 4.0) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// A seed for sample i of a case: SplitMix64 of the case seed and the index, so every sample has
// its own stream whatever thread computes it.
std::uint64_t sample_seed(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + index + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

SoftShadowTruth sampled_soft_shadow_oracle(const Case& c, const ViewSamples& samples,
                                           std::uint32_t rays_per_sample) {
  const SunDiskFrame frame = sun_disk_frame(c);
  check_receivers(c, samples);
  if (rays_per_sample == 0)
    throw InputError(c.source, "rays_per_sample", "the sampled oracle needs at least one ray");
  const auto side = std::uint32_t(std::ceil(std::sqrt(double(rays_per_sample)) - 1e-9));
  const double rays = double(side) * double(side);
  const std::size_t n = samples.samples.size();

  SoftShadowTruth truth;
  truth.exact = false;
  truth.eps_rel = c.parameters.eps_rel;
  truth.tau = c.parameters.eps_rel * c.scale();
  const double bound = std::sqrt(std::log(2.0 / sampled_oracle_failure_probability) / (2.0 * rays));
  truth.method = "sampled: " + std::to_string(side * side) +
                 " stratified Embree rays per sample over the disk (concentric map), bound " +
                 std::to_string(bound) +
                 " at failure probability 1e-9 per sample (Hoeffding); robust by the exact "
                 "oracle's band sensitivity";
  truth.visible_fraction.assign(n, 1.0);
  truth.error_bound.assign(n, 0.0);
  truth.band_sensitivity.assign(n, 0.0);
  truth.robust.assign(n, 0);
  truth.compared.assign(n, 0);

  // Every band move lies within this Euclidean distance (as in the exact oracle).
  const double move = std::sqrt(3.0) * truth.tau;
  const EmbreeScene scene(c, casters_of(c), ignore_receiver, c.triangle_scale());
  run_with_thread_limit(c.parameters.threads, [&] {
    const LightConeBvh casters(c);
    phase_progress::begin(n, "view samples");
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 16),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const ViewSample& sample = samples.samples[i];
            if (sample.sample_class != SampleClass::regular) continue;
            std::mt19937_64 random(sample_seed(c.parameters.seed, i));
            const auto uniform = [&] { return double(random() >> 11) * 0x1p-53; };
            ReceiverContext context;
            std::uint32_t unblocked = 0;
            const glm::vec3 origin = scene.to_scene(glm::dvec3(sample.position));
            for (std::uint32_t a = 0; a < side; ++a)
              for (std::uint32_t b = 0; b < side; ++b) {
                const double u = (double(a) + uniform()) / double(side);
                const double v = (double(b) + uniform()) / double(side);
                const glm::dvec2 on_disk = concentric_disk(u, v) * frame.tan_radius;
                const glm::dvec3 direction =
                    frame.direction + on_disk.x * frame.x_axis + on_disk.y * frame.y_axis;
                rtcInitIntersectContext(&context.context);
                context.receiver_primitive = scene.primitive_of_triangle(sample.receiver);
                RTCRay ray{};
                ray.org_x = origin.x;
                ray.org_y = origin.y;
                ray.org_z = origin.z;
                ray.dir_x = float(direction.x);
                ray.dir_y = float(direction.y);
                ray.dir_z = float(direction.z);
                ray.tnear = 0.0f;
                ray.tfar = std::numeric_limits<float>::infinity();
                ray.mask = 0xffffffffu;
                rtcOccluded1(scene.handle(), &context.context, &ray);
                if (ray.tfar != -std::numeric_limits<float>::infinity()) ++unblocked;
              }
            truth.visible_fraction[i] = double(unblocked) / rays;
            truth.error_bound[i] = bound;
            truth.compared[i] = 1;
            // Rays estimate the fraction but cannot tell how near it is to changing: the band
            // sensitivity, the exact oracle's own bound, decides robustness for both oracles.
            truth.band_sensitivity[i] = sample_band_sensitivity(c, frame, casters, sample, move);
            truth.robust[i] = truth.band_sensitivity[i] <= soft_robust_sensitivity ? 1 : 0;
          }
          phase_progress::advance(range.size());
        });
  });
  return truth;
}

}  // namespace shadowcts
