#include "gpu/ptsv/ptsv_algorithm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "reference/light_on_caster.h"
#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/counters.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/ptsv_algorithm.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/triangle_setup.h"
#include "reference/ptsv/two_pass.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/errors.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

namespace ref = ::shadowcts::ptsv;

using ref::VariantConfig;

// The reference's variants that this backend ports.
const std::vector<AlgorithmVariant<VariantConfig>> ported_variants =
    select_variants(ptsv_variants(), {"twopass", "explicit+planes", "implicit"});

const VariantConfig& variant_config(const std::string& variant) {
  return find_variant(ported_variants, variant, "ptsv/cuda").config;
}

// The device looks depth slices up in a table of 2^depth_bits + 1 slice starts.
constexpr int max_depth_bits = 24;

bool one_sample_per_pixel(const ViewSamples& samples) {
  return samples.width != 0 && samples.height != 0 &&
         samples.samples.size() == std::size_t(samples.width) * samples.height;
}

double rounding_for_node_bound(double node_bound) {
  return ref::NodeTolerances::for_bounds(node_bound, node_bound).rounding;
}

void copy3(const glm::dvec3& v, double out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

void copy3f(const glm::vec3& v, float out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

gpu_ptsv::Plane pack(const ref::Plane& p) {
  gpu_ptsv::Plane out{};
  copy3(p.normal, out.normal);
  copy3(p.anchor, out.anchor);
  out.shift = p.shift;
  return out;
}

gpu_ptsv::Volume pack(const ref::ShadowVolume& v, const Case& c) {
  gpu_ptsv::Volume out{};
  for (int k = 0; k < 3; ++k) out.plane[k] = pack(v.edges[std::size_t(k)]);
  out.plane[3] = pack(v.triangle_plane);
  for (int k = 0; k < v.extra_count; ++k) out.plane[4 + k] = pack(v.extra[std::size_t(k)]);
  out.extra_count = v.extra_count;
  for (int k = 0; k < 4; ++k) out.condition[k] = v.exact.condition[std::size_t(k)];
  for (int k = 0; k < 3; ++k) {
    copy3f(v.exact.vertices[std::size_t(k)], out.exact_vertices + 3 * k);
    out.edge_outside[k] = v.exact.edge_outside[std::size_t(k)];
  }
  out.triangle_outside = v.exact.triangle_outside;
  copy3f(v.exact.light, out.exact_light);
  out.directional = v.exact.directional ? 1 : 0;
  out.triangle = v.triangle;
  const Triangle& t = c.triangles[v.triangle];
  copy3f(t.v0, out.caster);
  copy3f(t.v1, out.caster + 3);
  copy3f(t.v2, out.caster + 6);
  return out;
}

struct HostSetup {
  gpu_ptsv::KernelInput input;
  ref::ClusterKeyLayout layout;
  ref::SetupCounts counts;
};

// What the reference does on the host before its keys (frame, bound, receiver rule, layout) and
// its triangle setup, packed for the kernels. Timed as the reference times it: the setup is build,
// the volumes query.
HostSetup prepare(const PreparedScene& scene, const VariantConfig& config, PhaseClock* clock) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  hard_shadow_light(c);  // throws InputError without a point or directional light
  check_receivers(c, samples);
  if (!one_sample_per_pixel(samples))
    throw InputError(c.source, "view samples", "not one sample per pixel");
  HostSetup s;
  gpu_ptsv::KernelInput& in = s.input;
  const ref::ViewFrame frame = ref::make_view_frame(c.camera, samples.width, samples.height);
  const double bound = ref::scene_bound(c, samples);
  const ref::ReceiverRule rule(c, samples);
  const ref::KeyLayoutResult layout =
      ref::make_cluster_key_layout(c.camera, samples.width, samples.height);
  if (!layout.problem.empty()) throw InputError(c.source, "camera", layout.problem);
  if (layout.layout.depth_bits > max_depth_bits)
    throw InputError(c.source, "camera", "more than 2^24 depth slices");
  s.layout = layout.layout;
  const ref::ClusterKeyLayout& L = layout.layout;
  gpu_ptsv::Layout& g = in.layout;
  g.tiles_x = L.tiles_x;
  g.tiles_y = L.tiles_y;
  g.x_bits = L.x_bits;
  g.y_bits = L.y_bits;
  g.depth_bits = L.depth_bits;
  g.leaf_level = L.mask_levels();
  g.width = frame.width;
  g.height = frame.height;
  copy3(frame.origin, g.origin);
  copy3(frame.right, g.right);
  copy3(frame.up, g.up);
  copy3(frame.forward, g.forward);
  g.tan_half_fov = frame.tan_half_fov;
  g.aspect = frame.aspect;
  in.slice_start.resize((std::size_t(1) << L.depth_bits) + 1);
  for (std::size_t k = 0; k < in.slice_start.size(); ++k)
    in.slice_start[k] = L.slice_start(std::uint32_t(k));

  // Samples, with the half-space of each regular sample's receiver (slot 0: no receiver).
  in.half_spaces.push_back(rule.half_space(no_receiver));
  std::unordered_map<std::uint32_t, std::uint32_t> slot;
  in.samples.resize(samples.samples.size());
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& v = samples.samples[i];
    gpu_ptsv::Sample& out = in.samples[i];
    copy3f(v.position, out.position);
    out.receiver = v.receiver;
    out.pixel_x = v.pixel_x;
    out.pixel_y = v.pixel_y;
    out.regular = v.sample_class == SampleClass::regular ? 1u : 0u;
    out.reach = rule.reject_reach()[i];
    out.half_space = 0;
    if (out.regular != 0 && v.receiver != no_receiver) {
      const auto [it, added] = slot.try_emplace(v.receiver, std::uint32_t(in.half_spaces.size()));
      if (added) in.half_spaces.push_back(rule.half_space(v.receiver));
      out.half_space = it->second;
    }
  }
  in.implicit_cells = config.implicit_cells();
  in.extra_planes = config.extra_planes;
  in.job_level = config.two_pass ? ref::default_job_level(L.mask_levels()) : -1;
  in.scene_bound = bound;
  in.accept_bias = ref::NodeTolerances::for_bounds(bound, bound).accept_bias;
  in.rounding_for_node_bound = rounding_for_node_bound;
  if (clock) clock->lap(build_phase);

  ref::SetupOptions options;
  options.extra_planes = config.extra_planes;
  const std::vector<ref::ShadowVolume> volumes = ref::set_up_shadow_volumes(
      c, ref::front_face_culling_meshes(c, samples, rule.reject_reach()), options, bound, s.counts);
  in.volumes.reserve(volumes.size());
  for (const ref::ShadowVolume& v : volumes) in.volumes.push_back(pack(v, c));
  if (clock) clock->lap(query_phase);
  return s;
}

