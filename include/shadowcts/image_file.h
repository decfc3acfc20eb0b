#pragma once
// Images of a run, written with OpenImageIO: 8-bit PNG for people, float EXR for tools.
#include <cstdint>
#include <string>
#include <vector>

namespace shadowcts {

struct RgbImage {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
};

// Writes all or nothing (temporary file renamed into place); the format follows the extension
// (.png, .exr). Throws OutputError naming the path on failure (encoding, a full disk, ...).
void write_image(const std::string& path, const RgbImage& image);

}  // namespace shadowcts
