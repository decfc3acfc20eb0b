#include "shadowcts/image_file.h"

#include <filesystem>
#include <string_view>

#include "atomic_file.h"
#include "image_codec.h"
#include "shadowcts/errors.h"

namespace shadowcts {

void write_image(const std::string& path, const RgbImage& image) {
  const std::filesystem::path target(path);
  const bool exr = target.extension() == ".exr";
  // Encoded into memory, the bytes go through the one checked file writer: OpenImageIO's PNG
  // writer does not report a failed write (a full disk gave zero-byte PNGs).
  ImageToEncode encode;
  encode.format = exr ? "openexr" : target.extension() == ".png" ? "png" : "";
  if (encode.format.empty()) throw OutputError(path, "no image format for this extension");
  encode.width = static_cast<int>(image.width);
  encode.height = static_cast<int>(image.height);
  encode.channel_names = {"R", "G", "B"};
  encode.channel_types.assign(3, exr ? PixelType::half : PixelType::uint8);
  // UINT8 pixels are converted to the file's type (0..255 -> 0..1 in EXR).
  encode.buffer_type = PixelType::uint8;
  encode.pixels = image.rgb.data();
  std::string error;
  const std::vector<unsigned char> bytes = image_codec().encode(encode, error);
  if (bytes.empty()) throw OutputError(path, error);
  write_file_atomically(
      target, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace shadowcts
