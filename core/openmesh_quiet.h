#pragma once
// OpenMesh's readers print their diagnostics (to its omerr stream, and some to std::clog or
// std::cerr directly: the PLY reader's "Unsupported keyword") and never report them to the caller.
// The loader finds every problem it reports itself (its pre-checks and its importer), so what
// OpenMesh prints is only silenced here, never read.
#include <mutex>
#include <streambuf>

namespace shadowcts {

// While alive, what OpenMesh writes to omerr, std::cerr and std::clog goes nowhere. omerr is
// process-global: the first instance redirects it from stderr into one process-wide sink for good
// (OpenMesh leaks on every reconnect), and each instance holds a process-wide lock, so concurrent
// loads serialize here. Loads run before any worker thread writes to these streams.
class OpenMeshQuiet {
 public:
  OpenMeshQuiet();
  ~OpenMeshQuiet();
  OpenMeshQuiet(const OpenMeshQuiet&) = delete;
  OpenMeshQuiet& operator=(const OpenMeshQuiet&) = delete;

 private:
  std::unique_lock<std::recursive_mutex> lock_;
  std::streambuf* previous_cerr_;
  std::streambuf* previous_clog_;
};

}  // namespace shadowcts
