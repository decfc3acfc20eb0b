#include "face_keeping_importer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "mesh_prechecks.h"

namespace shadowcts {
namespace {

// The line (from 1) that a byte offset of the file is on; counted only for messages.
std::size_t line_at(const std::string& path, std::uint64_t offset) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> block(std::size_t{1} << 16);
  std::size_t line = 1;
  while (offset > 0) {
    in.read(block.data(),
            static_cast<std::streamsize>(std::min<std::uint64_t>(offset, block.size())));
    if (in.gcount() <= 0) break;
    line += static_cast<std::size_t>(std::count(block.data(), block.data() + in.gcount(), '\n'));
    offset -= static_cast<std::uint64_t>(in.gcount());
  }
  return line;
}

// The whitespace-separated word of the file around a byte offset: where a read stopped, the word
// it failed on ("" at the end of the file).
std::string word_at(const std::string& path, std::uint64_t offset) {
  constexpr std::uint64_t reach = 64;
  const std::uint64_t start = offset > reach ? offset - reach : 0;
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(start));
  std::string window(2 * reach, '\0');
  in.read(window.data(), static_cast<std::streamsize>(window.size()));
  window.resize(static_cast<std::size_t>(in.gcount()));
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = std::min<std::size_t>(offset - start, window.size()), end = begin;
  while (begin > 0 && !space(window[begin - 1])) --begin;
  while (end < window.size() && !space(window[end])) ++end;
  return window.substr(begin, end - begin);
}

}  // namespace

std::vector<Triangle> FaceKeepingImporter::triangles() const {
  std::vector<Triangle> out;
  std::size_t first = 0;
  for (const std::uint32_t n : face_corners) {
    const auto at = [&](std::size_t c) {
      const Point& p = points[corners[first + c]];
      return glm::vec3(p[0], p[1], p[2]);
    };
    for (std::size_t i = 1; i + 1 < n; ++i) out.push_back(Triangle{at(0), at(i), at(i + 1), 0});
    first += n;
  }
  return out;
}

void FaceKeepingImporter::read_failed() {
  if (problem) return;
  const std::uint64_t offset = position();
  const std::string word = text_ ? word_at(path_, offset) : "";
  std::error_code error;
  const bool at_end = std::filesystem::file_size(path_, error) <= offset;
  // Counts and indices are whole numbers; vertices hold coordinates.
  const bool whole = !declared_vertices || (!vertex_open_ && points.size() >= *declared_vertices);
  const auto word_problem = float_problem(word);
  if (word.empty() || (at_end && !word_problem)) {
    // The end of the file, or right after the last number: the next read ran out.
    fail(reading(false), "the file ends before " + still_declared());
  } else if (!whole && word_problem) {
    fail(reading(true), "coordinate " + *word_problem);
  } else {
    fail(reading(true), quoted(word) + " is not a whole number from 0 to 4294967295");
  }
}

void FaceKeepingImporter::require_declared_counts() {
  if (declared_vertices &&
      (points.size() < *declared_vertices || faces_read < declared_faces.value_or(0))) {
    fail(reading(false), "the file ends before " + still_declared());
  }
}

FaceKeepingImporter::VertexHandle FaceKeepingImporter::add_vertex(const Point& point) {
  points.push_back(point);
  check_point(points.size() - 1);
  return VertexHandle(static_cast<int>(points.size() - 1));
}

FaceKeepingImporter::VertexHandle FaceKeepingImporter::add_vertex() {
  points.emplace_back(0.0f, 0.0f, 0.0f);
  vertex_open_ = true;
  return VertexHandle(static_cast<int>(points.size() - 1));
}

void FaceKeepingImporter::set_point(VertexHandle vertex, const Point& point) {
  vertex_open_ = false;
  if (!valid(vertex)) return;
  points[static_cast<std::size_t>(vertex.idx())] = point;
  check_point(static_cast<std::size_t>(vertex.idx()));
}

