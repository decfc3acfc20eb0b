#include "shadowcts/gbuffer_exr.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "atomic_file.h"
#include "image_codec.h"
#include "shadowcts/case.h"
#include "shadowcts/depth_reconstruction.h"
#include "shadowcts/errors.h"
#include "shadowcts/scene_file.h"

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

  ImageToEncode encode;
  encode.format = "openexr";  // zip: lossless, the round trip is bit-exact
  encode.width = static_cast<int>(samples.width);
  encode.height = static_cast<int>(samples.height);
  encode.channel_names.assign(float_channel_names.begin(), float_channel_names.end());
  encode.channel_names.emplace_back(id_channel_name);
  encode.channel_types.assign(6, PixelType::float32);
  encode.channel_types.push_back(PixelType::uint32);
  encode.pixels = pixels.data();  // packed in the file's channel types
  std::string error;
  const std::vector<unsigned char> bytes = image_codec().encode(encode, error);
  if (bytes.empty()) throw OutputError(path, error);
  write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

namespace {

// What the first header of an OpenEXR file declares, read here because OpenEXR allocates its
// scanline buffers from the data window as soon as OIIO opens the file (a forged 30000x30000
// header made open() itself throw bad_alloc under a memory limit).
struct Resolution {
  std::int64_t width, height;
};

struct ExrWindows {
  std::int32_t data[4] = {0, 0, -1, -1};     // xmin ymin xmax ymax
  std::int32_t display[4] = {0, 0, -1, -1};  // xmin ymin xmax ymax
  std::uint64_t pixel_bytes = 0;             // per pixel, all channels
};

// nullopt when the file is not a (readable) OpenEXR file: OIIO then says what it is.
std::optional<ExrWindows> read_exr_windows(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[8] = {};
  if (!in.read(reinterpret_cast<char*>(magic), sizeof magic)) return std::nullopt;
  if (!(magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01))
    return std::nullopt;
  auto read_name = [&](std::string& name) {  // NUL-terminated, at most 255 characters
    name.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (name.size() == 255) return false;
      name.push_back(c);
    }
    return false;
  };
  auto read_i32 = [&](std::int32_t& value) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
    value = static_cast<std::int32_t>(static_cast<std::uint32_t>(b[0]) | std::uint32_t(b[1]) << 8 |
                                      std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24);
    return true;
  };
  ExrWindows windows;
  bool has_data = false, has_display = false;
  std::string name, type;
  for (int attributes = 0; attributes < 10'000; ++attributes) {
    if (!read_name(name)) return std::nullopt;
    if (name.empty()) break;  // end of the header
    std::int32_t size = 0;
    if (!read_name(type) || !read_i32(size) || size < 0) return std::nullopt;
    const auto start = in.tellg();
    if ((name == "dataWindow" || name == "displayWindow") && type == "box2i" && size == 16) {
      std::int32_t* box = name == "dataWindow" ? windows.data : windows.display;
      for (int i = 0; i < 4; ++i)
        if (!read_i32(box[i])) return std::nullopt;
      (name == "dataWindow" ? has_data : has_display) = true;
    } else if (name == "channels" && type == "chlist") {
      // name, pixel type (0 UINT, 1 HALF, 2 FLOAT), pLinear + 3 reserved, x and y sampling.
      std::string channel;
      while (read_name(channel) && !channel.empty()) {
        std::int32_t pixel_type = 0, sampling = 0;
        if (!read_i32(pixel_type)) return std::nullopt;
        in.ignore(4);
        if (!read_i32(sampling) || !read_i32(sampling)) return std::nullopt;
        windows.pixel_bytes += pixel_type == 1 ? 2 : 4;
      }
    }
    in.clear();
    in.seekg(start + std::streamoff(size));
    if (!in) return std::nullopt;
  }
  if (!has_data || !has_display) return std::nullopt;
  return windows;
}

std::string box_text(const std::int32_t box[4]) {
  return std::to_string(std::int64_t(box[2]) - box[0] + 1) + "x" +
         std::to_string(std::int64_t(box[3]) - box[1] + 1) + " at (" + std::to_string(box[0]) +
         ", " + std::to_string(box[1]) + ")";
}

