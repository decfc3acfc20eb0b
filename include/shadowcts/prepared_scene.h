#pragma once
// The prepared scene: one per case, built once by the runner and read by every algorithm and
// backend. Its arrays are what a CUDA kernel uploads, what a Highway loop loads and what the C
// plugin ABI hands to a user's port: structure of arrays, float32 exactly as in the case.
#include <cstdint>
#include <optional>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Every triangle of the case, in Case::triangles order (receiver ids index it), as structure of
// arrays: corner k of triangle t is (x[k][t], y[k][t], z[k][t]).
struct CasterArrays {
  std::vector<float> x[3], y[3], z[3];
  std::vector<std::uint32_t> mesh;  // per triangle: index into the mesh arrays
  // Per triangle: 1 when it may shadow (its mesh casts and its area is not exactly zero). An
  // algorithm may skip the others; the oracles never count them.
  std::vector<std::uint8_t> casts;
  // Per mesh.
  std::vector<std::uint8_t> mesh_closed;  // closed surface, as the case's loader proved it
  std::vector<std::uint8_t> mesh_casts;

  std::size_t size() const { return mesh.size(); }
  glm::vec3 corner(std::size_t t, int k) const { return {x[k][t], y[k][t], z[k][t]}; }
};

// The regular samples (SampleClass::regular) only, compacted, in pixel order.
struct RegularSamples {
  std::vector<std::uint32_t> index;     // into ViewSamples::samples (= pixel_y * width + pixel_x)
  std::vector<float> px, py, pz;        // position
  std::vector<float> nx, ny, nz;        // geometric normal, unit, facing the camera
  std::vector<std::uint32_t> receiver;  // into CasterArrays, or no_receiver

  std::size_t size() const { return index.size(); }
  glm::vec3 position(std::size_t i) const { return {px[i], py[i], pz[i]}; }
  glm::vec3 normal(std::size_t i) const { return {nx[i], ny[i], nz[i]}; }
};

struct PreparedScene {
  const Case& source;               // camera, ranged lights, parameters, names for messages
  const ViewSamples& view_samples;  // every pixel, for outputs indexed by view sample
  CasterArrays casters;
  RegularSamples samples;
  std::optional<ShadowLight> light;  // the case's shadow light
  double scale = 0.0;                // S: the largest absolute coordinate of the case
  double tau = 0.0;                  // eps_rel * S

  // Spreads one value per regular sample over every view sample (`fill` elsewhere), the shape
  // of AlgorithmOutput's per-sample vectors.
  template <class T>
  std::vector<T> per_view_sample(const std::vector<T>& per_regular, T fill) const {
    std::vector<T> out(view_samples.samples.size(), fill);
    for (std::size_t i = 0; i < samples.index.size(); ++i) out[samples.index[i]] = per_regular[i];
    return out;
  }
};

// Builds the prepared scene of a validated case and its classified samples. Parallel and
// deterministic. The result refers to `c` and `view_samples`: they must outlive it.
PreparedScene prepare_scene(const Case& c, const ViewSamples& view_samples);

}  // namespace shadowcts
