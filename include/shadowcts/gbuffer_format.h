#pragma once
// How an engine's G-buffer gives the view samples (the manifest's "gbuffer" object,
// docs/case-manifest.md): where the positions come from (world positions, or depth with the
// inverse view-projection matrix) and how the receiver triangle is named (a case triangle index,
// a (mesh, primitive) pair as visibility buffers write it, or nothing: the suite finds it).
#include <array>
#include <cstdint>

namespace shadowcts {

enum class GBufferPositions : std::uint8_t {
  world,  // channels P.X P.Y P.Z: float32 world positions
  depth,  // channel Z: depth-buffer values, reconstructed with inverse_view_projection
};

enum class GBufferReceivers : std::uint8_t {
  triangle_id,     // channel id: the triangle index in the case's load order
  mesh_primitive,  // channels mesh, primitive: the case mesh, the triangle within it
  search,          // no id channel: the suite finds the triangle the sample lies on
};

// The NDC z a depth-buffer value d stands for.
enum class NdcDepthRange : std::uint8_t {
  zero_to_one,       // z = d: D3D, Vulkan, Metal, WebGPU, OpenGL with glClipControl
  minus_one_to_one,  // z = 2 d - 1: OpenGL's default
};

struct GBufferFormat {
  GBufferPositions positions = GBufferPositions::world;
  GBufferReceivers receivers = GBufferReceivers::triangle_id;
  // Depth only. Rows of the matrix M: the world point is (M v).xyz / (M v).w for
  // v = (x_ndc, y_ndc, z_ndc, 1).
  std::array<std::array<double, 4>, 4> inverse_view_projection{};
  NdcDepthRange depth_range = NdcDepthRange::zero_to_one;
  // The depth buffer's cleared value, which marks sky where no id does: 1, or 0 with reversed Z.
  bool reversed_z = false;
  // NDC y of the file's top row: +1 (D3D, Metal, WebGPU, OpenGL images flipped to top-down) or
  // -1 (Vulkan's default viewport, OpenGL rows written as glReadPixels returns them).
  int row_0_ndc_y = 1;
};

}  // namespace shadowcts
