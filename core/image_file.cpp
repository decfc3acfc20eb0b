#include "shadowcts/image_file.h"

#include <filesystem>
#include <memory>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "atomic_file.h"
#include "shadowcts/errors.h"

namespace shadowcts {

void write_image(const std::string& path, const RgbImage& image) {
  const std::filesystem::path target(path);
  const bool exr = target.extension() == ".exr";
  // OpenImageIO encodes into memory and the bytes go through the one checked file writer: its
  // PNG writer does not report a failed write (a full disk gave zero-byte PNGs).
  std::vector<unsigned char> bytes;
  {
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto out = OIIO::ImageOutput::create(path);  // the format follows the extension
    if (!out) throw OutputError(path, "no image writer: " + OIIO::geterror());
    if (!out->supports("ioproxy"))
      throw OutputError(path, "the image writer cannot encode into memory");
    OIIO::ImageSpec spec(int(image.width), int(image.height), 3,
                         exr ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
    if (exr) {
      spec.attribute("compression", "zip");
      // An empty DateTime keeps OpenEXR from stamping the write time into capDate: the same
      // run gives the same bytes.
      spec.attribute("DateTime", "");
    }
    // Passing UINT8 pixels lets OIIO convert them to the file's format (0..255 -> 0..1 in EXR).
    if (!out->set_ioproxy(&memory) || !out->open(path, spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, image.rgb.data()) || !out->close() ||
        out->has_error())
      throw OutputError(path, "cannot encode image: " + out->geterror());
  }
  if (bytes.empty()) throw OutputError(path, "the image writer produced no bytes");
  write_file_atomically(
      target, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace shadowcts
