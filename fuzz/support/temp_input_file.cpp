#include "temp_input_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

namespace shadowcts::fuzzing {

const std::string& scratch_folder() {
  // One folder per process: parallel fuzzing jobs (-jobs=N) must not overwrite each other's input.
  static const std::string folder = [] {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("shadowcts-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path.string();
  }();
  return folder;
}

std::string write_scratch_file(const std::string& name, const std::uint8_t* data,
                               std::size_t size) {
  const std::string path = scratch_folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error("cannot write the fuzz input to " + path);
  return path;
}

}  // namespace shadowcts::fuzzing
