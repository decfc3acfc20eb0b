#pragma once
// Outputs are written completely or not at all: into a sibling temporary, then renamed.
#include <filesystem>
#include <string_view>

namespace shadowcts {

// Every write, the close and the rename are checked (a full disk shows at any of them); throws
// OutputError naming the path and the system's reason, leaving no temporary behind.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace shadowcts
