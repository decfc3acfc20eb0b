#pragma once
// EXR G-buffers, so users can bring the G-buffer of their own engine. The suite writes world
// position (P.X P.Y P.Z, float), geometric normal (N.X N.Y N.Z, float), receiver triangle id
// ("id", uint32; 0xFFFFFFFF marks sky); it reads that, and the layouts engines write
// (gbuffer_format.h: depth with the inverse view-projection, (mesh, primitive) ids, no ids).
#include <cstdint>
#include <string>

#include "shadowcts/gbuffer_format.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct Case;

// Writes all or nothing: a temporary file renamed into place. Throws InputError on failure.
void write_gbuffer_exr(const std::string& path, const ViewSamples& samples);

// Reads a G-buffer; classes are sky (id 0xFFFFFFFF) or regular until classify_samples() runs.
// Throws InputError naming the file and the channel/pixel on malformed input (missing channels,
// NaN/Inf positions of non-sky pixels).
// Header limits, checked before any pixel is allocated: the data window equals the display
// window, no side exceeds max_gbuffer_side (the largest camera validate() accepts), and the
// file is large enough to hold the pixels it declares.
ViewSamples read_gbuffer_exr(const std::string& path);

// The same, and the resolution must be width x height (the case camera's), else InputError.
ViewSamples read_gbuffer_exr(const std::string& path, std::uint32_t width, std::uint32_t height);

// Reads an engine's G-buffer laid out as `format` says (gbuffer_format.h), against case c: its
// camera's size, and its meshes and triangles for (mesh, primitive) ids. Positions from depth are
// reconstructed in double and rounded to float32 once (depth_reconstruction.h). Receivers by id
// become case triangle indices; with GBufferReceivers::search every non-sky sample is left
// regular with receiver no_receiver, for the suite's search (oracles/receiver_search.h). Throws
// InputError naming the file, the channel and the pixel: a missing channel, a wrong size or
// channel type, NaN, a depth outside [0, 1] or one that reconstructs no finite point, a mesh or
// primitive id out of range. Sky: the id (0xFFFFFFFF in id or mesh) when there is one; without
// ids the depth buffer's cleared value, or an infinite P.
ViewSamples read_gbuffer_exr(const std::string& path, const GBufferFormat& format, const Case& c);

// Reads only the header: InputError unless read_gbuffer_exr(path, width, height) would pass its
// header checks. Manifests call it so that a wrong G-buffer fails before any output is written.
void check_gbuffer_exr_header(const std::string& path, std::uint32_t width, std::uint32_t height);

inline constexpr std::uint32_t max_gbuffer_side = 16384;

}  // namespace shadowcts
