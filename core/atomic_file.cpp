#include "atomic_file.h"

#include <fstream>
#include <stdexcept>

namespace shadowcts {

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
  std::filesystem::path temporary = path;
  temporary += ".partial";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(contents.data(), std::streamsize(contents.size()));
    file.close();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error(path.string() + ": cannot write");
    }
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace shadowcts
