#include "gpu/lightassign/lightassign_algorithm.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "reference/lightassign/tiled_assignment.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {

LightAssignKernelInput lightassign_kernel_input(const PreparedScene& scene,
                                                const std::string& variant) {
  const Case& c = scene.source;
  const Camera& camera = c.camera;
  LightAssignKernelInput in;
  // The frame the view samples were cast in (ViewFrustum's too).
  const CameraFrame frame = camera_frame(camera);
  LightAssignFrame& f = in.frame;
  f.origin = frame.origin;
  f.forward = frame.forward;
  f.right = frame.right;
  f.up = frame.up;
  f.tan_half_fov = frame.tan_half_fov;
  f.aspect = frame.aspect;
  f.width = camera.width;
  f.height = camera.height;

  const RegularSamples& regular = scene.samples;
  in.sample_pixel = regular.index;
  in.sample_position.resize(regular.size());
  in.sample_normal.resize(regular.size());
  for (std::size_t i = 0; i < regular.size(); ++i) {
    in.sample_position[i] = regular.position(i);
    in.sample_normal[i] = regular.normal(i);
  }
  in.lights.reserve(c.ranged_lights.size());
  for (const RangedLight& l : c.ranged_lights) in.lights.push_back({l.centre, l.range});
  in.tile_size = lightassign_tile_size;

  if (variant == "tiled") {
    in.tiled = true;
    return in;
  }
  const auto settings = clustered_settings(variant);
  if (!settings) throw std::invalid_argument("lightassign: unknown variant '" + variant + "'");
  in.tile_size = settings->tile_size;
  in.normal_divisions = settings->normal_divisions;
  in.explicit_bounds = settings->explicit_bounds;
  in.explicit_normal_cones = settings->explicit_normal_cones;
  // The reference's grid for the deepest depth the kernels find; its slice_of and slice_near are
  // glibc's log and pow, which the device's are not.
  auto grid = std::make_shared<std::optional<ClusterGrid>>();
  const ClusteredSettings s = *settings;
  in.hooks.grid = [grid, &camera, s](double deepest) {
    grid->emplace(camera, s.tile_size, s.normal_divisions, deepest);
    if (auto why = (*grid)->overflow_reason()) throw std::invalid_argument("lightassign: " + *why);
    LightAssignGrid g;
    g.tiles_x = (*grid)->tiles_x();
    g.tiles_y = (*grid)->tiles_y();
    g.slices = (*grid)->slices();
    g.bits_j = (*grid)->bits_j();
    g.bits_k = (*grid)->bits_k();
    g.bits_normal = (*grid)->bits_normal();
    g.bits = (*grid)->bits();
    g.near_plane = double(camera.near_plane);
    g.log_base = std::log((*grid)->slice_base());
    return g;
  };
  in.hooks.slice_of = [grid](double depth) { return (*grid)->slice_of(depth); };
  in.hooks.slice_near = [grid](std::uint64_t k) { return (*grid)->slice_near(k); };
  return in;
}

namespace {

class LightAssignKernelAlgorithm final : public LightAssignAlgorithm {
 public:
  explicit LightAssignKernelAlgorithm(LightAssignKernelBackend backend)
      : LightAssignAlgorithm(
            backend.describe("lightassign", Capabilities{.output = OutputKind::light_lists,
                                                         .ranged_lights = true}),
            select_variants(lightassign_variants(), {"tiled", "clustered", "clustered+eb",
                                                     "clustered+en", "clustered+nk3"})),
        backend_(std::move(backend)) {}

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    if (samples.samples.size() != std::size_t(samples.width) * samples.height)
      throw std::invalid_argument("lightassign: sample count is not width x height");
    LightAssignKernelInput input = lightassign_kernel_input(scene, variant.name);
    const bool tiled = input.tiled;
    const std::uint32_t tile_size = input.tile_size;
    LightAssignKernelResult result;
    // The emulator spreads blocks over oneTBB, and Thrust's TBB system runs there too: both keep
    // to the case's thread limit, as the reference does. The kernels free each input array once
    // uploaded.
    run_with_thread_limit(c.parameters.threads,
                          [&] { result = backend_.run_kernels(std::move(input)); });

    LightLists out;
    out.offsets = std::move(result.offsets);
    out.lights = std::move(result.lights);
    out.bounds.resize(result.bounds.size());
    for (std::size_t k = 0; k < result.bounds.size(); ++k)
      out.bounds[k] = {result.bounds[k].min, result.bounds[k].max};
    out.list_of_sample = scene.per_view_sample(result.list_of_regular, LightLists::no_list);

    const std::uint64_t key_bits = tiled
                                       ? tile_key_bits((samples.width + tile_size - 1) / tile_size,
                                                       (samples.height + tile_size - 1) / tile_size)
                                       : result.key_bits;
    ListWork work;
    work.nodes_tested = result.nodes_tested;
    work.light_tests = result.light_tests;
    work.backface_culled = result.backface_culled;
    AlgorithmOutput output;
    output.counters = light_assignment_counters(out, samples, work, key_bits, result.bounds_grown);
    if (backend_.emulated) output.counters.push_back({"emulated_threads", result.emulated_threads});
    output.light_lists = std::move(out);
    output.phase_ms = {{build_phase, result.build_ms}, {query_phase, result.query_ms}};
    return output;
  }

  LightAssignKernelBackend backend_;
};

}  // namespace

std::unique_ptr<Algorithm> make_lightassign_kernel_algorithm(LightAssignKernelBackend backend) {
  return std::make_unique<LightAssignKernelAlgorithm>(std::move(backend));
}

std::unique_ptr<Algorithm> make_lightassign_cuda_emu() {
  LightAssignKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's tiled and clustered light-assignment kernels EMULATED on the host "
      "(gpu/emulator: a fiber per CUDA thread, no GPU involved); the reference's lists";
  backend.run_kernels = run_lightassign_kernels_emulated;
  backend.emulated = true;
  return make_lightassign_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
