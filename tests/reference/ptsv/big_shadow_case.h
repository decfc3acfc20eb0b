#pragma once
// A camera looking down at a ground of two triangles, with one large caster triangle above it:
// its shadow covers whole clusters, so traversals trivially accept nodes.
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv_test {

inline Case big_shadow_case(bool directional) {
  Case c;
  c.name = "big_shadow";
  c.source = "test:big_shadow";
  c.meshes = {Mesh{"ground", false, true}, Mesh{"caster", false, true}};
  c.triangles = {
      Triangle{{-8.0f, 0.0f, -8.0f}, {8.0f, 0.0f, 8.0f}, {8.0f, 0.0f, -8.0f}, 0},
      Triangle{{-8.0f, 0.0f, -8.0f}, {-8.0f, 0.0f, 8.0f}, {8.0f, 0.0f, 8.0f}, 0},
      Triangle{{-4.0f, 3.0f, -3.5f}, {4.5f, 3.25f, -1.0f}, {-0.5f, 2.75f, 4.0f}, 1},
  };
  ShadowLight light;
  if (directional) {
    light.kind = ShadowLightKind::directional;
    light.direction = {-1.0f, 1.0f, -1.25f};
  } else {
    light.kind = ShadowLightKind::point;
    light.position = {-8.0f, 12.0f, -9.0f};
  }
  c.light = light;
  c.camera.position = {1.0f, 14.0f, 14.0f};
  c.camera.target = {1.5f, 0.0f, 2.0f};
  c.camera.width = 256;
  c.camera.height = 192;
  c.camera.near_plane = 0.5f;
  c.camera.far_plane = 50.0f;
  return c;
}

}  // namespace shadowcts::ptsv_test
