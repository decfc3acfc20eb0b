#pragma once
// OpenMesh helpers shared by the glTF and the OBJ/OFF/PLY/STL loaders: closedness of a triangle
// mesh (so that every format gets the same answer for the same geometry), and capture of
// OpenMesh's diagnostics (which it otherwise prints to stderr and never reports to the caller).
#include <mutex>
#include <span>
#include <sstream>
#include <string>

#include "shadowcts/case.h"

namespace shadowcts {

// True iff the triangles form closed, consistently oriented 2-manifold surfaces: every edge is
// shared by exactly two triangles that traverse it in opposite directions. Vertices are welded by
// exact float position first (glTF and PLY files often duplicate vertices per face for their
// normals), so the answer is about the geometry the algorithms see, not the file's indexing.
// Triangles with a repeated (welded) corner have no area and are ignored. Triangles OpenMesh cannot
// add (non-manifold, inconsistently oriented) make the answer false; false is always the safe
// answer (it only disables front-face culling).
bool is_closed_surface(std::span<const Triangle> triangles);

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