// The header checks shared by both readers, all before any pixel is allocated: a 326 KB file
// declaring 30000x30000 pixels took 3.65 GB when it was sized first and compared later.
void check_declared_size(const std::string& path, std::optional<Resolution> expected) {
  const auto windows = read_exr_windows(path);
  if (!windows) return;  // OIIO reports what is wrong with it
  const std::int64_t width = std::int64_t(windows->data[2]) - windows->data[0] + 1;
  const std::int64_t height = std::int64_t(windows->data[3]) - windows->data[1] + 1;
  if (!std::equal(windows->data, windows->data + 4, windows->display)) {
    throw InputError(path, "dataWindow",
                     box_text(windows->data) + " differs from the display window " +
                         box_text(windows->display) +
                         ": one sample per pixel of the display window is required");
  }
  if (width <= 0 || height <= 0) throw InputError(path, "dataWindow", "image size is zero");
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (expected && (width != expected->width || height != expected->height)) {
    throw InputError(path, "dataWindow",
                     size + " differs from the case camera's " + std::to_string(expected->width) +
                         "x" + std::to_string(expected->height));
  }
  if (width > max_gbuffer_side || height > max_gbuffer_side) {
    throw InputError(path, "dataWindow",
                     size + " exceeds the largest camera resolution " +
                         std::to_string(max_gbuffer_side) + "x" + std::to_string(max_gbuffer_side));
  }
  // No lossless EXR compression reaches 1:4096 (zip stays near 1:1000), so a file that small
  // cannot hold the pixels it declares.
  std::error_code error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, error);
  const std::uint64_t pixel_bytes =
      std::uint64_t(width) * std::uint64_t(height) * windows->pixel_bytes;
  if (!error && pixel_bytes / 4096 > file_size) {
    throw InputError(path, "dataWindow",
                     size + " pixels need " + std::to_string(pixel_bytes) +
                         " bytes, more than the file's " + std::to_string(file_size) +
                         " bytes can hold (truncated or forged header)");
  }
}

std::unique_ptr<ImageReader> open_gbuffer(const std::string& path,
                                          std::optional<Resolution> expected = {}) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(path, "file",
                     std::filesystem::exists(path, error) ? "not a regular file" : "not found");
  }
  check_declared_size(path, expected);
  std::string problem;
  std::unique_ptr<ImageReader> in = image_codec().open(path, problem);
  if (!in) throw InputError(path, "file", "cannot be read as an image: " + problem);
  const ImageHeader& spec = in->header();
  if (spec.format != "openexr") {
    throw InputError(path, "file", "is " + spec.format + ", not OpenEXR");
  }
  if (spec.deep) throw InputError(path, "file", "deep images are not G-buffers");
  if (spec.width <= 0 || spec.height <= 0) throw InputError(path, "file", "image size is zero");
  const std::string size = std::to_string(spec.width) + "x" + std::to_string(spec.height);
  if (spec.x != spec.full_x || spec.y != spec.full_y || spec.width != spec.full_width ||
      spec.height != spec.full_height) {
    throw InputError(path, "dataWindow",
                     size + " at (" + std::to_string(spec.x) + ", " + std::to_string(spec.y) +
                         ") differs from the display window " + std::to_string(spec.full_width) +
                         "x" + std::to_string(spec.full_height) + " at (" +
                         std::to_string(spec.full_x) + ", " + std::to_string(spec.full_y) +
                         "): one sample per pixel of the display window is required");
  }
  if (spec.width > static_cast<int>(max_gbuffer_side) ||
      spec.height > static_cast<int>(max_gbuffer_side)) {
    throw InputError(path, "dataWindow",
                     size + " exceeds the largest camera resolution " +
                         std::to_string(max_gbuffer_side) + "x" + std::to_string(max_gbuffer_side));
  }
  return in;
}

void check_resolution(const std::string& path, const ImageHeader& spec, std::uint32_t width,
                      std::uint32_t height) {
  if (static_cast<std::uint32_t>(spec.width) != width ||
      static_cast<std::uint32_t>(spec.height) != height) {
    throw InputError(path, "dataWindow",
                     std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                         " differs from the case camera's " + std::to_string(width) + "x" +
                         std::to_string(height));
  }
}

ViewSamples read_pixels(const std::string& path, ImageReader& input, const GBufferFormat& format,
                        const Case* c);

}  // namespace

void check_gbuffer_exr_header(const std::string& path, std::uint32_t width, std::uint32_t height) {
  const std::unique_ptr<ImageReader> in = open_gbuffer(path, Resolution{width, height});
  check_resolution(path, in->header(), width, height);
}

ViewSamples read_gbuffer_exr(const std::string& path) {
  const std::unique_ptr<ImageReader> in = open_gbuffer(path);
  return read_pixels(path, *in, GBufferFormat{}, nullptr);
}

