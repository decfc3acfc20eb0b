#include "reference/embree/soft_shadow_embree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "reference/embree/hard_shadow_embree.h"
#include "reference/sample_half_space.h"
#include "shadowcts/embree_scene.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

// The per-sample failure probability the per-sample budget is stated at.
constexpr double budget_failure_probability = 1e-9;
// Rays per Embree packet (rtcOccluded16); every variant's N is a multiple of it.
constexpr std::uint32_t packet = 16;

struct VariantRays {
  const char* name;
  std::uint32_t rays;
};
constexpr std::array<VariantRays, 3> variants = {
    {{"rays16", 16}, {"rays64", 64}, {"rays256", 256}}};

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double unit_interval(std::uint64_t bits) {
  return double(bits >> 11) * 0x1p-53;
}

// The equal-area concentric map (Shirley and Chiu) of [0, 1)^2 onto the unit disk.
glm::dvec2 concentric(double u, double v) {
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  constexpr double quarter = std::numbers::pi / 4.0;
  double r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = quarter * (b / a);
  } else {
    r = b;
    phi = 2.0 * quarter - quarter * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// An orthonormal frame (e1, e2, d) around the light's unit direction d.
struct DiskFrame {
  glm::dvec3 d, e1, e2;
  double tangent;  // tan(a): the disk's radius in the plane at unit distance along d
};

DiskFrame disk_frame(const ShadowLight& light) {
  DiskFrame f;
  f.d = glm::normalize(glm::dvec3(light.direction));
  const glm::dvec3 absolute = glm::abs(f.d);
  glm::dvec3 axis(0.0);
  axis[absolute.x <= absolute.y && absolute.x <= absolute.z ? 0
       : absolute.y <= absolute.z                           ? 1
                                                            : 2] = 1.0;
  f.e1 = glm::normalize(glm::cross(f.d, axis));
  f.e2 = glm::cross(f.d, f.e1);
  f.tangent = std::tan(double(light.angular_radius));
  return f;
}

// What the occlusion filter needs about the sample whose rays are in flight. Embree hands the
// filter the context pointer it was given, so the context is the first member.
struct SampleContext {
  RTCIntersectContext context;
  const PreparedScene* scene;
  const EmbreeScene* embree;
  const ViewSample* sample;
  HardShadowLight ray_light;  // directional, set per ray from its direction
};

// Rejects the receiver's own hits and, under the receiver half-space rule for the ray's own
// direction, hits that are not strictly on the light's side of the receiver's plane.
void filter_hits(const RTCFilterFunctionNArguments* args) {
  auto* sample = reinterpret_cast<SampleContext*>(args->context);
  const PreparedScene& scene = *sample->scene;
  const CasterArrays& casters = scene.casters;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const std::uint32_t t =
        sample->embree->triangle_of_primitive(RTCHitN_primID(args->hit, args->N, i));
    if (t == sample->sample->receiver) {
      args->valid[i] = 0;
      continue;
    }
    sample->ray_light.directional = true;
    sample->ray_light.direction = {RTCRayN_dir_x(args->ray, args->N, i),
                                   RTCRayN_dir_y(args->ray, args->N, i),
                                   RTCRayN_dir_z(args->ray, args->N, i)};
    const geometry::ReceiverHalfSpace half_space =
        sample_half_space(scene.source, sample->ray_light, *sample->sample);
    if (!geometry::caster_counts(half_space, glm::dvec3(sample->sample->position),
                                 glm::dvec3(casters.corner(t, 0)), glm::dvec3(casters.corner(t, 1)),
                                 glm::dvec3(casters.corner(t, 2))))
      args->valid[i] = 0;
  }
}

