#include "mesh_file_loader.h"

// OpenMesh's reader needs MeshIO.hh before the mesh type is declared.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_closedness.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

using FileMesh = OpenMesh::TriMesh_ArrayKernelT<>;

std::vector<std::string> split_whitespace(std::string_view line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.emplace_back(line.substr(start, i - start));
  }
  return tokens;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// OpenMesh's ASCII readers parse coordinates with iostreams: "nan", "inf" and values beyond float
// range fail to parse and the vertex is silently dropped or left as garbage, which renumbers or
// corrupts everything after it. The text formats are therefore scanned here first, so that such
// a vertex is reported by its number and line.
void check_coordinate_token(const std::string& path, const std::string& token,
                            const std::string& element) {
  double value = 0.0;
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (!token.empty() && *begin == '+') ++begin;  // from_chars rejects a leading '+'
  const auto [rest, error] = std::from_chars(begin, end, value);
  if (error == std::errc::result_out_of_range) {
    throw InputError(path, element, "coordinate '" + token + "' is out of float range");
  }
  if (error != std::errc() || rest != end) {
    throw InputError(path, element, "coordinate '" + token + "' is not a number");
  }
  if (!std::isfinite(value)) {
    throw InputError(path, element, "coordinate '" + token + "' is not finite");
  }
  if (std::fabs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
    throw InputError(path, element, "coordinate '" + token + "' is out of float range");
  }
}

std::string vertex_element(std::size_t vertex, std::size_t line) {
  return "vertex " + std::to_string(vertex) + " (line " + std::to_string(line) + ")";
}

// What the text pre-scan learned about the file, for cross-checking what OpenMesh read.
struct DeclaredCounts {
  std::optional<std::size_t> vertices;
  std::optional<std::size_t> triangles;  // after fan triangulation of polygons
};

// OBJ: "v x y z [w]" lines (vertex numbers are 1-based, as in the file); "f" lines give n - 2
// triangles each.
DeclaredCounts scan_obj(const std::string& path, std::istream& in) {
  DeclaredCounts counts{0, 0};
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      const std::size_t vertex = ++*counts.vertices;
      const std::string element =
          "v " + std::to_string(vertex) + " (line " + std::to_string(line_number) + ")";
      if (tokens.size() < 4) throw InputError(path, element, "fewer than 3 coordinates");
      for (std::size_t axis = 1; axis <= 3; ++axis)
        check_coordinate_token(path, tokens[axis], element);
    } else if (tokens[0] == "f" && tokens.size() >= 4) {
      *counts.triangles += tokens.size() - 3;
    }
  }
  return counts;
}

// ASCII STL: "vertex x y z" lines inside facets; binary STL is detected the way OpenMesh does,
// by its exact size 84 + 50 * facets.
DeclaredCounts scan_stl(const std::string& path, std::istream& in) {
  char header[84] = {};
  in.read(header, sizeof header);
  const auto header_bytes = static_cast<std::size_t>(in.gcount());
  std::error_code error;
  const auto file_size = std::filesystem::file_size(path, error);
  if (header_bytes == sizeof header && !error) {
    std::uint32_t facets = 0;
    std::memcpy(&facets, header + 80, sizeof facets);
    if (file_size == 84 + 50 * static_cast<std::uintmax_t>(facets)) {
      // Binary: OpenMesh silently drops facets with NaN corners, so they are named here.
      char facet[50];
      for (std::uint32_t f = 0; f < facets && in.read(facet, sizeof facet); ++f) {
        for (std::size_t corner = 0; corner < 3; ++corner) {
          float xyz[3];
          std::memcpy(xyz, facet + 12 + 12 * corner, sizeof xyz);
          if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
            throw InputError(path,
                             "facet " + std::to_string(f) + " vertex " + std::to_string(corner),
                             "non-finite coordinate");
          }
        }
      }
      return {std::nullopt, facets};
    }
  }
  in.clear();
  in.seekg(0);
  DeclaredCounts counts{std::nullopt, 0};
  std::string line;
  std::size_t line_number = 0, vertex = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    const std::string keyword = lowercase(tokens[0]);
    if (keyword == "facet") ++*counts.triangles;
    if (keyword != "vertex") continue;
    const std::string element = vertex_element(vertex++, line_number);
    if (tokens.size() < 4) throw InputError(path, element, "fewer than 3 coordinates");
    for (std::size_t axis = 1; axis <= 3; ++axis)
      check_coordinate_token(path, tokens[axis], element);
  }
  return counts;
}

// Next line that is not empty and not a '#' comment, split; empty at end of file.
std::vector<std::string> next_content_line(std::istream& in, std::size_t& line_number) {
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    const auto comment = line.find('#');
    if (comment != std::string::npos) line.erase(comment);
    auto tokens = split_whitespace(line);
    if (!tokens.empty()) return tokens;
  }
  return {};
}

std::optional<std::size_t> parse_count(const std::string& token) {
  std::size_t value = 0;
  const auto [rest, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || rest != token.data() + token.size()) return std::nullopt;
  return value;
}

