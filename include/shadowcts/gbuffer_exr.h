#pragma once
// EXR G-buffers, so users can bring the G-buffer of their own engine: world position (P.X P.Y
// P.Z, float), geometric normal (N.X N.Y N.Z, float), receiver triangle id ("id", uint32;
// 0xFFFFFFFF marks sky).
#include <string>

#include "shadowcts/view_samples.h"

namespace shadowcts {

// Writes all or nothing: a temporary file renamed into place. Throws InputError on failure.
void write_gbuffer_exr(const std::string& path, const ViewSamples& samples);

// Reads a G-buffer; classes are sky (id 0xFFFFFFFF) or regular until classify_samples() runs.
// Throws InputError naming the file and the channel/pixel on malformed input (missing channels,
// NaN/Inf positions of non-sky pixels).
ViewSamples read_gbuffer_exr(const std::string& path);

}  // namespace shadowcts
