// The image codec on OpenImageIO, built as the module libshadowcts_oiio.so (image_codec.h).
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image_codec.h"

namespace shadowcts {
namespace {

PixelType pixel_type(OIIO::TypeDesc type) {
  if (type == OIIO::TypeDesc::UINT8) return PixelType::uint8;
  if (type == OIIO::TypeDesc::UINT) return PixelType::uint32;
  if (type == OIIO::TypeDesc::HALF) return PixelType::half;
  if (type == OIIO::TypeDesc::FLOAT) return PixelType::float32;
  return PixelType::other;
}

OIIO::TypeDesc type_desc(PixelType type) {
  switch (type) {
    case PixelType::uint8:
      return OIIO::TypeDesc::UINT8;
    case PixelType::uint32:
      return OIIO::TypeDesc::UINT;
    case PixelType::half:
      return OIIO::TypeDesc::HALF;
    case PixelType::float32:
      return OIIO::TypeDesc::FLOAT;
    case PixelType::other:
      break;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

class OiioReader final : public ImageReader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)) {
    const OIIO::ImageSpec& spec = in_->spec();
    header_.format = in_->format_name();
    header_.deep = spec.deep;
    header_.x = spec.x;
    header_.y = spec.y;
    header_.width = spec.width;
    header_.height = spec.height;
    header_.full_x = spec.full_x;
    header_.full_y = spec.full_y;
    header_.full_width = spec.full_width;
    header_.full_height = spec.full_height;
    for (int c = 0; c < spec.nchannels; ++c) {
      header_.channel_names.push_back(spec.channel_name(c));
      header_.channel_types.push_back(pixel_type(spec.channelformat(c)));
      header_.channel_type_names.emplace_back(spec.channelformat(c).c_str());
    }
  }

  const ImageHeader& header() const override { return header_; }
  bool read_channel(int channel, float* values) override {
    return in_->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::FLOAT, values);
  }
  bool read_channel(int channel, std::uint32_t* values) override {
    return in_->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::UINT, values);
  }
  std::string error() override { return in_->geterror(); }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageHeader header_;
};

class OiioCodec final : public ImageCodec {
 public:
  std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const override {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in));
  }

  std::vector<unsigned char> encode(const ImageToEncode& image, std::string& error) const override {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(image.format);
    if (!out) {
      error = "no " + image.format + " writer: " + OIIO::geterror();
      return {};
    }
    if (!out->supports("ioproxy")) {
      error = "the " + image.format + " writer cannot encode into memory";
      return {};
    }
    const auto channels = static_cast<int>(image.channel_types.size());
    bool mixed = false;
    for (PixelType type : image.channel_types) mixed = mixed || type != image.channel_types[0];
    if (mixed && !out->supports("channelformats")) {
      error = "the " + image.format + " writer cannot mix channel types";
      return {};
    }
    OIIO::ImageSpec spec(image.width, image.height, channels, type_desc(image.channel_types[0]));
    spec.channelnames = image.channel_names;
    if (mixed)
      for (PixelType type : image.channel_types) spec.channelformats.push_back(type_desc(type));
    if (image.format == "openexr") {
      spec.attribute("compression", "zip");
      // An empty DateTime keeps OpenEXR from stamping the write time into capDate.
      spec.attribute("DateTime", "");
    }
    // UNKNOWN: the buffer is in the per-channel types of the spec.
    const OIIO::TypeDesc buffer =
        image.buffer_type ? type_desc(*image.buffer_type) : OIIO::TypeDesc::UNKNOWN;
    // The name is nominal: the bytes go to `memory`.
    if (!out->set_ioproxy(&memory) || !out->open("memory." + image.format, spec) ||
        !out->write_image(buffer, image.pixels) || !out->close() || out->has_error()) {
      error = "cannot encode the image: " + out->geterror();
      return {};
    }
    if (bytes.empty()) error = "the " + image.format + " writer produced no bytes";
    return bytes;
  }
};

}  // namespace
}  // namespace shadowcts

extern "C" __attribute__((visibility("default"))) const shadowcts::ImageCodec*
shadowcts_image_codec() {
  static const shadowcts::OiioCodec codec;
  return &codec;
}
