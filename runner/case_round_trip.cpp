#include "case_round_trip.h"

#include <cstdio>
#include <cstring>

#include "case_gbuffer.h"
#include "shadowcts/case_manifest.h"

namespace shadowcts {
namespace {

// Bit for bit: -0 is not 0 here, since a manifest must give back the very floats it was written
// from.
template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Hexadecimal floats: the text shows every bit.
std::string exact_text(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%a, %a, %a)", double(v.x), double(v.y), double(v.z));
  return text;
}

std::string light_difference(const std::optional<ShadowLight>& a,
                             const std::optional<ShadowLight>& b) {
  if (a.has_value() != b.has_value()) return a ? "the shadow light is missing" : "a shadow light";
  if (!a) return "";
  if (a->kind != b->kind) return "the shadow light's kind";
  if (a->kind == ShadowLightKind::point) {
    if (!same_bits(a->position, b->position)) return "the point light's position";
    return "";
  }
  if (!same_bits(a->direction, b->direction)) return "the light's direction";
  if (a->kind == ShadowLightKind::sun_disk && !same_bits(a->angular_radius, b->angular_radius))
    return "the sun's angular radius";
  return "";
}

std::string ranged_light_difference(const RangedLight& a, const RangedLight& b) {
  if (a.kind != b.kind) return "kind";
  if (!same_bits(a.centre, b.centre)) return "centre";
  if (!same_bits(a.range, b.range)) return "range";
  if (a.kind == RangedLightKind::spot) {
    if (!same_bits(a.direction, b.direction)) return "direction";
    if (!same_bits(a.cone_half_angle, b.cone_half_angle)) return "cone half angle";
  }
  return "";
}

std::string sample_difference(const ViewSample& a, const ViewSample& b) {
  if (a.sample_class != b.sample_class) return "class";
  if (a.pixel_x != b.pixel_x || a.pixel_y != b.pixel_y) return "pixel";
  if (a.sample_class == SampleClass::sky) return "";
  if (!same_bits(a.position, b.position)) return "position";
  if (!same_bits(a.normal, b.normal)) return "normal";
  if (a.receiver != b.receiver) return "receiver";
  return "";
}

}  // namespace

LoadedCase load_case_with_gbuffer(const std::string& manifest) {
  LoadedCase loaded;
  GBufferFormat format;
  loaded.c = load_case_manifest(manifest, format);
  if (!loaded.c.gbuffer_path.empty())
    loaded.samples = load_case_gbuffer(loaded.c, format).samples;
  else
    loaded.samples = generate_view_samples(loaded.c);
  return loaded;
}

std::string first_difference(const Case& written, const ViewSamples& written_samples,
                             const LoadedCase& loaded) {
  const Case& c = loaded.c;
  if (c.triangles.size() != written.triangles.size())
    return "loads " + std::to_string(c.triangles.size()) + " triangles, not " +
           std::to_string(written.triangles.size());
  for (std::size_t t = 0; t < c.triangles.size(); ++t) {
    const Triangle &a = written.triangles[t], &b = c.triangles[t];
    const std::string at = "triangle " + std::to_string(t) + ": ";
    const glm::vec3 *written_vertices[] = {&a.v0, &a.v1, &a.v2},
                    *loaded_vertices[] = {&b.v0, &b.v1, &b.v2};
    for (int k = 0; k < 3; ++k)
      if (!same_bits(*written_vertices[k], *loaded_vertices[k]))
        return at + "vertex " + std::to_string(k) + " " + exact_text(*written_vertices[k]) +
               " loads as " + exact_text(*loaded_vertices[k]);
    const Mesh &m = written.meshes[a.mesh], &n = c.meshes[b.mesh];
    if (m.caster != n.caster)
      return at + (m.caster ? "its mesh casts shadows, loads as casting none"
                            : "its mesh casts no shadow, loads as a caster");
    if (m.closed != n.closed)
      return at +
             (m.closed ? "its mesh is closed, loads as open" : "its mesh is open, loads as closed");
  }
  if (const std::string d = light_difference(written.light, c.light); !d.empty()) return d;
  if (c.ranged_lights.size() != written.ranged_lights.size())
    return "loads " + std::to_string(c.ranged_lights.size()) + " ranged lights, not " +
           std::to_string(written.ranged_lights.size());
  for (std::size_t i = 0; i < c.ranged_lights.size(); ++i)
    if (const std::string d = ranged_light_difference(written.ranged_lights[i], c.ranged_lights[i]);
        !d.empty())
      return "ranged light " + std::to_string(i) + ": " + d;
  const Camera &p = written.camera, &q = c.camera;
  if (!same_bits(p.position, q.position) || !same_bits(p.target, q.target) ||
      !same_bits(p.up, q.up) || !same_bits(p.vertical_fov_degrees, q.vertical_fov_degrees) ||
      !same_bits(p.near_plane, q.near_plane) || !same_bits(p.far_plane, q.far_plane) ||
      p.width != q.width || p.height != q.height)
    return "the camera";
  const RunParameters &r = written.parameters, &s = c.parameters;
  if (r.eps_rel != s.eps_rel || r.repeats != s.repeats || r.threads != s.threads ||
      r.seed != s.seed)
    return "the parameters";
  const ViewSamples& v = loaded.samples;
  if (v.width != written_samples.width || v.height != written_samples.height)
    return "the samples' size";
  for (std::size_t i = 0; i < v.samples.size(); ++i)
    if (const std::string d = sample_difference(written_samples.samples[i], v.samples[i]);
        !d.empty())
      return "sample " + std::to_string(i) + ": " + d;
  return "";
}

}  // namespace shadowcts
