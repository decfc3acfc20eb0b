#pragma once
// Outputs are written completely or not at all: into a sibling temporary, then renamed.
#include <filesystem>
#include <string>

namespace shadowcts {

// Throws std::runtime_error naming the path when it cannot be written.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace shadowcts