class KernelPtsv final : public VariantTableAlgorithm<VariantConfig> {
 public:
  explicit KernelPtsv(PtsvKernelBackend backend)
      : VariantTableAlgorithm(
            backend.describe("ptsv", Capabilities{.output = OutputKind::hard_shadow,
                                                  .point_light = true,
                                                  .directional_light = true,
                                                  .max_sample_triangle_pairs =
                                                      backend.max_sample_triangle_pairs}),
            ported_variants),
        backend_(std::move(backend)) {}

  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    // Before the base class's check of the same limit, to say why the limit is there.
    const std::uint64_t pairs =
        std::uint64_t(samples.count(SampleClass::regular)) * std::uint64_t(c.triangles.size());
    if (backend_.max_sample_triangle_pairs != 0 && pairs > backend_.max_sample_triangle_pairs)
      return "too large for this algorithm: " + std::to_string(pairs) +
             " sample x triangle pairs (limit " +
             std::to_string(backend_.max_sample_triangle_pairs) + "); " +
             backend_.size_limit_reason;
    if (auto why = Algorithm::unsupported_reason(c, samples, variant)) return why;
    if (auto why = unavailable_reason()) return why;
    const VariantConfig& config = this->variant(variant).config;
    if (!one_sample_per_pixel(samples)) return "the view samples are not one per pixel";
    const ref::ViewFrame frame = ref::make_view_frame(c.camera, samples.width, samples.height);
    const ref::KeyLayoutResult layout =
        ref::make_cluster_key_layout(c.camera, samples.width, samples.height);
    if (!layout.problem.empty()) return layout.problem;
    const std::string problem =
        ref::assign_cluster_keys(layout.layout, frame, samples, config.implicit_cells()).problem;
    if (!problem.empty()) return problem;
    if (layout.layout.depth_bits > max_depth_bits)
      return "the key layout has " + std::to_string(layout.layout.depth_bits) +
             " depth bits; the device's slice table holds at most 2^" +
             std::to_string(max_depth_bits) + " slices";
    return std::nullopt;
  }

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const VariantConfig& config = variant.config;
    PhaseClock clock;
    HostSetup setup = prepare(scene, config, &clock);
    gpu_ptsv::KernelResult result;
    // The emulator spreads blocks and Thrust over oneTBB: both keep to the case's thread limit.
    run_with_thread_limit(c.parameters.threads,
                          [&] { result = backend_.run_kernels(std::move(setup.input)); });
    clock.lap(query_phase);
    if (result.first_bad_sample != gpu_ptsv::no_sample) {
      // The reference's message for the sample the device found first.
      const ref::ViewFrame frame = ref::make_view_frame(c.camera, samples.width, samples.height);
      throw InputError(
          c.source, "view samples",
          ref::assign_cluster_keys(setup.layout, frame, samples, config.implicit_cells()).problem);
    }

    AlgorithmOutput output;
    output.shadowed = std::move(result.shadowed);
    const std::uint64_t light_on_caster =
        shadow_samples_by_light_on_caster(c, samples, output.shadowed);
    std::uint64_t nodes = 0;
    for (const gpu_ptsv::Level& level : result.levels) nodes += level.index.size();
    output.counters = ref::to_counters(result.counters, setup.counts,
                                       {.nodes = nodes,
                                        .levels = std::uint64_t(result.levels.size()),
                                        .key_bits = std::uint64_t(setup.layout.key_bits())},
                                       light_on_caster);
    if (backend_.emulated) output.counters.push_back({"emulated_threads", result.threads});
    output.phase_ms = clock.times();
    return output;
  }

  PtsvKernelBackend backend_;
};

}  // namespace