ViewSamples read_gbuffer_exr(const std::string& path, std::uint32_t width, std::uint32_t height) {
  const std::unique_ptr<ImageReader> in = open_gbuffer(path, Resolution{width, height});
  check_resolution(path, in->header(), width, height);
  return read_pixels(path, *in, GBufferFormat{}, nullptr);
}

ViewSamples read_gbuffer_exr(const std::string& path, const GBufferFormat& format, const Case& c) {
  const std::unique_ptr<ImageReader> in =
      open_gbuffer(path, Resolution{c.camera.width, c.camera.height});
  check_resolution(path, in->header(), c.camera.width, c.camera.height);
  return read_pixels(path, *in, format, &c);
}

namespace {

// One-channel reads: float channels converted to float (exact from HALF or FLOAT), ids kept UINT.
class ChannelReader {
 public:
  ChannelReader(const std::string& path, ImageReader& in) : path_(path), in_(in) {}

  int index(const std::string& name) const {
    const std::vector<std::string>& names = in_.header().channel_names;
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c] == name) return static_cast<int>(c);
    std::string present;
    for (const auto& channel : names) present += (present.empty() ? "" : " ") + channel;
    throw InputError(path_, "channel " + name, "is missing (channels: " + present + ")");
  }

  std::vector<float> floats(const std::string& name) const {
    const int c = index(name);
    const PixelType type = in_.header().channel_types[std::size_t(c)];
    if (type != PixelType::float32 && type != PixelType::half) {
      throw InputError(path_, "channel " + name, "must be FLOAT or HALF, is " + type_name(c));
    }
    std::vector<float> values(pixel_count());
    if (!in_.read_channel(c, values.data()))
      throw InputError(path_, "channel " + name, "cannot be read: " + in_.error());
    return values;
  }

  std::vector<std::uint32_t> uints(const std::string& name) const {
    const int c = index(name);
    if (in_.header().channel_types[std::size_t(c)] != PixelType::uint32) {
      // A float id would be normalized by the conversion and cannot hold 0xFFFFFFFF exactly.
      throw InputError(path_, "channel " + name,
                       "must be UINT (32-bit unsigned), is " + type_name(c));
    }
    std::vector<std::uint32_t> values(pixel_count());
    if (!in_.read_channel(c, values.data()))
      throw InputError(path_, "channel " + name, "cannot be read: " + in_.error());
    return values;
  }

 private:
  std::size_t pixel_count() const {
    return static_cast<std::size_t>(in_.header().width) * std::size_t(in_.header().height);
  }
  std::string type_name(int c) const { return in_.header().channel_type_names[std::size_t(c)]; }
  const std::string& path_;
  ImageReader& in_;
};

std::string channel_pixel(const char* channel, std::uint32_t x, std::uint32_t y) {
  return std::string("channel ") + channel + ", " + pixel_element(x, y);
}

// Per case mesh, its triangles in load order: (mesh, primitive) -> case triangle index.
std::vector<std::vector<std::uint32_t>> triangles_by_mesh(const Case& c) {
  std::vector<std::vector<std::uint32_t>> by_mesh(c.meshes.size());
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    if (c.triangles[t].mesh < by_mesh.size())
      by_mesh[c.triangles[t].mesh].push_back(static_cast<std::uint32_t>(t));
  return by_mesh;
}

