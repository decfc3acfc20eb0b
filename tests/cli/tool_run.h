#pragma once
// Running the shadowcts program from a test: scratch folders, file contents, exit statuses.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace shadowcts::testing {

// An empty folder <temp>/shadowcts_<name>.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("shadowcts_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Exit status of a bash script run in `dir` (stdout and stderr to stdout.txt and stderr.txt
// there); -1 when it did not exit (killed by a signal).
inline int run_shell(const std::string& script, const std::filesystem::path& dir) {
  std::ofstream(dir / "script.sh") << script;
  const std::string command =
      "cd '" + dir.string() + "' && bash script.sh > stdout.txt 2> stderr.txt";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The tool under test (SHADOWCTS_TOOL, set by CMake) with `arguments`, run in `dir`.
inline int run_tool(const std::string& arguments, const std::filesystem::path& dir) {
  return run_shell("exec '" SHADOWCTS_TOOL "' " + arguments + "\n", dir);
}

}  // namespace shadowcts::testing
