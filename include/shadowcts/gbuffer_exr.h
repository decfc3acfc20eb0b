#pragma once
// EXR G-buffers, so users can bring the G-buffer of their own engine: world position (P.X P.Y
// P.Z, float), geometric normal (N.X N.Y N.Z, float), receiver triangle id ("id", uint32;
// 0xFFFFFFFF marks sky).
#include <cstdint>
#include <string>

#include "shadowcts/view_samples.h"

namespace shadowcts {

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

// Reads only the header: InputError unless read_gbuffer_exr(path, width, height) would pass its
// header checks. Manifests call it so that a wrong G-buffer fails before any output is written.
void check_gbuffer_exr_header(const std::string& path, std::uint32_t width, std::uint32_t height);

inline constexpr std::uint32_t max_gbuffer_side = 16384;

}  // namespace shadowcts
