#pragma once
// Capture of OpenMesh's diagnostics for the OBJ/OFF/PLY/STL loader (which OpenMesh otherwise
// prints to stderr and never reports to the caller). Closedness: shadowcts/closed_surface.h.
#include <mutex>
#include <sstream>
#include <string>

namespace shadowcts {

// While alive, what OpenMesh reports on its error stream (omerr) is collected for text(). omerr is
// process-global: the first capture redirects it from stderr into one process-wide buffer for
// good (OpenMesh leaks on every reconnect), and each capture holds a process-wide lock, so
// concurrent loads serialize here. Some OpenMesh readers write to std::clog or std::cerr directly
// (the PLY reader's "Unsupported keyword" goes to std::clog): both go into the same buffer while a
// capture lives, so nothing of OpenMesh reaches the user's terminal unfiltered. Loads run before
// any worker thread writes to these streams.
class OpenMeshErrorCapture {
 public:
  OpenMeshErrorCapture();
  ~OpenMeshErrorCapture();
  OpenMeshErrorCapture(const OpenMeshErrorCapture&) = delete;
  OpenMeshErrorCapture& operator=(const OpenMeshErrorCapture&) = delete;

  // Everything OpenMesh reported so far.
  std::string text();

 private:
  std::unique_lock<std::recursive_mutex> lock_;
  std::streambuf* previous_cerr_;
  std::streambuf* previous_clog_;
};

}  // namespace shadowcts
