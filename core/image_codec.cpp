#include "image_codec.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace shadowcts {
namespace {

constexpr const char* module_name = "libshadowcts_oiio.so";

// Beside the running program first (a copied or installed layout), then where the build put it.
std::string module_path() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path beside = program.parent_path() / module_name;
    if (std::filesystem::exists(beside, error)) return beside.string();
  }
  return SHADOWCTS_IMAGE_CODEC_MODULE;
}

const ImageCodec* load_codec() {
  const std::string path = module_path();
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module) {
    const char* reason = dlerror();
    throw std::runtime_error("cannot load the image module " + path + ": " +
                             (reason ? reason : "unknown reason"));
  }
  using Entry = const ImageCodec* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(module, "shadowcts_image_codec"));
  if (!entry)
    throw std::runtime_error("the image module " + path + " has no shadowcts_image_codec");
  return entry();  // the module stays loaded for the life of the process
}

}  // namespace

const ImageCodec& image_codec() {
  static const ImageCodec* const codec = load_codec();
  return *codec;
}

}  // namespace shadowcts