FaceKeepingImporter::FaceHandle FaceKeepingImporter::add_face(const VHandles& indices) {
  // Faces and vertices as the reader numbers them: from 0, in the order it hands them over.
  // Messages are only composed for the first problem: naming a line reads the file.
  const std::size_t face = faces_read++;
  if (indices.size() < 3) {
    if (!problem) {
      fail(located("face", face),
           "has " + std::to_string(indices.size()) + " corner(s); a face needs at least 3");
    }
    return FaceHandle();
  }
  for (const VertexHandle vertex : indices) {
    if (valid(vertex)) continue;
    if (!problem) {
      fail(located("face", face), "vertex index " + number(vertex.idx()) + " is out of range (" +
                                      std::to_string(points.size()) + " vertices read)");
    }
    return FaceHandle();
  }
  for (std::size_t i = 0; i < indices.size(); ++i) {
    for (std::size_t j = i + 1; j < indices.size(); ++j) {
      if (indices[i] != indices[j]) continue;
      ++repeated_vertex_faces;
      repeated_vertex_triangles += indices.size() - 2;
      if (!first_repeated_vertex) {
        first_repeated_vertex =
            located("face", face) + " uses vertex " + number(indices[i].idx()) + " more than once";
      }
      return FaceHandle();
    }
  }
  for (const VertexHandle vertex : indices)
    corners.push_back(static_cast<std::uint32_t>(vertex.idx()));
  face_corners.push_back(static_cast<std::uint32_t>(indices.size()));
  return FaceHandle(static_cast<int>(face_corners.size() - 1));
}

FaceKeepingImporter::FaceHandle FaceKeepingImporter::add_face(HalfedgeHandle) {
  fail("face " + std::to_string(faces_read++), "given as halfedges, which is not supported");
  return FaceHandle();
}

// A vertex the reader delivered: finite, and no larger than a case accepts.
void FaceKeepingImporter::check_point(std::size_t vertex) {
  const Point& p = points[vertex];
  const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  if (problem || (finite && std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])}) <=
                                max_scene_coordinate))
    return;
  std::string what = finite ? "coordinate beyond 1e30 (the largest coordinate a case accepts) ("
                            : "non-finite coordinate (";
  for (int axis = 0; axis < 3; ++axis) what += std::to_string(p[axis]) + (axis < 2 ? ", " : ")");
  fail(located("vertex", vertex), what);
}

std::uint64_t FaceKeepingImporter::position() const {
  const auto at = watched_->rdbuf()->pubseekoff(0, std::ios::cur, std::ios::in);
  return at < 0 ? 0 : static_cast<std::uint64_t>(at);
}

// A vertex or face number (from 0) as the reader gives it: with the line the reader is on in a
// watched text file, marked "(from 0)" where no line says which one it is.
std::string FaceKeepingImporter::located(const std::string& kind, std::size_t n) const {
  return kind + " " + std::to_string(n) + (!watched_ ? " (from 0)" : "") +
         (watched_ && text_ ? " (line " + std::to_string(line_at(path_, position())) + ")" : "");
}

std::string FaceKeepingImporter::number(int n) const {
  return std::to_string(n) + (!watched_ ? " (from 0)" : "");
}

// The element a read failed in: the header before reserve() declared the counts, then the
// vertices, then the faces.
std::string FaceKeepingImporter::reading(bool with_line) const {
  const std::string line =
      with_line && text_ ? " (line " + std::to_string(line_at(path_, position())) + ")" : "";
  if (!declared_vertices) return "header" + line;
  if (vertex_open_) return "vertex " + std::to_string(points.size() - 1) + line;
  if (points.size() < *declared_vertices) return "vertex " + std::to_string(points.size()) + line;
  return "face " + std::to_string(faces_read) + line;
}

std::string FaceKeepingImporter::still_declared() const {
  if (!declared_vertices) return "the end of its header";
  if (vertex_open_ || points.size() < *declared_vertices)
    return "the " + std::to_string(*declared_vertices) + " vertices its header declares";
  return "the " + std::to_string(declared_faces.value_or(0)) + " faces its header declares";
}

}  // namespace shadowcts
