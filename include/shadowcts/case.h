#pragma once
// The case model: everything an oracle or an algorithm reads. Positions are float32 world
// coordinates; oracles and algorithms all read exactly these values.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace shadowcts {

struct Mesh {
  std::string name;
  bool closed = false;  // is_closed_surface (shadowcts/closed_surface.h): exact positions
  bool caster = true;   // false: receives shadows but casts none
};

struct Triangle {
  glm::vec3 v0, v1, v2;
  std::uint32_t mesh = 0;  // index into Case::meshes
};

// The light that casts the hard or soft shadows of a case.
enum class ShadowLightKind { point, directional, sun_disk };

struct ShadowLight {
  ShadowLightKind kind = ShadowLightKind::point;
  glm::vec3 position{0.0f};  // point light
  glm::vec3 direction{
      0.0f};  // directional and sun disk: unit vector from the scene towards the light
  float angular_radius = 0.0f;  // sun disk, radians, in (0, pi/2)
};

// Ranged lights for light assignment: spheres, and spot lights (sphere intersected with a cone).
enum class RangedLightKind { sphere, spot };

struct RangedLight {
  RangedLightKind kind = RangedLightKind::sphere;
  glm::vec3 centre{0.0f};
  float range = 0.0f;
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // spot: unit axis of the cone
  float cone_half_angle = 0.0f;            // spot: radians, in (0, pi)
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vertical_fov_degrees = 60.0f;
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  std::uint32_t width = 256;
  std::uint32_t height = 256;
};

struct RunParameters {
  double eps_rel = 1.0 / 65536.0;  // ambiguity band: tau = eps_rel * largest |coordinate|
  std::uint32_t repeats = 2;       // timed repeats after a warm-up run; median and min-max reported
  std::uint32_t threads = 0;       // 0: all hardware threads
  std::uint64_t seed = 1;
};

// An engine's own result for the case's frame (`shadowcts check`, the manifest's "result"): a
// file of per-pixel values or light lists, judged like a registered algorithm's output.
enum class ExternalResultKind { none, mask, visibility, light_lists };

struct ExternalResultFile {
  ExternalResultKind kind = ExternalResultKind::none;
  std::string path;  // resolved against the manifest's folder
  // mask: the channel holds a visibility (1 lit) instead of a shadow amount (1 shadowed).
  bool mask_is_visibility = false;
  // visibility: the error the engine declares it may make (per robust sample, mean).
  double budget_per_sample = 1.0 / 256.0;
  double budget_mean = 1.0 / 1024.0;
};

struct Case {
  std::string name;    // dotted, stable: e.g. "ground_blockers.64k"
  std::string source;  // file or generator it came from, for messages
  std::vector<Mesh> meshes;
  std::vector<Triangle> triangles;
  std::optional<ShadowLight> light;
  std::vector<RangedLight> ranged_lights;
  Camera camera;
  RunParameters parameters;
  // An EXR G-buffer (see gbuffer_exr.h) to take the view samples from instead of casting
  // primary rays; empty: samples are generated with Embree.
  std::string gbuffer_path;
  // What `shadowcts check` judges; kind none for cases that only `run` algorithms.
  ExternalResultFile external_result;

  // Largest absolute coordinate of the case (triangles, camera, point light): the scale S of the
  // ambiguity band.
  double scale() const;
  // Largest absolute coordinate of the triangles alone.
  double triangle_scale() const;
};

// Throws InputError naming case.source and the element if the case is not valid: NaN/Inf,
// mesh ids out of range, no triangles, zero-length directions, impossible camera or light
// parameters. Zero-area triangles are valid (they cast no shadow).
void validate(const Case& c);

}  // namespace shadowcts
