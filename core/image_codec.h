#pragma once
// Image files through OpenImageIO, loaded on first use from the module libshadowcts_oiio.so
// (image_codec_oiio.cpp) instead of being linked: Debian's OpenImageIO pulls in 270 libraries
// (GDAL, DCMTK, OpenCV, ...) whose loading costs every process ~0.45 s before main, which each
// CTest process and every `shadowcts --help` paid although most never touch an image file.
// The interface is what the suite needs of OpenImageIO and nothing more.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace shadowcts {

enum class PixelType { uint8, uint32, half, float32, other };

struct ImageHeader {
  std::string format;  // OpenImageIO's format name: "openexr", "png", ...
  bool deep = false;
  int x = 0, y = 0, width = 0, height = 0;                      // data window
  int full_x = 0, full_y = 0, full_width = 0, full_height = 0;  // display window
  std::vector<std::string> channel_names;
  std::vector<PixelType> channel_types;
  std::vector<std::string> channel_type_names;  // OpenImageIO's names, for messages
};

// An image file opened for reading.
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // Channel `channel` of every pixel of the data window, row-major, converted to the
  // destination type (HALF and FLOAT to float exactly; UINT to uint32 as is). False on a read
  // error: error() says what.
  virtual bool read_channel(int channel, float* values) = 0;
  virtual bool read_channel(int channel, std::uint32_t* values) = 0;
  virtual std::string error() = 0;
};

struct ImageToEncode {
  std::string format;  // "png" or "openexr"
  int width = 0, height = 0;
  std::vector<std::string> channel_names;
  std::vector<PixelType> channel_types;  // in the file
  // The type of every channel of `pixels` (converted to the file's types), or nullopt: the
  // pixels are packed in the file's channel types.
  std::optional<PixelType> buffer_type;
  const void* pixels = nullptr;  // row-major, top row first, channels interleaved
};

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // nullptr and `error` set when `path` cannot be opened as an image.
  virtual std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const = 0;
  // The file's bytes; OpenEXR files are zip-compressed (lossless) and carry no write time, so
  // the same pixels give the same bytes. Empty and `error` set on failure.
  virtual std::vector<unsigned char> encode(const ImageToEncode& image,
                                            std::string& error) const = 0;
};

// The codec, loading the module on the first call (thread-safe). Throws std::runtime_error
// naming the module when it cannot be loaded.
const ImageCodec& image_codec();

}  // namespace shadowcts

// The module's one entry point (C linkage: found by name with dlsym).
extern "C" const shadowcts::ImageCodec* shadowcts_image_codec();
