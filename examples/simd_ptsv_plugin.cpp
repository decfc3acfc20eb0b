// libexample_simd_ptsv.so: the suite's own SIMD ptsv port (simd/ptsv, Highway + oneTBB) wrapped as
// a plugin, to show that the C ABI carries a real optimized algorithm. C++ inside, only the C ABI
// (include/shadowcts/backend_abi.h) outside: a run rebuilds the case, its view samples and the
// prepared scene from the flat arrays it receives, runs the port and writes its answers into the
// caller's buffers.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowcts/backend_abi.h"
#include "shadowcts/prepared_scene.h"
#include "simd/ptsv/ptsv_algorithm.h"

namespace {

using namespace shadowcts;

const Algorithm& port() {
  static const std::unique_ptr<Algorithm> algorithm = make_simd_ptsv();
  return *algorithm;
}

void rebuild_case(const ShadowctsScene& s, Case& c, ViewSamples& samples) {
  c.name = s.case_name;
  c.source = "plugin scene";
  c.meshes.resize(s.mesh_count);
  for (std::size_t m = 0; m < s.mesh_count; ++m) {
    c.meshes[m].closed = s.mesh_closed[m] != 0;
    c.meshes[m].caster = s.mesh_casts[m] != 0;
  }
  c.triangles.resize(s.triangle_count);
  for (std::size_t t = 0; t < s.triangle_count; ++t) {
    Triangle& tri = c.triangles[t];
    tri.v0 = {s.x[0][t], s.y[0][t], s.z[0][t]};
    tri.v1 = {s.x[1][t], s.y[1][t], s.z[1][t]};
    tri.v2 = {s.x[2][t], s.y[2][t], s.z[2][t]};
    tri.mesh = s.mesh[t];
  }
  ShadowLight light;
  light.kind =
      s.light.kind == SHADOWCTS_LIGHT_POINT ? ShadowLightKind::point : ShadowLightKind::directional;
  light.position = {s.light.position[0], s.light.position[1], s.light.position[2]};
  light.direction = {s.light.direction[0], s.light.direction[1], s.light.direction[2]};
  c.light = light;
  c.camera.position = {s.camera_position[0], s.camera_position[1], s.camera_position[2]};
  c.camera.target = {s.camera_target[0], s.camera_target[1], s.camera_target[2]};
  c.camera.up = {s.camera_up[0], s.camera_up[1], s.camera_up[2]};
  c.camera.vertical_fov_degrees = s.vertical_fov_degrees;
  c.camera.near_plane = s.near_plane;
  c.camera.far_plane = s.far_plane;
  c.camera.width = s.width;
  c.camera.height = s.height;
  c.parameters.threads = s.threads;
  if (s.scale > 0) c.parameters.eps_rel = s.tau / s.scale;
  samples.width = s.width;
  samples.height = s.height;
  samples.samples.assign(std::size_t(s.width) * s.height, ViewSample{});
  for (std::size_t y = 0; y < s.height; ++y)
    for (std::size_t x = 0; x < s.width; ++x) {
      ViewSample& v = samples.samples[y * s.width + x];
      v.pixel_x = std::uint32_t(x);
      v.pixel_y = std::uint32_t(y);
    }
  for (std::size_t i = 0; i < s.sample_count; ++i) {
    ViewSample& v = samples.samples.at(s.sample_pixel[i]);
    v.position = {s.px[i], s.py[i], s.pz[i]};
    v.normal = {s.nx[i], s.ny[i], s.nz[i]};
    v.receiver = s.receiver[i];
    v.sample_class = SampleClass::regular;
  }
}

int32_t run_variant(std::size_t variant, const ShadowctsScene* s, ShadowctsOutputs* o,
                    char* message, std::size_t capacity) {
  try {
    if (s->struct_size != sizeof(ShadowctsScene) || o->struct_size != sizeof(ShadowctsOutputs) ||
        !o->shadowed)
      throw std::runtime_error("ABI structs of another size or no shadow output");
    if (s->light.kind != SHADOWCTS_LIGHT_POINT && s->light.kind != SHADOWCTS_LIGHT_DIRECTIONAL)
      throw std::runtime_error("light kind not declared");
    Case c;
    ViewSamples view_samples;
    rebuild_case(*s, c, view_samples);
    // The arrays exactly as given (prepare_scene would derive the same ones from the case).
    PreparedScene scene{c, view_samples, {}, {}, c.light, s->scale, s->tau};
    const std::size_t t = s->triangle_count, n = s->sample_count;
    CasterArrays& tris = scene.casters;
    for (int k = 0; k < 3; ++k) {
      tris.x[k].assign(s->x[k], s->x[k] + t);
      tris.y[k].assign(s->y[k], s->y[k] + t);
      tris.z[k].assign(s->z[k], s->z[k] + t);
    }
    tris.mesh.assign(s->mesh, s->mesh + t);
    tris.casts.assign(s->casts, s->casts + t);
    tris.mesh_closed.assign(s->mesh_closed, s->mesh_closed + s->mesh_count);
    tris.mesh_casts.assign(s->mesh_casts, s->mesh_casts + s->mesh_count);
    RegularSamples& regular = scene.samples;
    regular.index.assign(s->sample_pixel, s->sample_pixel + n);
    regular.px.assign(s->px, s->px + n);
    regular.py.assign(s->py, s->py + n);
    regular.pz.assign(s->pz, s->pz + n);
    regular.nx.assign(s->nx, s->nx + n);
    regular.ny.assign(s->ny, s->ny + n);
    regular.nz.assign(s->nz, s->nz + n);
    regular.receiver.assign(s->receiver, s->receiver + n);
    const AlgorithmOutput out = port().run(scene, port().info().variants.at(variant));
    for (std::size_t i = 0; i < n; ++i) o->shadowed[i] = out.shadowed.at(s->sample_pixel[i]);
    for (const auto& [name, value] : out.counters) {
      if (o->counter_count >= o->counter_capacity) break;
      ShadowctsCounter& counter = o->counters[o->counter_count++];
      std::snprintf(counter.name, sizeof counter.name, "%s", name.c_str());
      counter.value = value;
    }
    return SHADOWCTS_STATUS_OK;
  } catch (const std::exception& e) {
    std::snprintf(message, capacity, "%s", e.what());
    return SHADOWCTS_STATUS_ERROR;
  }
}

// One C function per variant: the ABI passes no variant index.
template <std::size_t K>
int32_t run_k(void*, const ShadowctsScene* s, ShadowctsOutputs* o, char* message,
              std::size_t capacity) {
  return run_variant(K, s, o, message, capacity);
}
constexpr ShadowctsRunFunction run_functions[] = {run_k<0>, run_k<1>, run_k<2>, run_k<3>,
                                                  run_k<4>, run_k<5>, run_k<6>, run_k<7>};

}  // namespace

