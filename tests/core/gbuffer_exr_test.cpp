// EXR G-buffers: bit-exact round trip, named errors for missing channels and non-finite pixels,
// all-or-nothing writes.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "memory_limited_child.h"
#include "shadowcts/errors.h"
#include "shadowcts/gbuffer_exr.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / (std::string("shadowcts_gbuffer_") + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// 4x3 samples with awkward floats (negative zero, subnormal, huge) and two sky pixels.
ViewSamples awkward_samples() {
  ViewSamples s;
  s.width = 4;
  s.height = 3;
  for (std::uint32_t y = 0; y < s.height; ++y) {
    for (std::uint32_t x = 0; x < s.width; ++x) {
      ViewSample sample;
      sample.pixel_x = x;
      sample.pixel_y = y;
      const auto i = y * s.width + x;
      if (i == 1 || i == 10) {
        sample.sample_class = SampleClass::sky;
        s.samples.push_back(sample);
        continue;
      }
      sample.sample_class = SampleClass::regular;
      sample.receiver = i == 5 ? 0xFFFFFFFEu : i * 1000003u;
      sample.position = glm::vec3(-0.0f, std::numeric_limits<float>::denorm_min() * float(i + 1),
                                  3.4e38f / float(i + 1));
      sample.normal = glm::vec3(0.1f * float(i), -1.0f / 3.0f, 0.7071067811865476f);
      s.samples.push_back(sample);
    }
  }
  return s;
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
         std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y) &&
         std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z);
}

