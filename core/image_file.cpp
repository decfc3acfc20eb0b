#include "shadowcts/image_file.h"

#include <filesystem>
#include <memory>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace shadowcts {

void write_image(const std::string& path, const RgbImage& image) {
  const std::filesystem::path target(path);
  // Keep the extension last so OpenImageIO still picks the format from it.
  const std::filesystem::path temporary =
      target.parent_path() / (target.stem().string() + ".partial" + target.extension().string());
  const bool exr = target.extension() == ".exr";
  {
    auto out = OIIO::ImageOutput::create(temporary.string());
    if (!out) throw std::runtime_error(path + ": no image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(int(image.width), int(image.height), 3,
                         exr ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
    if (exr) {
      spec.attribute("compression", "zip");
      // An empty DateTime keeps OpenEXR from stamping the write time into capDate: the same
      // run gives the same bytes.
      spec.attribute("DateTime", "");
    }
    // Passing UINT8 pixels lets OIIO convert them to the file's format (0..255 -> 0..1 in EXR).
    if (!out->open(temporary.string(), spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, image.rgb.data()) || !out->close()) {
      const std::string error = out->geterror();
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error(path + ": cannot write image: " + error);
    }
  }
  std::filesystem::rename(temporary, target);
}

}  // namespace shadowcts