extern "C" SHADOWCTS_BACKEND_EXPORT int32_t
shadowcts_backend_negotiate(uint32_t requested_abi_version, ShadowctsBackend* table) {
  if (requested_abi_version != SHADOWCTS_BACKEND_ABI_VERSION ||
      table->struct_size != sizeof(ShadowctsBackend))
    return SHADOWCTS_STATUS_ABI_MISMATCH;
  static std::vector<ShadowctsVariant> variants;
  if (variants.empty()) {
    const AlgorithmInfo& info = port().info();
    const Capabilities& caps = info.capabilities;
    const std::size_t count = std::min(info.variants.size(), std::size(run_functions));
    for (std::size_t k = 0; k < count; ++k) {
      ShadowctsVariant v{};
      v.name = info.variants[k].c_str();
      v.algorithm = SHADOWCTS_ALGORITHM_PTSV;
      v.output_kind = SHADOWCTS_OUTPUT_HARD;
      v.light_kinds = (caps.point_light ? SHADOWCTS_LIGHT_POINT : 0u) |
                      (caps.directional_light ? SHADOWCTS_LIGHT_DIRECTIONAL : 0u);
      v.flags = caps.needs_closed_meshes ? SHADOWCTS_VARIANT_NEEDS_CLOSED_MESHES : 0u;
      // Implicit cluster bounds are spans of pixel coordinates: samples placed anywhere else
      // (a fuzzer's) fall outside them, which the port reports as an input error.
      if (info.variants[k].starts_with("implicit"))
        v.flags |= SHADOWCTS_VARIANT_NEEDS_SAMPLES_IN_THEIR_PIXELS;
      v.max_triangles = UINT64_MAX;
      v.max_regular_samples = UINT64_MAX;
      v.max_sample_triangle_pairs =
          caps.max_sample_triangle_pairs ? caps.max_sample_triangle_pairs : UINT64_MAX;
      v.run = run_functions[k];
      variants.push_back(v);
    }
  }
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "example_simd_ptsv";
  table->version = "1.0.0";
  table->build_id = "simd/ptsv of this suite";
  table->variant_count = std::uint32_t(variants.size());
  table->variants = variants.data();
  return SHADOWCTS_STATUS_OK;
}
