#include "mesh_closedness.h"

#include <array>
#include <bit>
#include <cstdint>
#include <iostream>
#include <map>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

namespace shadowcts {
namespace {

using ClosednessMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Exact position key; -0 and +0 are the same point.
using PositionKey = std::array<std::uint32_t, 3>;

PositionKey position_key(const glm::vec3& p) {
  PositionKey key{};
  for (int axis = 0; axis < 3; ++axis) {
    const float coordinate = p[axis] == 0.0f ? 0.0f : p[axis];
    key[static_cast<std::size_t>(axis)] = std::bit_cast<std::uint32_t>(coordinate);
  }
  return key;
}

}  // namespace

bool is_closed_surface(std::span<const Triangle> triangles) {
  if (triangles.empty()) return false;
  ClosednessMesh mesh;
  // std::map keeps the vertex numbering independent of hashing: deterministic.
  std::map<PositionKey, ClosednessMesh::VertexHandle> welded;
  auto vertex_for = [&](const glm::vec3& p) {
    auto [it, inserted] = welded.try_emplace(position_key(p));
    if (inserted) it->second = mesh.add_vertex(ClosednessMesh::Point(p.x, p.y, p.z));
    return it->second;
  };
  // add_face reports its failures on omerr; the answer (false) is all the caller needs.
  OpenMeshErrorCapture silenced;
  for (const Triangle& t : triangles) {
    const auto a = vertex_for(t.v0);
    const auto b = vertex_for(t.v1);
    const auto c = vertex_for(t.v2);
    // A triangle with a repeated corner has no area and casts no shadow: it neither opens nor
    // closes the surface (CAD exports have such slivers where float rounding merged corners).
    if (a == b || b == c || a == c) continue;
    // add_face fails on complex edges and vertices: non-manifold or inconsistently oriented.
    if (!mesh.add_face(a, b, c).is_valid()) return false;
  }
  if (mesh.n_faces() == 0) return false;
  for (const auto halfedge : mesh.halfedges()) {
    if (mesh.is_boundary(halfedge)) return false;
  }
  return true;
}

namespace {
std::recursive_mutex& openmesh_error_stream_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

// OpenMesh's error stream is redirected once per process, into one buffer: its disconnect()
// never frees what connect() allocated, so connecting per load would leak every time.
std::ostringstream& openmesh_error_buffer() {
  static std::ostringstream* buffer = [] {
    auto* b = new std::ostringstream;  // lives as long as OpenMesh's stream refers to it
    omerr().disconnect(std::cerr);
    omerr().connect(*b);
    return b;
  }();
  return *buffer;
}
}  // namespace

OpenMeshErrorCapture::OpenMeshErrorCapture()
    : lock_(openmesh_error_stream_mutex()), previous_cerr_(nullptr), previous_clog_(nullptr) {
  omerr().flush();
  openmesh_error_buffer().str("");
  std::cerr.flush();
  std::clog.flush();
  previous_cerr_ = std::cerr.rdbuf(openmesh_error_buffer().rdbuf());
  previous_clog_ = std::clog.rdbuf(openmesh_error_buffer().rdbuf());
}

OpenMeshErrorCapture::~OpenMeshErrorCapture() {
  omerr().flush();
  std::cerr.rdbuf(previous_cerr_);
  std::clog.rdbuf(previous_clog_);
  openmesh_error_buffer().str("");
}

std::string OpenMeshErrorCapture::text() {
  omerr().flush();
  std::cerr.flush();
  std::clog.flush();
  return openmesh_error_buffer().str();
}

}  // namespace shadowcts