// OFF: header keyword ([ST][C][N][4][n]OFF, optionally BINARY), counts "vertices faces edges",
// then one vertex per line. Only plain 3D ASCII OFF is scanned; OpenMesh reads the others alone.
DeclaredCounts scan_off(const std::string& path, std::istream& in) {
  std::size_t line_number = 0;
  auto tokens = next_content_line(in, line_number);
  if (tokens.empty()) return {};
  const std::string keyword = tokens[0];
  const bool plain_ascii = keyword.size() >= 3 && keyword.ends_with("OFF") &&
                           keyword.find('4') == std::string::npos && !keyword.starts_with("n") &&
                           !(tokens.size() > 1 && tokens[1] == "BINARY");
  if (!plain_ascii) return {};
  tokens.erase(tokens.begin());
  if (tokens.empty()) tokens = next_content_line(in, line_number);
  if (tokens.size() < 2) return {};
  const auto vertices = parse_count(tokens[0]);
  const auto faces = parse_count(tokens[1]);
  if (!vertices || !faces) return {};
  for (std::size_t vertex = 0; vertex < *vertices; ++vertex) {
    const auto coordinates = next_content_line(in, line_number);
    const std::string element = vertex_element(vertex, line_number);
    if (coordinates.empty()) {
      throw InputError(
          path, "vertex " + std::to_string(vertex),
          "file ends before the " + std::to_string(*vertices) + " vertices its header declares");
    }
    if (coordinates.size() < 3) throw InputError(path, element, "fewer than 3 coordinates");
    for (std::size_t axis = 0; axis < 3; ++axis)
      check_coordinate_token(path, coordinates[axis], element);
  }
  std::size_t triangles = 0;
  for (std::size_t face = 0; face < *faces; ++face) {
    const auto indices = next_content_line(in, line_number);
    const std::string element =
        "face " + std::to_string(face) + " (line " + std::to_string(line_number) + ")";
    if (indices.empty()) {
      throw InputError(
          path, "face " + std::to_string(face),
          "file ends before the " + std::to_string(*faces) + " faces its header declares");
    }
    const auto corner_count = parse_count(indices[0]);
    if (!corner_count || indices.size() < 1 + *corner_count) {
      throw InputError(path, element, "malformed face (vertex count, then that many indices)");
    }
    for (std::size_t corner = 1; corner <= *corner_count; ++corner) {
      const auto index = parse_count(indices[corner]);
      if (!index || *index >= *vertices) {
        throw InputError(path, element,
                         "vertex index '" + indices[corner] + "' is out of range (" +
                             std::to_string(*vertices) + " vertices)");
      }
    }
    if (*corner_count >= 3) triangles += *corner_count - 2;
  }
  return {*vertices, triangles};
}

// PLY: the header declares the element counts; an ASCII file whose first element is the vertex
// element has its x, y, z properties scanned (one vertex per line).
DeclaredCounts scan_ply(const std::string& path, std::istream& in) {
  std::size_t line_number = 0;
  bool ascii = false, vertex_is_first = false, vertex_has_list = false;
  std::optional<std::size_t> vertices, faces;
  std::string current_element;
  std::vector<std::string> vertex_properties;
  for (;;) {
    std::string line;
    // OpenMesh's PLY reader loops forever on a header without end_header: refuse it here.
    if (!std::getline(in, line))
      throw InputError(path, "header", "the PLY header has no end_header line");
    ++line_number;
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "end_header") break;
    if (tokens[0] == "format" && tokens.size() > 1) ascii = tokens[1] == "ascii";
    if (tokens[0] == "element" && tokens.size() > 2) {
      if (current_element.empty()) vertex_is_first = tokens[1] == "vertex";
      current_element = tokens[1];
      if (tokens[1] == "vertex") vertices = parse_count(tokens[2]);
      if (tokens[1] == "face") faces = parse_count(tokens[2]);
    }
    if (tokens[0] == "property" && current_element == "vertex") {
      if (tokens.size() > 1 && tokens[1] == "list") vertex_has_list = true;
      vertex_properties.push_back(tokens.back());
    }
  }
  DeclaredCounts counts{vertices, std::nullopt};
  std::vector<std::size_t> columns;
  for (const char* axis : {"x", "y", "z"}) {
    const auto it = std::find(vertex_properties.begin(), vertex_properties.end(), axis);
    if (it == vertex_properties.end()) {
      throw InputError(path, "header", std::string("vertex element has no property ") + axis);
    }
    columns.push_back(static_cast<std::size_t>(it - vertex_properties.begin()));
  }
  if (!ascii || !vertex_is_first || vertex_has_list || !vertices) return counts;
  for (std::size_t vertex = 0; vertex < *vertices; ++vertex) {
    std::string line;
    if (!std::getline(in, line)) {
      throw InputError(
          path, "vertex " + std::to_string(vertex),
          "file ends before the " + std::to_string(*vertices) + " vertices its header declares");
    }
    ++line_number;
    const auto tokens = split_whitespace(line);
    const std::string element = vertex_element(vertex, line_number);
    if (tokens.size() < vertex_properties.size()) {
      throw InputError(path, element,
                       "fewer values than the " + std::to_string(vertex_properties.size()) +
                           " vertex properties of the header");
    }
    for (const std::size_t column : columns) check_coordinate_token(path, tokens[column], element);
  }
  (void)faces;  // polygons: their triangle count is not known from the header
  return counts;
}

