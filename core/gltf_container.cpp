#include "gltf_container.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

std::vector<unsigned char> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "file", "read error");
  return bytes;
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

bool is_glb(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

bool has_glb_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

// The first four bytes as hex and, when printable, as text: "67 6c 54 46 'glTF'".
std::string magic_text(const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 4) return "missing: the file has " + std::to_string(bytes.size()) + " bytes";
  static constexpr char digits[] = "0123456789abcdef";
  std::string hex, printable = "'";
  for (std::size_t i = 0; i < 4; ++i) {
    hex += (i ? " " : "") + std::string{digits[bytes[i] >> 4], digits[bytes[i] & 15]};
    printable += std::isprint(bytes[i]) ? static_cast<char>(bytes[i]) : '.';
  }
  return hex + " " + printable + "', expected 67 6c 54 46 'glTF'";
}

// The JSON chunk of a GLB container, after checking the container's own lengths.
std::string glb_json_chunk(const std::string& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 20) throw InputError(path, "GLB header", "file is shorter than a GLB header");
  const std::uint32_t version = read_u32_le(bytes.data() + 4);
  const std::uint32_t length = read_u32_le(bytes.data() + 8);
  if (version != 2) {
    throw InputError(path, "GLB header",
                     "container version " + std::to_string(version) + " is not supported (2)");
  }
  if (length != bytes.size()) {
    throw InputError(path, "GLB header",
                     "declares " + std::to_string(length) + " bytes, the file has " +
                         std::to_string(bytes.size()) +
                         (length > bytes.size() ? " (truncated)" : ""));
  }
  const std::uint32_t chunk_length = read_u32_le(bytes.data() + 12);
  if (std::memcmp(bytes.data() + 16, "JSON", 4) != 0) {
    throw InputError(path, "GLB chunk 0", "is not the JSON chunk");
  }
  if (chunk_length > bytes.size() - 20) {
    throw InputError(path, "GLB chunk 0", "JSON chunk extends past the end of the file");
  }
  return std::string(reinterpret_cast<const char*>(bytes.data()) + 20, chunk_length);
}

}  // namespace

GltfContainer read_gltf_container(const std::string& path) {
  GltfContainer file;
  file.bytes = read_file_bytes(path);
  file.binary = is_glb(file.bytes);
  if (!file.binary && has_glb_extension(path))
    throw InputError(path, "GLB header", "not a GLB file (magic " + magic_text(file.bytes) + ")");
  file.json_text = file.binary ? glb_json_chunk(path, file.bytes)
                               : std::string(file.bytes.begin(), file.bytes.end());
  return file;
}

}  // namespace shadowcts
