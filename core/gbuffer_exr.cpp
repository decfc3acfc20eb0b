#include "shadowcts/gbuffer_exr.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

constexpr std::uint32_t sky_id = 0xFFFFFFFFu;
constexpr std::array<const char*, 6> float_channel_names = {"P.X", "P.Y", "P.Z",
                                                            "N.X", "N.Y", "N.Z"};
constexpr const char* id_channel_name = "id";

// One pixel as written: six FLOAT channels then one UINT channel, packed.
struct GBufferPixel {
  float values[6];
  std::uint32_t id;
};
static_assert(sizeof(GBufferPixel) == 28);

std::string pixel_element(std::uint32_t x, std::uint32_t y) {
  return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void remove_quietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace

void write_gbuffer_exr(const std::string& path, const ViewSamples& samples) {
  const std::uint64_t pixel_count =
      static_cast<std::uint64_t>(samples.width) * static_cast<std::uint64_t>(samples.height);
  if (samples.width == 0 || samples.height == 0) {
    throw InputError(path, "samples", "image size is zero");
  }
  if (samples.samples.size() != pixel_count) {
    throw InputError(path, "samples",
                     std::to_string(samples.samples.size()) + " samples for a " +
                         std::to_string(samples.width) + "x" + std::to_string(samples.height) +
                         " image");
  }
  std::vector<GBufferPixel> pixels(samples.samples.size());
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    const auto x = static_cast<std::uint32_t>(i % samples.width);
    const auto y = static_cast<std::uint32_t>(i / samples.width);
    if (s.pixel_x != x || s.pixel_y != y) {
      throw InputError(path, "samples[" + std::to_string(i) + "]",
                       "belongs to pixel (" + std::to_string(s.pixel_x) + ", " +
                           std::to_string(s.pixel_y) + ") but sits at " + pixel_element(x, y) +
                           " of the row-major order");
    }
    const bool sky = s.sample_class == SampleClass::sky;
    if (!sky && s.receiver == no_receiver) {
      throw InputError(path, pixel_element(x, y), "non-sky sample without a receiver triangle");
    }
    pixels[i] =
        GBufferPixel{{s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z},
                     sky ? sky_id : s.receiver};
  }

  // Created by format name: the temporary's ".tmp" extension names no format.
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("openexr");
  if (!out)
    throw InputError(path, "file", "OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
  if (!out->supports("channelformats")) {
    throw InputError(path, "file", "this OpenEXR writer cannot mix FLOAT and UINT channels");
  }
  OIIO::ImageSpec spec(static_cast<int>(samples.width), static_cast<int>(samples.height), 7,
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames.assign(float_channel_names.begin(), float_channel_names.end());
  spec.channelnames.emplace_back(id_channel_name);
  spec.channelformats.assign(6, OIIO::TypeDesc::FLOAT);
  spec.channelformats.emplace_back(OIIO::TypeDesc::UINT);
  spec.attribute("compression", "zip");  // lossless: the round trip is bit-exact
  spec.attribute("DateTime", "");        // no write-time stamp in capDate: same samples, same bytes

  const std::filesystem::path target(path);
  const std::filesystem::path temporary(path + ".tmp");
  if (!out->open(temporary.string(), spec)) {
    const std::string problem = out->geterror();
    remove_quietly(temporary);
    throw InputError(path, "file", "cannot be written: " + problem);
  }
  // UNKNOWN: the buffer is in the per-channel native formats of the spec.
  const bool written = out->write_image(OIIO::TypeDesc::UNKNOWN, pixels.data());
  const bool closed = out->close();
  if (!written || !closed) {
    const std::string problem = out->geterror();
    out.reset();
    remove_quietly(temporary);
    throw InputError(path, "file", "cannot be written: " + problem);
  }
  out.reset();
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    remove_quietly(temporary);
    throw InputError(path, "file", "cannot be renamed into place: " + error.message());
  }
}

ViewSamples read_gbuffer_exr(const std::string& path) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "file", "cannot be read as an image: " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  if (std::string(in->format_name()) != "openexr") {
    throw InputError(path, "file", std::string("is ") + in->format_name() + ", not OpenEXR");
  }
  if (spec.deep) throw InputError(path, "file", "deep images are not G-buffers");
  if (spec.width <= 0 || spec.height <= 0) throw InputError(path, "file", "image size is zero");
  if (spec.x != spec.full_x || spec.y != spec.full_y || spec.width != spec.full_width ||
      spec.height != spec.full_height) {
    throw InputError(path, "dataWindow",
                     "differs from the display window: one sample per pixel of "
                     "the display window is required");
  }

  auto channel_index = [&](const std::string& name) {
    for (int c = 0; c < spec.nchannels; ++c) {
      if (spec.channelnames[static_cast<std::size_t>(c)] == name) return c;
    }
    std::string present;
    for (const auto& channel : spec.channelnames) present += (present.empty() ? "" : " ") + channel;
    throw InputError(path, "channel " + name, "is missing (channels: " + present + ")");
  };
  const auto width = static_cast<std::uint32_t>(spec.width);
  const auto height = static_cast<std::uint32_t>(spec.height);
  const std::size_t pixel_count = static_cast<std::size_t>(width) * height;

  // Each channel is read alone, converted to float (exact from HALF or FLOAT) or kept as UINT.
  std::array<std::vector<float>, 6> float_channels;
  for (std::size_t k = 0; k < float_channel_names.size(); ++k) {
    const int c = channel_index(float_channel_names[k]);
    const OIIO::TypeDesc format = spec.channelformat(c);
    if (format != OIIO::TypeDesc::FLOAT && format != OIIO::TypeDesc::HALF) {
      throw InputError(path, std::string("channel ") + float_channel_names[k],
                       "must be FLOAT or HALF, is " + std::string(format.c_str()));
    }
    float_channels[k].resize(pixel_count);
    if (!in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, float_channels[k].data())) {
      throw InputError(path, std::string("channel ") + float_channel_names[k],
                       "cannot be read: " + in->geterror());
    }
  }
  const int id_channel = channel_index(id_channel_name);
  if (spec.channelformat(id_channel) != OIIO::TypeDesc::UINT) {
    // A float id would be normalized by the conversion and cannot hold 0xFFFFFFFF exactly.
    throw InputError(path, "channel id",
                     "must be UINT (32-bit unsigned), is " +
                         std::string(spec.channelformat(id_channel).c_str()));
  }
  std::vector<std::uint32_t> ids(pixel_count);
  if (!in->read_image(0, 0, id_channel, id_channel + 1, OIIO::TypeDesc::UINT, ids.data())) {
    throw InputError(path, "channel id", "cannot be read: " + in->geterror());
  }
  in->close();

  ViewSamples samples;
  samples.width = width;
  samples.height = height;
  samples.samples.resize(pixel_count);
  for (std::size_t i = 0; i < pixel_count; ++i) {
    ViewSample& s = samples.samples[i];
    s.pixel_x = static_cast<std::uint32_t>(i % width);
    s.pixel_y = static_cast<std::uint32_t>(i / width);
    if (ids[i] == sky_id) {
      // Engines write anything into sky pixels (often inf): sky samples are never compared, so
      // their geometry is zeroed rather than carried along.
      s.sample_class = SampleClass::sky;
      s.receiver = no_receiver;
      continue;
    }
    s.sample_class = SampleClass::regular;
    s.receiver = ids[i];
    s.position = glm::vec3(float_channels[0][i], float_channels[1][i], float_channels[2][i]);
    s.normal = glm::vec3(float_channels[3][i], float_channels[4][i], float_channels[5][i]);
    if (!finite(s.position)) {
      throw InputError(path, pixel_element(s.pixel_x, s.pixel_y), "position P is not finite");
    }
    if (!finite(s.normal)) {
      throw InputError(path, pixel_element(s.pixel_x, s.pixel_y), "normal N is not finite");
    }
    if (s.normal == glm::vec3(0.0f)) {
      throw InputError(path, pixel_element(s.pixel_x, s.pixel_y), "normal N has zero length");
    }
  }
  return samples;
}

}  // namespace shadowcts