std::size_t count_occurrences(const std::string& text, std::string_view what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) {
    ++count;
  }
  return count;
}

}  // namespace

LoadedScene load_mesh_file(const std::string& path) {
  const std::filesystem::path file(path);
  const std::string format = lowercase(file.extension().string());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");

  DeclaredCounts declared;
  if (format == ".obj") declared = scan_obj(path, in);
  if (format == ".stl") declared = scan_stl(path, in);
  if (format == ".off") declared = scan_off(path, in);
  if (format == ".ply") declared = scan_ply(path, in);
  in.close();

  FileMesh mesh;
  std::string diagnostics;
  bool read_ok = false;
  {
    OpenMeshErrorCapture capture;
    OpenMesh::IO::Options options;
    try {
      read_ok = OpenMesh::IO::read_mesh(mesh, path, options);
    } catch (const std::exception& e) {
      throw InputError(path, "file", std::string("OpenMesh failed: ") + e.what());
    }
    diagnostics = capture.text();
  }
  auto with_diagnostics = [&](std::string problem) {
    if (!diagnostics.empty()) problem += " (OpenMesh: " + diagnostics + ")";
    while (!problem.empty() && problem.back() == '\n') problem.pop_back();
    return problem;
  };
  if (!read_ok) throw InputError(path, "file", with_diagnostics("OpenMesh cannot read it"));

  // Faces OpenMesh could not add because an index points nowhere (out of range, or at a vertex it
  // failed to read) are missing geometry: the file is malformed.
  const std::size_t invalid_index_faces =
      count_occurrences(diagnostics, "Face contains invalid vertex index");
  if (invalid_index_faces > 0 ||
      diagnostics.find("invalid faces, that could not be added") != std::string::npos) {
    throw InputError(path, "faces",
                     std::to_string(invalid_index_faces > 0 ? invalid_index_faces : 1) +
                         " face(s) reference a vertex that does not exist (index out of range, "
                         "or a vertex whose coordinates could not be read)");
  }
  if (mesh.n_faces() == 0) {
    throw InputError(path, "faces",
                     with_diagnostics("no faces: empty, or not a valid " + format + " file"));
  }
  if (declared.vertices && mesh.n_vertices() < *declared.vertices) {
    throw InputError(path, "vertices",
                     "the file declares " + std::to_string(*declared.vertices) +
                         " vertices, OpenMesh read " + std::to_string(mesh.n_vertices()));
  }

  LoadedScene scene;
  const std::size_t degenerate_faces = count_occurrences(diagnostics, "Face has equal vertices");
  if (degenerate_faces > 0) {
    scene.warnings.push_back(path + ": faces: " + std::to_string(degenerate_faces) +
                             " face(s) with a repeated vertex dropped (no area, no shadow)");
  }
  const std::size_t non_manifold_faces = count_occurrences(diagnostics, "complex edge") +
                                         count_occurrences(diagnostics, "complex vertex");
  if (non_manifold_faces > 0) {
    scene.warnings.push_back(path + ": faces: " + std::to_string(non_manifold_faces) +
                             " non-manifold face(s) kept with duplicated vertices");
  }
  if (declared.triangles && mesh.n_faces() + degenerate_faces < *declared.triangles) {
    scene.warnings.push_back(path + ": faces: the file has " + std::to_string(*declared.triangles) +
                             " triangles, OpenMesh read " + std::to_string(mesh.n_faces()));
  }

  for (const auto vertex : mesh.vertices()) {
    const auto& p = mesh.point(vertex);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InputError(path, "vertex " + std::to_string(vertex.idx()),
                       "non-finite coordinate (" + std::to_string(p[0]) + ", " +
                           std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")");
    }
  }

  scene.triangles.reserve(mesh.n_faces());
  for (const auto face : mesh.faces()) {
    glm::vec3 corners[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    int corner = 0;
    for (const auto vertex : mesh.fv_range(face)) {
      const auto& p = mesh.point(vertex);
      corners[corner++] = glm::vec3(p[0], p[1], p[2]);
      if (corner == 3) break;
    }
    scene.triangles.push_back(Triangle{corners[0], corners[1], corners[2], 0});
  }
  Mesh loaded_mesh;
  loaded_mesh.name = file.stem().string();
  loaded_mesh.closed = is_closed_surface(scene.triangles);
  scene.meshes.push_back(std::move(loaded_mesh));
  return scene;
}

}  // namespace shadowcts
