#pragma once
// What OpenMesh's readers read, received as they read it: every vertex, and every face with its
// corners as the file gives them. Nothing goes through OpenMesh's mesh topology, so a face that a
// PolyMesh would reject (a complex edge or vertex: three faces on an edge, inconsistent
// orientation) is kept as it is; a conformance suite must not change its input. What can be
// checked on what the readers deliver is checked here: vertices (finite, within the largest
// coordinate a case accepts), faces (at least 3 corners, each a vertex read), the counts the OFF
// and PLY readers declare before their data. Faces that name a vertex more than once have no area:
// they are counted and dropped. Problems are recorded, not thrown, so that no exception of ours
// crosses OpenMesh's reader; the first one is reported once the reader returns.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <OpenMesh/Core/IO/importer/BaseImporter.hh>

#include "shadowcts/scene_file.h"

namespace shadowcts {

class FaceKeepingImporter final : public OpenMesh::IO::BaseImporter {
 public:
  using Point = OpenMesh::Vec3f;
  using VertexHandle = OpenMesh::VertexHandle;
  using HalfedgeHandle = OpenMesh::HalfedgeHandle;
  using EdgeHandle = OpenMesh::EdgeHandle;
  using FaceHandle = OpenMesh::FaceHandle;

  std::vector<Point> points;                // in the reader's vertex order
  std::vector<std::uint32_t> corners;       // kept faces' corners, one face after the other
  std::vector<std::uint32_t> face_corners;  // number of corners of each kept face
  std::size_t faces_read = 0;               // every add_face call
  std::size_t repeated_vertex_faces = 0;    // dropped: a corner repeats
  std::size_t repeated_vertex_triangles = 0;
  std::optional<std::string> first_repeated_vertex;  // "face 3 (line 9) uses vertex 1 ..."
  std::optional<std::pair<std::string, std::string>> problem;  // element, what is wrong
  // The counts the OFF and PLY readers declare to reserve() before their data.
  std::optional<std::size_t> declared_vertices, declared_faces;

  // `watched`: the stream the reader reads (OFF, PLY), or null where it opens the file itself
  // (OBJ, STL). With a watched stream, messages name the element a failed read stopped in, and
  // in a text file (`text`) the line.
  FaceKeepingImporter(std::string path, const std::istream* watched, bool text)
      : path_(std::move(path)), watched_(watched), text_(text) {}

  // Fan triangulation (corner 0, i, i + 1), as OpenMesh's TriMesh splits a polygon.
  std::vector<Triangle> triangles() const;

  // A read of the watched stream failed (its exception ended the reader): names the word it
  // failed on, or the end of the file, and the element it was reading.
  void read_failed();
  // Every vertex and face the reader's counts declared arrived (its loops also stop, without a
  // failed read, where the file ends right after a value).
  void require_declared_counts();

  VertexHandle add_vertex(const Point& point) override;
  // The PLY reader adds a vertex before it reads it and sets its point after.
  VertexHandle add_vertex() override;
  void set_point(VertexHandle vertex, const Point& point) override;
  FaceHandle add_face(const VHandles& indices) override;
  // Only OpenMesh's own .om format builds faces from halfedges; the loader does not read it.
  FaceHandle add_face(HalfedgeHandle) override;
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }

  // Like OpenMesh's importer for its TriMesh, so that each reader takes the path it took before.
  bool is_triangle_mesh() const override { return true; }
  // The declared counts are not trusted with memory: nothing is reserved, they are only kept.
  void reserve(unsigned int vertices, unsigned int, unsigned int faces) override {
    declared_vertices = vertices;
    declared_faces = faces;
  }
  size_t n_vertices() const override { return points.size(); }
  size_t n_faces() const override { return face_corners.size(); }
  size_t n_edges() const override { return 0; }

  // What the loader does not use: normals, colours, texture coordinates, status, halfedges.
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  std::string path_;
  const std::istream* watched_;
  bool text_;
  bool vertex_open_ = false;  // added, its point not yet set

  bool valid(VertexHandle vertex) const {
    return vertex.idx() >= 0 && static_cast<std::size_t>(vertex.idx()) < points.size();
  }
  void fail(const std::string& element, std::string what) {
    if (!problem) problem.emplace(element, std::move(what));
  }
  void check_point(std::size_t vertex);
  std::uint64_t position() const;
  std::string located(const std::string& kind, std::size_t n) const;
  std::string number(int n) const;
  std::string reading(bool with_line) const;
  std::string still_declared() const;
};

}  // namespace shadowcts
