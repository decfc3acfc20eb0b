#pragma once
// What OpenMesh's mesh readers would crash on, or silently read as something else without a
// failed read, checked before they read the file. The OBJ and STL readers parse each line in a
// string stream of their own, so their values are checked here (an unparsable coordinate drops
// the vertex and renumbers the rest; "f /1 2 3" fails an assertion); the OFF and PLY readers read
// from the loader's checking stream (mesh_file_loader.cpp), so only what they misread before any
// value is checked here: the OFF keyword line and the PLY header. Each problem is an InputError
// naming the file, the element and the line.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace shadowcts {

// What the pre-checks learned about a file, for cross-checking what OpenMesh's reader delivered.
struct DeclaredCounts {
  DeclaredCounts(std::optional<std::size_t> vertices_ = {},
                 std::optional<std::size_t> triangles_ = {})
      : vertices(vertices_), triangles(triangles_) {}
  std::optional<std::size_t> vertices;
  std::optional<std::size_t> triangles;              // after fan triangulation of polygons
  std::size_t faces = 0;                             // faces seen by the scan
  std::size_t repeated_vertex_faces = 0;             // of them, with fewer than 3 distinct corners
  std::optional<std::string> first_repeated_vertex;  // "f 2 (line 7) uses vertex 3 more ..."
  std::vector<std::string> skipped_words;            // PLY header words the reader skips
  bool binary = false;  // OFF, PLY: the data after the header are binary
};

// `format` is the lowercase extension with its dot (".obj", ".stl", ".off", ".ply").
DeclaredCounts precheck_mesh_file(const std::string& path, const std::string& format);

// What is wrong with `word` as a coordinate, e.g. "'nan' is not finite"; nullopt for a finite
// number in float range. OpenMesh's readers parse coordinates with iostreams, where "nan", "inf"
// and values beyond float range fail to parse.
std::optional<std::string> float_problem(const std::string& word);

// A word of the file in a message, quoted and cut short.
std::string quoted(const std::string& word);

}  // namespace shadowcts