// `c` is needed for (mesh, primitive) ids only.
ViewSamples read_pixels(const std::string& path, ImageReader& input, const GBufferFormat& format,
                        const Case* c) try {
  const ChannelReader read(path, input);
  const ImageHeader spec = input.header();
  const auto width = static_cast<std::uint32_t>(spec.width);
  const auto height = static_cast<std::uint32_t>(spec.height);
  const std::size_t pixel_count = static_cast<std::size_t>(width) * height;

  const bool from_depth = format.positions == GBufferPositions::depth;
  std::array<std::vector<float>, 3> position_channels;
  if (from_depth) {
    position_channels[0] = read.floats("Z");
  } else {
    for (std::size_t k = 0; k < 3; ++k) position_channels[k] = read.floats(float_channel_names[k]);
  }
  std::array<std::vector<float>, 3> normal_channels;
  for (std::size_t k = 0; k < 3; ++k) normal_channels[k] = read.floats(float_channel_names[3 + k]);
  std::vector<std::uint32_t> ids, primitives;
  if (format.receivers == GBufferReceivers::triangle_id) ids = read.uints(id_channel_name);
  if (format.receivers == GBufferReceivers::mesh_primitive) {
    ids = read.uints("mesh");
    primitives = read.uints("primitive");
  }

  std::vector<std::vector<std::uint32_t>> mesh_triangles;
  if (format.receivers == GBufferReceivers::mesh_primitive) mesh_triangles = triangles_by_mesh(*c);
  const float cleared_depth = format.reversed_z ? 0.0f : 1.0f;

  ViewSamples samples;
  samples.width = width;
  samples.height = height;
  samples.samples.resize(pixel_count);
  for (std::size_t i = 0; i < pixel_count; ++i) {
    ViewSample& s = samples.samples[i];
    s.pixel_x = static_cast<std::uint32_t>(i % width);
    s.pixel_y = static_cast<std::uint32_t>(i / width);
    // Engines write anything into sky pixels (often inf): sky samples are never compared, so
    // their geometry is zeroed rather than carried along.
    bool sky = false;
    if (!ids.empty()) {
      sky = ids[i] == sky_id;
    } else if (from_depth) {
      sky = position_channels[0][i] == cleared_depth;
    } else {
      for (std::size_t k = 0; k < 3; ++k) sky = sky || std::isinf(position_channels[k][i]);
    }
    if (sky) {
      s.sample_class = SampleClass::sky;
      s.receiver = no_receiver;
      continue;
    }
    s.sample_class = SampleClass::regular;
    if (from_depth) {
      const float depth = position_channels[0][i];
      if (std::isnan(depth))
        throw InputError(path, channel_pixel("Z", s.pixel_x, s.pixel_y), "is NaN");
      if (!(depth >= 0.0f && depth <= 1.0f))
        throw InputError(path, channel_pixel("Z", s.pixel_x, s.pixel_y),
                         "depth " + std::to_string(depth) + " is outside [0, 1]");
      const auto p = world_from_depth(format, s.pixel_x, s.pixel_y, width, height, depth);
      // The one rounding to float32: these are the positions every oracle and algorithm reads.
      if (p) s.position = glm::vec3(*p);
      if (!p || !finite(s.position) ||
          std::max({std::fabs(p->x), std::fabs(p->y), std::fabs(p->z)}) > max_scene_coordinate)
        throw InputError(path, channel_pixel("Z", s.pixel_x, s.pixel_y),
                         "depth " + std::to_string(depth) +
                             " reconstructs no finite point within 1e30 with "
                             "inverse_view_projection (w = 0 or overflow; check the matrix and "
                             "depth_range)");
    } else {
      s.position =
          glm::vec3(position_channels[0][i], position_channels[1][i], position_channels[2][i]);
      if (!finite(s.position)) {
        throw InputError(path, "channels P.X P.Y P.Z, " + pixel_element(s.pixel_x, s.pixel_y),
                         "position P is not finite");
      }
    }
    s.normal = glm::vec3(normal_channels[0][i], normal_channels[1][i], normal_channels[2][i]);
    if (!finite(s.normal)) {
      throw InputError(path, "channels N.X N.Y N.Z, " + pixel_element(s.pixel_x, s.pixel_y),
                       "normal N is not finite");
    }
    if (s.normal == glm::vec3(0.0f)) {
      throw InputError(path, "channels N.X N.Y N.Z, " + pixel_element(s.pixel_x, s.pixel_y),
                       "normal N has zero length");
    }
    switch (format.receivers) {
      case GBufferReceivers::triangle_id:
        s.receiver = ids[i];  // its range is checked against the case by classify_samples()
        break;
      case GBufferReceivers::mesh_primitive: {
        if (ids[i] >= mesh_triangles.size())
          throw InputError(path, channel_pixel("mesh", s.pixel_x, s.pixel_y),
                           "mesh " + std::to_string(ids[i]) + " is out of range (the case has " +
                               std::to_string(mesh_triangles.size()) + " meshes)");
        const std::vector<std::uint32_t>& triangles = mesh_triangles[ids[i]];
        if (primitives[i] >= triangles.size())
          throw InputError(path, channel_pixel("primitive", s.pixel_x, s.pixel_y),
                           "primitive " + std::to_string(primitives[i]) +
                               " is out of range (mesh " + std::to_string(ids[i]) + " '" +
                               c->meshes[ids[i]].name + "' has " +
                               std::to_string(triangles.size()) + " triangles)");
        s.receiver = triangles[primitives[i]];
        break;
      }
      case GBufferReceivers::search:
        s.receiver = no_receiver;  // found by the suite
        break;
    }
  }
  return samples;
} catch (const std::bad_alloc&) {
  // Within the header limits but beyond this machine's memory: still this file's problem.
  throw InputError(path, "file",
                   "not enough memory for " + std::to_string(input.header().width) + "x" +
                       std::to_string(input.header().height) + " pixels");
}

}  // namespace

}  // namespace shadowcts