std::unique_ptr<Algorithm> make_ptsv_kernel_algorithm(PtsvKernelBackend backend) {
  return std::make_unique<KernelPtsv>(std::move(backend));
}

std::unique_ptr<Algorithm> make_cuda_emu_ptsv() {
  PtsvKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's ptsv kernels EMULATED on the host (gpu/emulator: a fiber per CUDA "
      "thread, Thrust on oneTBB, no GPU involved); the reference's keys, nodes, counters and mask";
  backend.run_kernels = gpu_ptsv::run_ptsv_kernels_emulated;
  backend.emulated = true;
  // Fibers for every device thread: the query grows with samples x triangles. Measured on the
  // 2-core machines (2026-12-02): 1M triangles x 924k samples (9.2e11 pairs) took 194 s
  // (implicit), 80 s (twopass), 54 s (explicit+planes); the limit keeps each under about 60 s.
  backend.max_sample_triangle_pairs = 250'000'000'000ull;
  backend.size_limit_reason =
      "emulated kernels: ~194 s (implicit), 80 s (twopass) measured at 9.2e11 pairs (1M "
      "triangles x 924k samples, 2 cores); the cuda backend runs them on a device";
  return make_ptsv_kernel_algorithm(std::move(backend));
}

namespace gpu_ptsv {

KernelInput kernel_input(const PreparedScene& scene, const std::string& variant) {
  return prepare(scene, variant_config(variant), nullptr).input;
}

}  // namespace gpu_ptsv
}  // namespace shadowcts
