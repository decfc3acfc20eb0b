#include "shadowcts/algorithm.h"

#include <algorithm>
#include <string>

#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts {

std::optional<std::string> sample_outside_its_pixel(const Case& c, const ViewSamples& samples) {
  const CameraFrame frame = camera_frame(c.camera);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class == SampleClass::regular &&
        !in_pixel_wedge(frame, samples.width, samples.height, s.pixel_x, s.pixel_y,
                        glm::dvec3(s.position)))
      return "needs every view sample inside its own pixel's view frustum (samples cast from "
             "the camera); view sample " +
             std::to_string(i) + " lies outside that of pixel (" + std::to_string(s.pixel_x) +
             ", " + std::to_string(s.pixel_y) + ")";
  }
  return std::nullopt;
}

std::optional<std::string> Algorithm::unsupported_reason(const Case& c, const ViewSamples& samples,
                                                         const std::string& variant) const {
  const AlgorithmInfo& meta = info();
  const Capabilities& caps = meta.capabilities;
  if (std::find(meta.variants.begin(), meta.variants.end(), variant) == meta.variants.end())
    return "unknown variant '" + variant + "'";
  if (caps.output == OutputKind::light_lists) {
    if (c.ranged_lights.empty()) return "the case has no ranged lights";
  } else {
    if (!c.light) return "the case has no shadow light";
    switch (c.light->kind) {
      case ShadowLightKind::point:
        if (!caps.point_light) return "needs a directional or sun-disk light";
        break;
      case ShadowLightKind::directional:
        if (!caps.directional_light) return "does not support directional lights";
        break;
      case ShadowLightKind::sun_disk:
        if (!caps.sun_disk && caps.output == OutputKind::soft_shadow)
          return "does not support sun-disk lights";
        // A hard-shadow algorithm treats a sun disk as its centre direction only when it can do
        // directional lights; the planner decides whether hard shadows are compared at all.
        if (caps.output == OutputKind::hard_shadow && !caps.directional_light)
          return "does not support directional lights";
        break;
    }
  }
  if (caps.needs_closed_meshes)
    for (const Mesh& m : c.meshes)
      if (m.caster && !m.closed) return "needs closed caster meshes; '" + m.name + "' is open";
  if (caps.needs_samples_in_their_pixels)
    if (auto why = sample_outside_its_pixel(c, samples)) return why;
  if (caps.max_sample_triangle_pairs != 0) {
    const std::uint64_t pairs =
        std::uint64_t(samples.count(SampleClass::regular)) * std::uint64_t(c.triangles.size());
    if (pairs > caps.max_sample_triangle_pairs)
      return "too large for this algorithm: " + std::to_string(pairs) +
             " sample x triangle pairs (limit " + std::to_string(caps.max_sample_triangle_pairs) +
             ")";
  }
  return std::nullopt;
}

std::vector<std::string> Algorithm::timed_phases(const std::string&) const {
  return {};
}

SoftErrorBudget Algorithm::soft_error_budget(const std::string&) const {
  return {};
}

double Algorithm::robust_mismatch_ceiling(const std::string&) const {
  return 0.0;
}

AlgorithmOutput Algorithm::run(const Case& c, const ViewSamples& samples,
                               const std::string& variant) const {
  return run(prepare_scene(c, samples), variant);
}

}  // namespace shadowcts