std::string read_error(const fs::path& path) {
  try {
    read_gbuffer_exr(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was read without InputError";
  return "";
}

// Writes an EXR with the given FLOAT channels (value = channel index + pixel index) and, when
// with_id, a UINT "id" channel of zeros, in the order given.
void write_custom_exr(const fs::path& path, const std::vector<std::string>& float_channels,
                      bool id_first, bool with_id) {
  const int width = 2, height = 2;
  OIIO::ImageSpec spec(width, height, 0, OIIO::TypeDesc::FLOAT);
  std::vector<std::string> names;
  if (with_id && id_first) names.push_back("id");
  names.insert(names.end(), float_channels.begin(), float_channels.end());
  if (with_id && !id_first) names.push_back("id");
  spec.nchannels = static_cast<int>(names.size());
  spec.channelnames = names;
  for (const auto& name : names) {
    spec.channelformats.push_back(name == "id" ? OIIO::TypeDesc::UINT : OIIO::TypeDesc::FLOAT);
  }
  std::vector<std::uint32_t> data;  // 4-byte channels: floats stored by their bits
  for (int p = 0; p < width * height; ++p) {
    for (std::size_t c = 0; c < names.size(); ++c) {
      data.push_back(names[c] == "id" ? 7u
                                      : std::bit_cast<std::uint32_t>(float(c) + float(p) + 1.0f));
    }
  }
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UNKNOWN, data.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

TEST(GBufferExr, RoundTripIsBitExact) {
  const TempDir dir;
  const fs::path file = dir.path() / "gbuffer.exr";
  const ViewSamples written = awkward_samples();
  write_gbuffer_exr(file.string(), written);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  const ViewSamples read = read_gbuffer_exr(file.string());
  ASSERT_EQ(read.width, written.width);
  ASSERT_EQ(read.height, written.height);
  ASSERT_EQ(read.samples.size(), written.samples.size());
  for (std::size_t i = 0; i < read.samples.size(); ++i) {
    const ViewSample& a = written.samples[i];
    const ViewSample& b = read.samples[i];
    EXPECT_EQ(b.sample_class, a.sample_class) << i;
    EXPECT_EQ(b.receiver, a.receiver) << i;
    EXPECT_EQ(b.pixel_x, a.pixel_x) << i;
    EXPECT_EQ(b.pixel_y, a.pixel_y) << i;
    EXPECT_TRUE(same_bits(b.position, a.position)) << i;
    EXPECT_TRUE(same_bits(b.normal, a.normal)) << i;
  }
  EXPECT_EQ(read.count(SampleClass::sky), 2u);
}

TEST(GBufferExr, ChannelsAreFoundByNameInAnyOrder) {
  const TempDir dir;
  const fs::path file = dir.path() / "reordered.exr";
  write_custom_exr(file, {"N.Z", "P.Y", "N.X", "P.X", "N.Y", "P.Z"}, true, true);
  const ViewSamples read = read_gbuffer_exr(file.string());
  ASSERT_EQ(read.samples.size(), 4u);
  const ViewSample& s = read.samples[3];  // pixel 3: value = channel index (id is 0) + 3 + 1
  EXPECT_EQ(s.receiver, 7u);
  EXPECT_EQ(s.position, glm::vec3(4 + 4, 4 + 2, 4 + 6));
  EXPECT_EQ(s.normal, glm::vec3(4 + 3, 4 + 5, 4 + 1));
}

TEST(GBufferExr, MissingChannelIsAnInputError) {
  const TempDir dir;
  const fs::path no_id = dir.path() / "no_id.exr";
  write_custom_exr(no_id, {"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z"}, false, false);
  const std::string message = read_error(no_id);
  EXPECT_NE(message.find(no_id.string() + ": channel id: is missing"), std::string::npos)
      << message;
  const fs::path no_normal = dir.path() / "no_normal.exr";
  write_custom_exr(no_normal, {"P.X", "P.Y", "P.Z", "N.X", "N.Y"}, false, true);
  const std::string normal_message = read_error(no_normal);
  EXPECT_NE(normal_message.find("channel N.Z: is missing"), std::string::npos) << normal_message;
}

TEST(GBufferExr, NonFinitePositionNamesThePixel) {
  const TempDir dir;
  const fs::path file = dir.path() / "nan.exr";
  ViewSamples samples = awkward_samples();
  samples.samples[2 * 4 + 1].position.y = std::numeric_limits<float>::quiet_NaN();
  write_gbuffer_exr(file.string(), samples);
  const std::string message = read_error(file);
  EXPECT_NE(message.find(file.string() +
                         ": channels P.X P.Y P.Z, pixel (1, 2): position P is not finite"),
            std::string::npos)
      << message;
}

TEST(GBufferExr, NonFiniteSkyPixelsAreAccepted) {
  const TempDir dir;
  const fs::path file = dir.path() / "sky.exr";
  ViewSamples samples = awkward_samples();
  samples.samples[1].position = glm::vec3(std::numeric_limits<float>::infinity());
  write_gbuffer_exr(file.string(), samples);
  const ViewSamples read = read_gbuffer_exr(file.string());
  EXPECT_EQ(read.samples[1].sample_class, SampleClass::sky);
  EXPECT_EQ(read.samples[1].position, glm::vec3(0.0f));
}

TEST(GBufferExr, ZeroNormalNamesThePixel) {
  const TempDir dir;
  const fs::path file = dir.path() / "zero_normal.exr";
  ViewSamples samples = awkward_samples();
  samples.samples[4].normal = glm::vec3(0.0f);
  write_gbuffer_exr(file.string(), samples);
  const std::string message = read_error(file);
  EXPECT_NE(message.find("pixel (0, 1): normal N has zero length"), std::string::npos) << message;
}

TEST(GBufferExr, WriteIsAllOrNothing) {
  const TempDir dir;
  const fs::path missing_folder = dir.path() / "no_such_folder" / "gbuffer.exr";
  EXPECT_THROW(write_gbuffer_exr(missing_folder.string(), awkward_samples()), OutputError);
  EXPECT_FALSE(fs::exists(missing_folder));
  EXPECT_FALSE(fs::exists(missing_folder.string() + ".tmp"));

  // A failed write leaves an existing file untouched; a good one replaces it whole.
  const fs::path file = dir.path() / "gbuffer.exr";
  write_gbuffer_exr(file.string(), awkward_samples());
  ViewSamples inconsistent = awkward_samples();
  inconsistent.samples.pop_back();
  EXPECT_THROW(write_gbuffer_exr(file.string(), inconsistent), InputError);
  EXPECT_EQ(read_gbuffer_exr(file.string()).samples.size(), 12u);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  std::size_t entries = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    (void)entry;
    ++entries;
  }
  EXPECT_EQ(entries, 1u);
}

TEST(GBufferExr, NotAnExrIsAnInputError) {
  const TempDir dir;
  const fs::path file = dir.path() / "text.exr";
  { std::ofstream(file) << "not an image"; }
  const std::string message = read_error(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
}

// ---- hostile headers (issue 14): sizes are checked before any pixel is allocated

// An all-sky width x height G-buffer.
ViewSamples sky_samples(std::uint32_t width, std::uint32_t height) {
  ViewSamples s;
  s.width = width;
  s.height = height;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      ViewSample sample;
      sample.pixel_x = x;
      sample.pixel_y = y;
      sample.sample_class = SampleClass::sky;
      s.samples.push_back(sample);
    }
  }
  return s;
}

// Rewrites the box2i attribute `name` of an EXR file to (0, 0) - (width - 1, height - 1).
void patch_window(const fs::path& file, const std::string& name, std::int32_t width,
                  std::int32_t height) {
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string key = name + std::string("\0box2i\0", 7);
  const auto at = bytes.find(key);
  ASSERT_NE(at, std::string::npos) << name;
  const std::int32_t box[4] = {0, 0, width - 1, height - 1};
  std::memcpy(bytes.data() + at + key.size() + 4, box, sizeof box);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// Zeros appended up to `size` bytes: room for the longer chunk offset table a forged header
// implies, so that OpenEXR opens the file (the reported one had 326 KB).
void pad_to(const fs::path& file, std::size_t size) {
  const auto current = static_cast<std::size_t>(fs::file_size(file));
  if (current < size)
    std::ofstream(file, std::ios::binary | std::ios::app) << std::string(size - current, '\0');
}

fs::path forged_gbuffer(const TempDir& dir, const std::string& name, std::int32_t width,
                        std::int32_t height) {
  const fs::path file = dir.path() / name;
  write_gbuffer_exr(file.string(), sky_samples(64, 48));
  patch_window(file, "dataWindow", width, height);
  patch_window(file, "displayWindow", width, height);
  pad_to(file, 326 * 1024);
  return file;
}

TEST(GBufferExrHostile, ForgedHugeDataWindowIsRefusedBeforeAllocation) {
  const TempDir dir;
  for (const std::int32_t side : {30000, 60000}) {
    const fs::path file = forged_gbuffer(dir, std::to_string(side) + ".exr", side, side);
    const auto outcome = testing::run_with_memory_limit([&] { read_gbuffer_exr(file.string()); });
    EXPECT_TRUE(outcome.input_error) << side << ": " << outcome.message;
    EXPECT_NE(outcome.message.find(file.string() + ": dataWindow: " + std::to_string(side) + "x" +
                                   std::to_string(side) +
                                   " exceeds the largest camera resolution 16384x16384"),
              std::string::npos)
        << outcome.message;
  }
  // The reported case: compared with the 64x48 camera before OpenEXR sizes anything.
  const fs::path forged = dir.path() / "30000.exr";
  const auto against_camera =
      testing::run_with_memory_limit([&] { check_gbuffer_exr_header(forged.string(), 64, 48); });
  EXPECT_NE(against_camera.message.find(forged.string() +
                                        ": dataWindow: 30000x30000 differs from the case "
                                        "camera's 64x48"),
            std::string::npos)
      << against_camera.message;
  // Within the camera limit, but far more pixels than the file can hold.
  const fs::path file = forged_gbuffer(dir, "16000.exr", 16000, 16000);
  const auto outcome = testing::run_with_memory_limit([&] { read_gbuffer_exr(file.string()); });
  EXPECT_TRUE(outcome.input_error) << outcome.message;
  EXPECT_NE(outcome.message.find("16000x16000 pixels need 7168000000 bytes, more than the file's"),
            std::string::npos)
      << outcome.message;
}

TEST(GBufferExrHostile, ResolutionIsComparedWithTheCameraBeforeReading) {
  const TempDir dir;
  const fs::path file = dir.path() / "small.exr";
  write_gbuffer_exr(file.string(), sky_samples(64, 48));
  EXPECT_NO_THROW(check_gbuffer_exr_header(file.string(), 64, 48));
  EXPECT_EQ(read_gbuffer_exr(file.string(), 64, 48).samples.size(), 64u * 48u);
  try {
    check_gbuffer_exr_header(file.string(), 640, 480);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  file.string() + ": dataWindow: 64x48 differs from the case camera's 640x480"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read_gbuffer_exr(file.string(), 640, 480), InputError);
  // Not a regular file: said so, not "not found" and not an image error.
  try {
    read_gbuffer_exr("/dev/zero");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/zero: file: not a regular file"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace shadowcts