class EmbreeSoftShadow final : public VariantTableAlgorithm<std::uint32_t> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // Embree's float32 range, as for the hard-shadow peer (hard_shadow_embree.h); the ray
  // directions are unit vectors, so the case scale alone decides.
  std::optional<std::string> input_problem(const Case& c, const ViewSamples&,
                                           const Variant&) const override {
    const double scale = c.scale();
    if (!(scale >= std::ldexp(1.0, embree_min_scale_exponent)) ||
        scale > std::ldexp(1.0, embree_max_scale_exponent))
      return "the case scale S = " + std::to_string(scale) +
             " is outside Embree's float32 range 2^" + std::to_string(embree_min_scale_exponent) +
             " <= S <= 2^" + std::to_string(embree_max_scale_exponent);
    return std::nullopt;
  }

  // build: the Embree scene of the casters (BVH build, commit); query: the rays.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const std::uint32_t rays = variant.config;
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    if (!scene.light || scene.light->kind != ShadowLightKind::sun_disk)
      throw std::invalid_argument("embree_soft: the case has no sun disk");
    check_receivers(c, samples);
    const DiskFrame frame = disk_frame(*scene.light);
    const RegularSamples& regular = scene.samples;
    std::vector<float> fraction(regular.size(), 1.0f);
    std::atomic<std::uint64_t> occluded_total{0};
    PhaseClock clock;
    run_with_thread_limit(c.parameters.threads, [&] {
      clock.restart();
      std::vector<std::uint32_t> casters;
      for (std::uint32_t t = 0; t < scene.casters.size(); ++t)
        if (scene.casters.casts[t]) casters.push_back(t);
      const EmbreeScene embree(c, std::move(casters), filter_hits, 0.0);  // the peer: unscaled
      clock.lap(build_phase);
      phase_progress::begin(regular.size(), "regular samples");
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, regular.size(), 64),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          std::uint64_t occluded_here = 0;
                          alignas(64) RTCRay16 ray;
                          alignas(64) int valid[packet];
                          for (std::size_t j = range.begin(); j != range.end(); ++j) {
                            const ViewSample& sample = samples.samples[regular.index[j]];
                            SampleContext context{};
                            rtcInitIntersectContext(&context.context);
                            context.scene = &scene;
                            context.embree = &embree;
                            context.sample = &sample;
                            std::uint32_t blocked = 0;
                            for (std::uint32_t first = 0; first < rays; first += packet) {
                              for (std::uint32_t k = 0; k < packet; ++k) {
                                const glm::dvec2 q = embree_soft_disk_point(
                                    c.parameters.seed, regular.index[j], rays, first + k);
                                const glm::dvec3 direction = glm::normalize(
                                    frame.d + frame.tangent * (q.x * frame.e1 + q.y * frame.e2));
                                valid[k] = -1;
                                ray.org_x[k] = regular.px[j];
                                ray.org_y[k] = regular.py[j];
                                ray.org_z[k] = regular.pz[j];
                                ray.dir_x[k] = float(direction.x);
                                ray.dir_y[k] = float(direction.y);
                                ray.dir_z[k] = float(direction.z);
                                ray.tnear[k] = 0.0f;
                                ray.tfar[k] = std::numeric_limits<float>::infinity();
                                ray.time[k] = 0.0f;
                                ray.mask[k] = ~0u;
                                ray.id[k] = first + k;
                                ray.flags[k] = 0;
                              }
                              rtcOccluded16(valid, embree.handle(), &context.context, &ray);
                              // Embree marks an occluded ray by tfar = -inf.
                              for (std::uint32_t k = 0; k < packet; ++k)
                                blocked += ray.tfar[k] < 0.0f ? 1 : 0;
                            }
                            occluded_here += blocked;
                            // rays is a power of two: the quotient is exact in float.
                            fraction[j] = float(rays - blocked) / float(rays);
                          }
                          occluded_total += occluded_here;
                          phase_progress::advance(range.size());
                        });
      clock.lap(query_phase);
    });
    AlgorithmOutput output;
    output.visible_fraction = scene.per_view_sample(fraction, 1.0f);
    output.counters = {{"rays", std::uint64_t(rays) * regular.size()},
                       {"occluded_rays", occluded_total.load()}};
    output.phase_ms = clock.times();
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_embree_soft_shadow() {
  std::vector<AlgorithmVariant<std::uint32_t>> table;
  for (const VariantRays& v : variants)
    table.push_back(
        {.name = v.name, .config = v.rays, .soft_error_budget = embree_soft_error_budget(v.name)});
  return std::make_unique<EmbreeSoftShadow>(
      AlgorithmDescription{
          .id = "embree_soft",
          .backend = "embree",
          .summary = "Embree 3 robust occlusion rays towards N stratified points of the sun disk "
                     "(gnomonic measure, equal-area strata, fixed seed); receiver half-space rule "
                     "per ray",
          .capabilities = {.output = OutputKind::soft_shadow, .sun_disk = true}},
      std::move(table));
}

std::uint32_t embree_soft_rays(const std::string& variant) {
  for (const VariantRays& v : variants)
    if (variant == v.name) return v.rays;
  throw std::invalid_argument("embree_soft: unknown variant '" + variant + "'");
}

SoftErrorBudget embree_soft_error_budget(const std::string& variant) {
  const double n = double(embree_soft_rays(variant));
  // docs/soft-shadow-budgets.md. The estimate is the mean of N independent stratum indicators
  // (stratum i blocked with probability p_i, its covered share), so e = sum (X_i - p_i) / N.
  // Per sample, Hoeffding: P(|e| > t) <= 2 exp(-2 N t^2). Mean: E|e| <= sqrt(Var e) <=
  // sqrt(N / 4) / N = 1 / (2 sqrt N) (every stratum half covered); the budget is twice that.
  SoftErrorBudget budget;
  budget.per_sample = std::sqrt(std::log(2.0 / budget_failure_probability) / (2.0 * n));
  budget.mean = 1.0 / std::sqrt(n);
  return budget;
}

glm::dvec2 embree_soft_disk_point(std::uint64_t seed, std::uint32_t pixel, std::uint32_t rays,
                                  std::uint32_t stratum) {
  const auto k = std::uint32_t(std::lround(std::sqrt(double(rays))));
  // A counter-based generator: the jitter of a stratum depends on (seed, pixel, stratum) only, so
  // any thread order gives the same points.
  const std::uint64_t key =
      mix(seed * 0x9E3779B97F4A7C15ull ^ mix((std::uint64_t(pixel) << 32) | stratum));
  const double u = (double(stratum % k) + unit_interval(mix(key))) / double(k);
  const double v = (double(stratum / k) + unit_interval(mix(key + 0x9E3779B97F4A7C15ull))) / k;
  return concentric(u, v);
}

}  // namespace shadowcts
