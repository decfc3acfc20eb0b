#include "mesh_file_loader.h"

// MeshIO.hh registers OpenMesh's readers with its IOManager.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "openmesh_quiet.h"
#include "shadowcts/closed_surface.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

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

// A vertex coordinate: a number, and no larger than a case accepts.
void check_position_token(const std::string& path, const std::string& token,
                          const std::string& element) {
  check_coordinate_token(path, token, element);
  if (std::fabs(std::strtod(token.c_str(), nullptr)) > max_scene_coordinate) {
    throw InputError(
        path, element,
        "coordinate '" + token + "' is beyond 1e30 (the largest coordinate a case accepts)");
  }
}

// Text formats read byte by byte: UTF-16 (a byte-order mark or NUL bytes) reads as nothing at
// all, which would end as "no faces".
void require_single_byte_text(const std::string& path, const std::string& line,
                              std::size_t line_number) {
  const bool utf16_mark = line.size() >= 2 && ((line[0] == '\xFF' && line[1] == '\xFE') ||
                                               (line[0] == '\xFE' && line[1] == '\xFF'));
  if (line_number == 1 && utf16_mark) {
    throw InputError(path, "line 1",
                     "the file is UTF-16 (byte-order mark); it must be ASCII or UTF-8 text");
  }
  if (line.find('\0') != std::string::npos) {
    throw InputError(path, "line " + std::to_string(line_number),
                     "contains a NUL byte: not ASCII or UTF-8 text (UTF-16?)");
  }
}

std::string vertex_element(std::size_t vertex, std::size_t line) {
  return "vertex " + std::to_string(vertex) + " (line " + std::to_string(line) + ")";
}

// What the text pre-scan learned about the file, for cross-checking what OpenMesh read.
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

  // One face of the file at `element`, by its corners' vertex numbers (as the file numbers
  // them). Fewer than 3 corners is an error (OpenMesh drops the face without a word); fewer than
  // 3 distinct ones make a face OpenMesh drops (it keeps a polygon as the polygon without the
  // repeat), remembered for the messages.
  void face(const std::string& path, const std::string& element, std::vector<long long> corners,
            const char* noun = "vertex") {
    ++faces;
    if (corners.size() < 3) {
      throw InputError(
          path, element,
          "has " + std::to_string(corners.size()) + " corner(s); a face needs at least 3");
    }
    std::sort(corners.begin(), corners.end());
    const auto repeated = std::adjacent_find(corners.begin(), corners.end());
    const auto distinct = std::unique(corners.begin(), corners.end()) - corners.begin();
    if (distinct < 3) {
      ++repeated_vertex_faces;
      if (!first_repeated_vertex) {
        first_repeated_vertex =
            element + " uses " + noun + " " + std::to_string(*repeated) + " more than once";
      }
    }
  }
};

// An OBJ index: an integer, 1-based, or negative to count back from the last element so far.
std::optional<long long> obj_index(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  long long value = 0;
  const auto [rest, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || rest != text.data() + text.size())
    return std::nullopt;
  return value;
}

// A face corner "v", "v/t", "v//n" or "v/t/n": the vertex index, after checking that every part
// is an index (OpenMesh reads "1/a" as vertex 1 and ignores the rest).
long long corner_vertex_index(const std::string& path, const std::string& element,
                              const std::string& corner) {
  std::vector<std::string_view> parts;
  std::string_view text(corner);
  for (std::size_t slash; (slash = text.find('/')) != std::string_view::npos;) {
    parts.push_back(text.substr(0, slash));
    text.remove_prefix(slash + 1);
  }
  parts.push_back(text);
  const auto vertex = obj_index(parts[0]);
  if (!vertex) {
    throw InputError(path, element, "corner '" + corner + "' does not start with a vertex index");
  }
  if (parts.size() > 3) {
    throw InputError(path, element,
                     "corner '" + corner + "' has more than vertex/texture/normal indices");
  }
  static constexpr const char* what[] = {"vertex", "texture", "normal"};
  for (std::size_t i = 1; i < parts.size(); ++i) {
    if (parts[i].empty() && !(i == 1 && parts.size() == 3)) {  // only "v//n" may leave one out
      throw InputError(path, element, "corner '" + corner + "' has an empty " + what[i] + " index");
    }
    if (!parts[i].empty() && (!obj_index(parts[i]) || *obj_index(parts[i]) == 0)) {
      throw InputError(path, element,
                       "corner '" + corner + "': " + what[i] + " index '" + std::string(parts[i]) +
                           "' is not a non-zero integer");
    }
  }
  return *vertex;
}

// OBJ: "v x y z [w]" lines (vertex numbers are 1-based, as in the file); "f" lines give n - 2
// triangles each. Every face corner must be an index of a vertex defined before the face:
// OpenMesh's reader aborts on an assertion for a corner without one ("f /1 2 3", found by the OBJ
// fuzz target) and silently drops faces with indices out of range.
DeclaredCounts scan_obj(const std::string& path, std::istream& in) {
  DeclaredCounts counts{0, 0};
  std::string line;
  std::size_t line_number = 0, face = 0;
  while (std::getline(in, line)) {
    ++line_number;
    require_single_byte_text(path, line, line_number);
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      const std::size_t vertex = ++*counts.vertices;
      const std::string element =
          "v " + std::to_string(vertex) + " (line " + std::to_string(line_number) + ")";
      if (tokens.size() < 4) throw InputError(path, element, "fewer than 3 coordinates");
      for (std::size_t axis = 1; axis <= 3; ++axis)
        check_position_token(path, tokens[axis], element);
    } else if (tokens[0] == "f") {
      const std::string element =
          "f " + std::to_string(++face) + " (line " + std::to_string(line_number) + ")";
      if (tokens.size() < 4) {
        counts.face(path, element, std::vector<long long>(tokens.size() - 1));  // throws
      }
      const auto vertices_so_far = static_cast<long long>(*counts.vertices);
      std::vector<long long> corners;
      for (std::size_t corner = 1; corner < tokens.size(); ++corner) {
        const long long index = corner_vertex_index(path, element, tokens[corner]);
        if (index == 0) {
          throw InputError(path, element, "vertex index 0 (OBJ indices start at 1)");
        }
        if (index < 0 && -index > vertices_so_far) {
          throw InputError(path, element,
                           "relative vertex index " + std::to_string(index) + " reaches before " +
                               "the first vertex (" + std::to_string(vertices_so_far) +
                               " vertices so far)");
        }
        if (index > vertices_so_far) {
          throw InputError(path, element,
                           "vertex index " + std::to_string(index) + " is out of range (" +
                               std::to_string(vertices_so_far) +
                               " vertices so far; a face must come after its vertices)");
        }
        corners.push_back(index < 0 ? vertices_so_far + 1 + index : index);
      }
      counts.face(path, element, corners);
      *counts.triangles += tokens.size() - 3;
    }
  }
  return counts;
}

// A facet's corners numbered by their points: {0, 0, 2} when corners 0 and 1 coincide.
std::vector<long long> same_point_ids(const float (&points)[3][3]) {
  std::vector<long long> ids;
  for (long long c = 0; c < 3; ++c) {
    long long id = c;
    for (long long earlier = 0; earlier < c; ++earlier) {
      if (points[earlier][0] == points[c][0] && points[earlier][1] == points[c][1] &&
          points[earlier][2] == points[c][2]) {
        id = earlier;
        break;
      }
    }
    ids.push_back(id);
  }
  return ids;
}

// True when the first non-blank characters are "solid": how an ASCII STL starts.
bool starts_like_ascii_stl(const char* header, std::size_t size) {
  std::size_t i = 0;
  while (i < size &&
         (header[i] == ' ' || header[i] == '\t' || header[i] == '\r' || header[i] == '\n'))
    ++i;
  return size - i >= 5 && std::memcmp(header + i, "solid", 5) == 0;
}

// What a binary STL's header promises against what the file holds.
std::string binary_stl_size_problem(std::uint32_t facets, std::uintmax_t file_size) {
  const std::uintmax_t needed = 84 + 50 * static_cast<std::uintmax_t>(facets);
  std::string problem = "declares " + std::to_string(facets) + " triangles (84 + 50 x " +
                        std::to_string(facets) + " = " + std::to_string(needed) +
                        " bytes), the file has " + std::to_string(file_size) + " bytes";
  if (file_size >= 84) {
    const std::uintmax_t room = (file_size - 84) / 50;
    problem += " (room for " + std::to_string(room) + (room == 1 ? " triangle" : " triangles") +
               ((file_size - 84) % 50 != 0
                    ? " and " + std::to_string((file_size - 84) % 50) + " stray bytes)"
                    : ")");
  }
  return problem;
}

// ASCII STL: "vertex x y z" lines inside facets; binary STL is detected the way OpenMesh does,
// by its exact size 84 + 50 * facets.
DeclaredCounts scan_stl(const std::string& path, std::istream& in) {
  char header[84] = {};
  in.read(header, sizeof header);
  const auto header_bytes = static_cast<std::size_t>(in.gcount());
  std::error_code error;
  const auto file_size = std::filesystem::file_size(path, error);
  std::uint32_t facets = 0;
  std::memcpy(&facets, header + 80, sizeof facets);
  if (header_bytes == sizeof header && !error) {
    if (file_size == 84 + 50 * static_cast<std::uintmax_t>(facets)) {
      // Binary: OpenMesh silently drops facets with NaN corners, so they are named here.
      char facet[50];
      DeclaredCounts counts(std::nullopt, facets);
      for (std::uint32_t f = 0; f < facets && in.read(facet, sizeof facet); ++f) {
        float points[3][3];
        std::memcpy(points, facet + 12, sizeof points);
        counts.face(path, "facet " + std::to_string(f), same_point_ids(points),
                    "the point of corner");
        for (std::size_t corner = 0; corner < 3; ++corner) {
          const float(&xyz)[3] = points[corner];
          const std::string element =
              "facet " + std::to_string(f) + " vertex " + std::to_string(corner);
          if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
            throw InputError(path, element, "non-finite coordinate");
          }
          for (const float v : xyz) {
            if (std::fabs(v) > max_scene_coordinate) {
              throw InputError(path, element,
                               "coordinate " + std::to_string(v) +
                                   " is beyond 1e30 (the largest coordinate a case accepts)");
            }
          }
        }
      }
      return counts;
    }
  }
  if (!error && !starts_like_ascii_stl(header, header_bytes)) {
    // Not "solid ...": a binary STL whose size does not match its count. OpenMesh would read it
    // as text and find nothing ("no faces").
    throw InputError(path, header_bytes < sizeof header ? "file" : "binary STL header",
                     header_bytes < sizeof header
                         ? "not an ASCII STL (no 'solid') and shorter than a binary STL header "
                           "(84 bytes, the file has " +
                               std::to_string(file_size) + ")"
                         : binary_stl_size_problem(facets, file_size));
  }
  in.clear();
  in.seekg(0);
  DeclaredCounts counts{std::nullopt, 0};
  std::string line;
  std::size_t line_number = 0, vertex = 0;
  float points[3][3] = {};
  // OpenMesh's reader takes the 3 lines after any line containing "outer" (or "OUTER") as the
  // facet's corners, each a word and 3 coordinates, whatever the word is. A corner line without
  // them leaves the reader's point uninitialized (garbage coordinates that differ from run to
  // run, found by replaying mutated seeds), so each of those lines must hold them.
  std::size_t corner_lines_left = 0, loops = 0, loop_line = 0;
  const auto loop_element = [&] {
    return "facet " + std::to_string(loops - 1) + " (line " + std::to_string(loop_line) + ")";
  };
  while (std::getline(in, line)) {
    ++line_number;
    const auto tokens = split_whitespace(line);
    if (corner_lines_left > 0) {
      const std::size_t corner = 3 - corner_lines_left--;
      if (tokens.size() < 4) {
        throw InputError(path, loop_element(),
                         "corner " + std::to_string(corner) + " (line " +
                             std::to_string(line_number) +
                             ") is not 'vertex x y z': the 3 lines after 'outer loop' are the "
                             "facet's corners");
      }
      for (std::size_t axis = 1; axis <= 3; ++axis)
        check_position_token(path, tokens[axis], vertex_element(vertex, line_number));
    } else if (line.find("outer") != std::string::npos || line.find("OUTER") != std::string::npos) {
      corner_lines_left = 3;
      ++loops;
      loop_line = line_number;
    }
    if (tokens.empty()) continue;
    const std::string keyword = lowercase(tokens[0]);
    if (keyword == "facet") ++*counts.triangles;
    if (keyword != "vertex") continue;
    const std::string element = vertex_element(vertex++, line_number);
    if (tokens.size() < 4) throw InputError(path, element, "fewer than 3 coordinates");
    for (std::size_t axis = 1; axis <= 3; ++axis) {
      check_position_token(path, tokens[axis], element);
      points[(vertex - 1) % 3][axis - 1] = std::strtof(tokens[axis].c_str(), nullptr);
    }
    if (vertex % 3 == 0) {
      counts.face(path,
                  "facet " + std::to_string(vertex / 3 - 1) + " (line " +
                      std::to_string(line_number - 2) + ")",
                  same_point_ids(points), "the point of corner");
    }
  }
  if (corner_lines_left > 0) {
    throw InputError(path, loop_element(),
                     "the file ends before the facet's 3 corners (the 3 lines after 'outer loop')");
  }
  if (*counts.triangles == 0 && header_bytes == sizeof header && !error) {
    // Binary STLs often start with "solid" too.
    throw InputError(path, "file",
                     "no 'facet' in it as ASCII STL, and as binary STL its header " +
                         binary_stl_size_problem(facets, file_size));
  }
  return counts;
}

// ---- OFF and PLY: the file is walked the way OpenMesh's reader walks it, before OpenMesh sees
// it. OpenMesh trusts the declared counts (it reserves memory for them and loops over them even
// past the end of the file) and checks its stream only for hard I/O errors, so a count that
// does not parse, or one larger than the file, makes it allocate gigabytes or loop forever (both
// found by the fuzz targets). Every value is therefore checked here with the same token
// boundaries as OpenMesh's `stream >> value`, and a file is handed to OpenMesh only when each
// of its reads will succeed on what was checked.

// Whitespace-separated tokens, as `stream >> value` reads them (the C locale's whitespace), with
// the line each one is on.
class TokenReader {
 public:
  TokenReader(std::istream& in, std::size_t line) : in_(in), line_(line) {}

  // The next token, or nullopt at the end of the file.
  std::optional<std::string> next() {
    int c = in_.get();
    while (c != std::char_traits<char>::eof() && std::isspace(c)) {
      if (c == '\n') ++line_;
      c = in_.get();
    }
    if (c == std::char_traits<char>::eof()) return std::nullopt;
    token_line_ = line_;
    std::string token;
    while (c != std::char_traits<char>::eof() && !std::isspace(c)) {
      token.push_back(static_cast<char>(c));
      c = in_.get();
    }
    if (c != std::char_traits<char>::eof()) in_.unget();  // `>>` leaves the separator
    return token;
  }

  // What std::getline does: the rest of the current line, newline included.
  void skip_rest_of_line() {
    int c = in_.get();
    while (c != std::char_traits<char>::eof() && c != '\n') c = in_.get();
    if (c == '\n') ++line_;
  }

  // The line of the last token next() returned.
  std::size_t line() const { return token_line_; }
  std::string at_line() const { return " (line " + std::to_string(token_line_) + ")"; }

 private:
  std::istream& in_;
  std::size_t line_;
  std::size_t token_line_ = 0;
};

// Bytes from the stream's position to the end of the file (0 once the stream has failed).
std::uint64_t bytes_left(std::istream& in, std::uintmax_t file_size) {
  const auto position = in.tellg();
  if (position < 0 || static_cast<std::uintmax_t>(position) > file_size) return 0;
  return file_size - static_cast<std::uintmax_t>(position);
}

// A count or index as `stream >> unsigned` reads it, restricted to plain digits (it would also
// take a sign and wrap "-1" to 4294967295).
std::optional<std::uint32_t> parse_u32(const std::string& token) {
  std::uint32_t value = 0;
  const auto [rest, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || rest != token.data() + token.size())
    return std::nullopt;
  return value;
}

bool is_int32(const std::string& token) {
  std::string_view text(token);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  std::int32_t value = 0;
  const auto [rest, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc() && rest == text.data() + text.size();
}

// The next token, or an InputError saying which element the file ends in.
std::string required_token(const std::string& path, TokenReader& tokens, const std::string& element,
                           const std::string& what) {
  auto token = tokens.next();
  if (!token) throw InputError(path, element, "file ends before " + what);
  return *token;
}

std::uint32_t required_u32(const std::string& path, TokenReader& tokens, const std::string& element,
                           const std::string& what) {
  const std::string token = required_token(path, tokens, element, "the " + what);
  const auto value = parse_u32(token);
  if (!value) {
    const std::string shown = token.size() > 24 ? token.substr(0, 24) + "..." : token;
    throw InputError(path, element + tokens.at_line(),
                     "the " + what + " '" + shown + "' is not a whole number from 0 to 4294967295");
  }
  return *value;
}

// Little- or big-endian unsigned integer of `bytes` bytes, or nullopt at the end of the file.
std::optional<std::uint32_t> read_binary_u32(std::istream& in, int bytes, bool big_endian) {
  unsigned char raw[4] = {};
  if (!in.read(reinterpret_cast<char*>(raw), bytes)) return std::nullopt;
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    const int shift = 8 * (big_endian ? bytes - 1 - i : i);
    value |= std::uint32_t(raw[i]) << shift;
  }
  return value;
}

std::string too_large(std::uint64_t needed, std::uint64_t available) {
  return "needs at least " + std::to_string(needed) + " bytes, but only " +
         std::to_string(available) + " follow the header";
}

// -- OFF ----------------------------------------------------------------------------------------

struct OffKeyword {
  bool readable = false;  // OpenMesh's reader accepts it (3D only)
  bool binary = false;
  bool normals = false, colors = false, texcoords = false;
};

// The first line as OpenMesh's OFF reader decodes it: [ST][C][N][4][n]OFF, then "BINARY" after
// exactly one character. It looks at no more than 4095 characters.
OffKeyword off_keyword(const std::string& first_line, bool had_newline) {
  OffKeyword keyword;
  std::string line = first_line.substr(0, 4095);
  // Characters OpenMesh counts: the line, and the newline when there was one.
  std::size_t remaining = line.size() + (had_newline && first_line.size() < 4095 ? 1 : 0);
  line.append(16, '\0');
  std::size_t p = 0;
  auto take = [&](char c) {
    if (remaining == 0 || line[p] != c) return false;
    ++p;
    --remaining;
    return true;
  };
  if (remaining > 1 && line[0] == 'S' && line[1] == 'T') {
    keyword.texcoords = true;
    p = 2;
    remaining -= 2;
  }
  keyword.colors = take('C');
  keyword.normals = take('N');
  const bool four_dimensional = take('4');
  const bool n_dimensional = take('n');
  if (remaining < 3 || line.compare(p, 3, "OFF") != 0) return keyword;
  p += 4;
  remaining = remaining >= 4 ? remaining - 4 : 0;
  keyword.binary = remaining >= 6 && line.compare(p, 6, "BINARY") == 0;
  keyword.readable = !four_dimensional && !n_dimensional;
  return keyword;
}

// Binary OFF: little-endian 32-bit counts, vertices of 3 floats (+ 3 normal floats, 3 colour
// integers, 2 texture floats as the keyword says), faces as a count and that many indices.
DeclaredCounts scan_binary_off(const std::string& path, std::istream& in, const OffKeyword& keyword,
                               std::uintmax_t file_size) {
  std::uint32_t header[3];
  for (std::uint32_t& value : header) {
    const auto read = read_binary_u32(in, 4, false);
    if (!read)
      throw InputError(path, "header", "file ends before the vertex, face and edge counts");
    value = *read;
  }
  const std::uint32_t vertices = header[0], faces = header[1];
  const std::uint64_t vertex_bytes =
      12 + (keyword.normals ? 12 : 0) + (keyword.colors ? 12 : 0) + (keyword.texcoords ? 8 : 0);
  const std::uint64_t needed = vertices * vertex_bytes + std::uint64_t(faces) * 4;
  const std::uint64_t available = bytes_left(in, file_size);
  if (needed > available) {
    throw InputError(path, "header",
                     "declares " + std::to_string(vertices) + " vertices and " +
                         std::to_string(faces) + " faces, which " + too_large(needed, available));
  }
  for (std::uint32_t vertex = 0; vertex < vertices; ++vertex) {
    float xyz[3];
    in.read(reinterpret_cast<char*>(xyz), sizeof xyz);
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      throw InputError(path, "vertex " + std::to_string(vertex), "non-finite coordinate");
    in.ignore(static_cast<std::streamsize>(vertex_bytes - sizeof xyz));
  }
  DeclaredCounts counts;
  std::size_t triangles = 0;
  for (std::uint32_t face = 0; face < faces; ++face) {
    const std::string element = "face " + std::to_string(face);
    const auto corners = read_binary_u32(in, 4, false);
    if (!corners) {
      throw InputError(
          path, element,
          "file ends before the " + std::to_string(faces) + " faces its header declares");
    }
    const std::uint64_t left = bytes_left(in, file_size);
    if (std::uint64_t(*corners) * 4 > left) {
      throw InputError(path, element,
                       std::to_string(*corners) + " vertex indices need " +
                           std::to_string(std::uint64_t(*corners) * 4) + " bytes, only " +
                           std::to_string(left) + " are left");
    }
    std::vector<long long> indices;
    for (std::uint32_t corner = 0; corner < *corners; ++corner) {
      const std::uint32_t index = *read_binary_u32(in, 4, false);
      if (index >= vertices) {
        throw InputError(path, element,
                         "vertex index " + std::to_string(index) + " is out of range (" +
                             std::to_string(vertices) + " vertices)");
      }
      indices.push_back(index);
    }
    counts.face(path, element, std::move(indices));
    triangles += *corners - 2;
  }
  counts.vertices = vertices;
  counts.triangles = triangles;
  return counts;
}

// OFF: the keyword line, counts "vertices faces edges", vertices (3 coordinates, 3 more with N,
// the rest of the line is colour and texture), faces (a count, then that many indices, then
// with C the rest of the line).
DeclaredCounts scan_off(const std::string& path, std::istream& in) {
  std::error_code size_error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, size_error);
  std::string first_line;
  if (size_error || !std::getline(in, first_line)) return {};  // OpenMesh reports it
  const OffKeyword keyword = off_keyword(first_line, !in.eof());
  if (!keyword.readable) return {};  // not an OFF file OpenMesh can read: it says so
  if (keyword.binary) return scan_binary_off(path, in, keyword, file_size);
  const auto keyword_tokens = split_whitespace(first_line);
  if (keyword_tokens.size() > 1) {
    throw InputError(path, "line 1",
                     "text after the OFF keyword: the counts must be on the next line (the reader "
                     "skips the rest of the keyword line)");
  }

  TokenReader tokens(in, 2);
  const std::string header = "header";
  const std::uint32_t vertices = required_u32(path, tokens, header, "vertex count");
  const std::uint32_t faces = required_u32(path, tokens, header, "face count");
  required_u32(path, tokens, header, "edge count");
  // Every number takes at least one character and a separator (the last one may end the file):
  // counts the rest of the file cannot hold are refused before anything is read.
  const std::uint64_t room = bytes_left(in, file_size) + 1;
  const std::uint64_t vertex_room = 2 * (keyword.normals ? 6 : 3);
  if (vertices > room / vertex_room) {
    throw InputError(path, "vertex " + std::to_string(room / vertex_room),
                     "the file ends before the " + std::to_string(vertices) +
                         " vertices its header declares (the " + std::to_string(room - 1) +
                         " bytes after the counts hold at most " +
                         std::to_string(room / vertex_room) + ")");
  }
  const std::uint64_t face_room = (room - vertices * vertex_room) / 2;
  if (faces > face_room) {
    throw InputError(path, "face " + std::to_string(face_room),
                     "the file ends before the " + std::to_string(faces) +
                         " faces its header declares (the bytes after the vertices hold at most " +
                         std::to_string(face_room) + ")");
  }

  for (std::uint32_t vertex = 0; vertex < vertices; ++vertex) {
    const std::string element = "vertex " + std::to_string(vertex);
    const std::string what = "the " + std::to_string(vertices) + " vertices its header declares";
    for (int axis = 0; axis < (keyword.normals ? 6 : 3); ++axis) {
      const std::string token = required_token(path, tokens, element, what);
      if (axis < 3) {
        check_position_token(path, token, element + tokens.at_line());
      } else {
        check_coordinate_token(path, token, element + tokens.at_line());
      }
    }
    tokens.skip_rest_of_line();
  }
  DeclaredCounts counts;
  std::size_t triangles = 0;
  for (std::uint32_t face = 0; face < faces; ++face) {
    const std::string element = "face " + std::to_string(face);
    const std::string what = "the " + std::to_string(faces) + " faces its header declares";
    const std::string count = required_token(path, tokens, element, what);
    const std::string located = element + tokens.at_line();
    const auto corners = parse_u32(count);
    if (!corners) {
      throw InputError(path, located, "malformed face (vertex count, then that many indices)");
    }
    std::vector<long long> indices;
    for (std::uint32_t corner = 0; corner < *corners; ++corner) {
      const std::string token = required_token(path, tokens, located, what);
      const auto index = parse_u32(token);
      if (!index || *index >= vertices) {
        throw InputError(path, located,
                         "vertex index '" + token + "' is out of range (" +
                             std::to_string(vertices) + " vertices)");
      }
      indices.push_back(*index);
    }
    counts.face(path, located, std::move(indices));
    if (keyword.colors) tokens.skip_rest_of_line();
    triangles += *corners - 2;
  }
  counts.vertices = vertices;
  counts.triangles = triangles;
  return counts;
}

// -- PLY ----------------------------------------------------------------------------------------

enum class PlyType { unknown, int8, uint8, int16, uint16, int32, uint32, float32, float64 };

// The type names OpenMesh knows, in the order it tries them when a property line names two.
constexpr std::pair<std::string_view, PlyType> ply_type_names[] = {
    {"float32", PlyType::float32}, {"float64", PlyType::float64}, {"float", PlyType::float32},
    {"double", PlyType::float64},  {"int8", PlyType::int8},       {"uint8", PlyType::uint8},
    {"char", PlyType::int8},       {"uchar", PlyType::uint8},     {"int32", PlyType::int32},
    {"uint32", PlyType::uint32},   {"int", PlyType::int32},       {"uint", PlyType::uint32},
    {"int16", PlyType::int16},     {"uint16", PlyType::uint16},   {"short", PlyType::int16},
    {"ushort", PlyType::uint16}};

PlyType ply_type(const std::string& name) {
  for (const auto& [type_name, type] : ply_type_names)
    if (name == type_name) return type;
  return PlyType::unknown;
}

int ply_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::float64:
      return 8;
    case PlyType::unknown:
      return 0;
    default:
      return 4;
  }
}

// The 1- and 4-byte integers OpenMesh's binary reader can read as indices and colours.
bool ply_byte_or_word(PlyType type) {
  return type == PlyType::int8 || type == PlyType::uint8 || type == PlyType::int32 ||
         type == PlyType::uint32;
}

enum class PlyRole {
  coordinate,   // vertex x, y, z: read as float
  float_value,  // vertex normal and texture coordinate: read as float
  color,        // read as float or as an integer
  vertex_list,  // the face's vertex_indices
  skipped,      // anything else: read and dropped
};

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::unknown;  // the entries' type for a list
  PlyType count_type = PlyType::unknown;
  bool list = false;
  PlyRole role = PlyRole::skipped;
};

struct PlyElement {
  std::string name;
  std::uint32_t count = 0;
  std::string located;  // "element 'face' (line 8)"
  std::vector<PlyProperty> properties;
};

PlyRole ply_role(const std::string& element, const std::string& property) {
  const auto is = [&](std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(),
                       [&](const char* name) { return property == name; });
  };
  if (element == "vertex") {
    if (is({"x", "y", "z"})) return PlyRole::coordinate;
    if (is({"nx", "ny", "nz", "u", "s", "v", "t"})) return PlyRole::float_value;
    if (is({"red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"}))
      return PlyRole::color;
  }
  if (element == "face" && is({"red", "green", "blue", "alpha"})) return PlyRole::color;
  return PlyRole::skipped;
}

struct PlyHeader {
  bool binary = false, big_endian = false;
  std::vector<PlyElement> elements;
  std::uint64_t body_start = 0;            // binary: where OpenMesh starts reading the data
  std::vector<std::string> skipped_words;  // header words the reader does not know, once each
};

// One "property ..." line after its keyword, with the rules of OpenMesh's reader and the shapes
// it reads wrongly refused.
PlyProperty read_ply_property(const std::string& path, TokenReader& tokens, PlyElement& element,
                              bool binary) {
  const std::string end = "the end_header line";
  PlyProperty property;
  const std::string first = required_token(path, tokens, "header", end);
  const std::string located = "header" + tokens.at_line();
  if (first == "list") {
    const std::string count_type = required_token(path, tokens, "header", end);
    const std::string entry_type = required_token(path, tokens, "header", end);
    property.name = required_token(path, tokens, "header", end);
    property.list = true;
    property.count_type = ply_type(count_type);
    property.type = ply_type(entry_type);
    if (count_type != "uint8" && count_type != "uchar" && count_type != "uint16" &&
        count_type != "int") {
      throw InputError(
          path, located,
          "list count type '" + count_type + "' is not supported (uint8, uchar, uint16 or int)");
    }
    if (element.name != "face" ||
        (property.name != "vertex_indices" && property.name != "vertex_index")) {
      throw InputError(path, located,
                       "list property '" + property.name +
                           "' is not supported: only the face element's vertex_indices is read");
    }
    if (!element.properties.empty()) {
      throw InputError(path, located,
                       "face property '" + element.properties.front().name +
                           "' before vertex_indices is not supported (the reader drops it)");
    }
    if (property.type == PlyType::unknown || property.type == PlyType::float32 ||
        property.type == PlyType::float64) {
      throw InputError(path, located, "vertex index type '" + entry_type + "' is not an integer");
    }
    if (binary && (count_type == "uint16" || !ply_byte_or_word(property.type))) {
      throw InputError(path, located,
                       "binary vertex lists need a uint8, uchar or int count and 8- or 32-bit "
                       "indices");
    }
    property.role = PlyRole::vertex_list;
    return property;
  }
  const std::string second = required_token(path, tokens, "header", end);
  // OpenMesh takes the type from whichever word is one, in its own order of names.
  for (const auto& [type_name, type] : ply_type_names) {
    if (first == type_name || second == type_name) {
      property.type = type;
      break;
    }
  }
  property.name = ply_type(first) != PlyType::unknown ? second : first;
  if (property.type == PlyType::unknown ||
      (ply_type(first) == PlyType::unknown && ply_type(second) == PlyType::unknown)) {
    throw InputError(path, located, "property '" + first + " " + second + "' has no known type");
  }
  property.role = ply_role(element.name, property.name);
  if (binary && (property.role == PlyRole::coordinate || property.role == PlyRole::float_value) &&
      property.type != PlyType::float32) {
    throw InputError(path, located,
                     "binary vertex property '" + property.name +
                         "' must be float (the reader reads no other type for it)");
  }
  if (binary && property.role == PlyRole::color && property.type != PlyType::float32 &&
      !ply_byte_or_word(property.type)) {
    throw InputError(
        path, located,
        "binary colour property '" + property.name + "' must be float or an 8- or 32-bit integer");
  }
  return property;
}

// The header, token by token as OpenMesh reads it. OpenMesh loops forever when its stream fails
// before end_header (a count that does not parse, the end of the file): every read is checked.
PlyHeader read_ply_header(const std::string& path, std::istream& in, TokenReader& tokens) {
  PlyHeader header;
  const std::string end = "the end_header line";
  const std::string format = required_token(path, tokens, "header", end);
  const std::string format_line = tokens.at_line();
  const std::string encoding = required_token(path, tokens, "header", end);
  const std::string version = required_token(path, tokens, "header", end);
  if (format != "format") {
    throw InputError(path, "header" + format_line,
                     "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
  }
  if (encoding != "ascii" && encoding != "binary_little_endian" &&
      encoding != "binary_big_endian") {
    throw InputError(path, "header" + format_line, "unsupported PLY format '" + encoding + "'");
  }
  check_coordinate_token(path, version, "format version" + format_line);
  header.binary = encoding != "ascii";
  header.big_endian = encoding == "binary_big_endian";

  std::set<std::string> seen;
  for (;;) {
    const auto before_keyword = in.tellg();
    const auto keyword = tokens.next();
    // OpenMesh's reader loops forever on a header without end_header: refuse it here.
    if (!keyword) throw InputError(path, "header", "the PLY header has no end_header line");
    if (*keyword == "end_header") {
      if (header.binary) {
        // OpenMesh seeks to 12 (or, after "\r\n", 14) bytes past where this token's leading
        // whitespace began: the data it reads start there.
        in.seekg(before_keyword);
        char c[2] = {};
        in.read(c, 2);
        header.body_start =
            static_cast<std::uint64_t>(before_keyword) + (c[0] == '\r' && c[1] == '\n' ? 14 : 12);
        in.clear();
      }
      break;
    }
    if (*keyword == "comment") {
      tokens.skip_rest_of_line();
    } else if (*keyword == "element") {
      PlyElement element;
      element.name = required_token(path, tokens, "header", end);
      element.located = "element '" + element.name + "'" + tokens.at_line();
      element.count = required_u32(path, tokens, "element '" + element.name + "'", "element count");
      if ((element.name == "vertex" || element.name == "face") && !seen.insert(element.name).second)
        throw InputError(path, element.located, "a second '" + element.name + "' element");
      if (element.name == "face" && !seen.count("vertex"))
        throw InputError(path, element.located, "the face element comes before the vertex element");
      header.elements.push_back(std::move(element));
    } else if (*keyword == "property") {
      if (header.elements.empty()) {
        throw InputError(path, "header" + tokens.at_line(), "property before any element");
      }
      PlyElement& element = header.elements.back();
      element.properties.push_back(read_ply_property(path, tokens, element, header.binary));
    } else if (std::find(header.skipped_words.begin(), header.skipped_words.end(), *keyword) ==
               header.skipped_words.end()) {
      // Any other word is skipped, as OpenMesh does ("obj_info", free text), and reported.
      header.skipped_words.push_back(*keyword);
    }
  }
  return header;
}

// PLY: the header declares the elements; the data are walked the way OpenMesh reads them (up to
// the end of the face element, where it stops), so that no count, list length or index it reads
// is out of range.
DeclaredCounts scan_ply(const std::string& path, std::istream& in) {
  std::error_code size_error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, size_error);
  if (size_error) return {};
  std::string first_line;
  std::getline(in, first_line);
  const auto first = split_whitespace(first_line);
  if (first.size() != 1 || (first[0] != "ply" && first[0] != "PLY"))
    throw InputError(path, "line 1", "not a PLY file (the first line is not 'ply')");
  TokenReader tokens(in, 2);
  const PlyHeader header = read_ply_header(path, in, tokens);
  const PlyElement* vertex_element = nullptr;
  for (const PlyElement& element : header.elements)
    if (element.name == "vertex") vertex_element = &element;
  for (const char* axis : {"x", "y", "z"}) {
    const auto named = [&](const PlyProperty& p) { return p.name == axis; };
    const auto count = vertex_element ? std::count_if(vertex_element->properties.begin(),
                                                      vertex_element->properties.end(), named)
                                      : 0;
    if (count != 1) {
      throw InputError(path, "header",
                       std::string("vertex element has ") + (count == 0 ? "no" : "more than one") +
                           " property " + axis);
    }
  }
  const std::uint32_t vertices = vertex_element->count;

  // Caps by the file size, before anything is read: each value takes at least its size (binary)
  // or one character and a separator (text; the last one may end the file).
  const std::uint64_t available =
      header.binary ? (header.body_start <= file_size ? file_size - header.body_start : 0)
                    : bytes_left(in, file_size) + 1;
  std::uint64_t needed = 0;
  for (const PlyElement& element : header.elements) {
    std::uint64_t per_instance = 0;
    for (const PlyProperty& p : element.properties)
      per_instance += header.binary ? ply_size(p.list ? p.count_type : p.type) : 2;
    const std::uint64_t bytes =
        std::uint64_t(element.count) * std::max<std::uint64_t>(1, per_instance);
    if (bytes > available) {
      throw InputError(path, element.located,
                       "declares " + std::to_string(element.count) + " instances, which " +
                           too_large(bytes, available));
    }
    needed += bytes;
  }
  if (needed > available) {
    throw InputError(path, "header", "the declared elements " + too_large(needed, available));
  }

  if (header.binary) in.seekg(static_cast<std::streamoff>(header.body_start));
  DeclaredCounts counts;
  for (const PlyElement& element : header.elements) {
    const std::string what = "the " + std::to_string(element.count) + " '" + element.name +
                             "' elements its header declares";
    for (std::uint32_t i = 0; i < element.count; ++i) {
      const std::string element_i = element.name + " " + std::to_string(i);
      for (const PlyProperty& p : element.properties) {
        if (!header.binary) {
          const std::string token = required_token(path, tokens, element_i, what);
          const std::string located = element_i + tokens.at_line();
          if (p.role == PlyRole::coordinate) {
            check_position_token(path, token, located);
          } else if (p.role == PlyRole::float_value ||
                     (p.role == PlyRole::color && p.type == PlyType::float32)) {
            check_coordinate_token(path, token, located);
          } else if (p.role == PlyRole::color && !is_int32(token)) {
            throw InputError(path, located, "colour '" + token + "' is not an integer");
          } else if (p.role == PlyRole::vertex_list) {
            const auto corners = parse_u32(token);
            if (!corners)
              throw InputError(path, located, "vertex count '" + token + "' is not a number");
            std::vector<long long> indices;
            for (std::uint32_t corner = 0; corner < *corners; ++corner) {
              const std::string index = required_token(path, tokens, located, what);
              const auto value = parse_u32(index);
              if (!value || *value >= vertices) {
                throw InputError(path, located,
                                 "vertex index '" + index + "' is out of range (" +
                                     std::to_string(vertices) + " vertices)");
              }
              indices.push_back(*value);
            }
            counts.face(path, located, std::move(indices));
          }
          continue;
        }
        const std::string& located = element_i;
        if (p.role == PlyRole::vertex_list) {
          const auto corners = read_binary_u32(in, ply_size(p.count_type), header.big_endian);
          if (!corners) throw InputError(path, located, "file ends before " + what);
          // An int count is read as signed and converted: -1 becomes 4294967295.
          std::uint32_t n = *corners;
          if (p.count_type == PlyType::int32) n = std::uint32_t(std::int32_t(n));
          const std::uint64_t bytes = std::uint64_t(n) * ply_size(p.type);
          const std::uint64_t left = bytes_left(in, file_size);
          if (bytes > left) {
            throw InputError(path, located,
                             std::to_string(n) + " vertex indices need " + std::to_string(bytes) +
                                 " bytes, only " + std::to_string(left) + " are left");
          }
          std::vector<long long> indices;
          for (std::uint32_t corner = 0; corner < n; ++corner) {
            std::uint32_t index = *read_binary_u32(in, ply_size(p.type), header.big_endian);
            if (p.type == PlyType::int8) index = std::uint32_t(std::int32_t(std::int8_t(index)));
            if (index >= vertices) {
              throw InputError(path, located,
                               "vertex index " + std::to_string(index) + " is out of range (" +
                                   std::to_string(vertices) + " vertices)");
            }
            indices.push_back(index);
          }
          counts.face(path, located, std::move(indices));
          continue;
        }
        if (!in.ignore(ply_size(p.type)) || in.gcount() != ply_size(p.type))
          throw InputError(path, located, "file ends before " + what);
      }
    }
    if (element.name == "face") break;  // OpenMesh reads nothing after the faces
  }
  counts.vertices = vertices;
  counts.skipped_words = header.skipped_words;
  return counts;
}

// The words of a list, quoted, the first four of them.
std::string quoted_list(const std::vector<std::string>& words) {
  std::string list;
  for (std::size_t i = 0; i < words.size() && i < 4; ++i)
    list += (list.empty() ? "'" : ", '") + words[i] + "'";
  if (words.size() > 4) list += ", ... (" + std::to_string(words.size()) + " words)";
  return list;
}

// What OpenMesh's reader reads, received as it reads it: every vertex, and every face with its
// corners as the file gives them. Nothing goes through OpenMesh's mesh topology, so a face that a
// PolyMesh would reject (a complex edge or vertex: three faces on an edge, inconsistent
// orientation) is kept as it is; a conformance suite must not change its input. Faces that name
// a vertex more than once have no area: they are counted and dropped (the pre-checks name the
// first one with its line). Problems are recorded, not thrown, so that no exception crosses
// OpenMesh's reader; the first one is reported once the reader returns.
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
  std::optional<std::string> first_repeated_vertex;  // "face 3 (from 0) uses vertex 1 (from 0) ..."
  std::optional<std::pair<std::string, std::string>> problem;  // element, what is wrong

  // Fan triangulation (corner 0, i, i + 1), as OpenMesh's TriMesh splits a polygon.
  std::vector<Triangle> triangles() const {
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

  VertexHandle add_vertex(const Point& point) override {
    points.push_back(point);
    return VertexHandle(static_cast<int>(points.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(Point(0.0f, 0.0f, 0.0f)); }
  void set_point(VertexHandle vertex, const Point& point) override {
    if (valid(vertex)) points[static_cast<std::size_t>(vertex.idx())] = point;
  }

  FaceHandle add_face(const VHandles& indices) override {
    // Faces and vertices as the reader numbers them: from 0, in the order it hands them over.
    const std::string element = "face " + std::to_string(faces_read++) + " (from 0)";
    if (indices.size() < 3) {
      fail(element,
           "has " + std::to_string(indices.size()) + " corner(s); a face needs at least 3");
      return FaceHandle();
    }
    for (const VertexHandle vertex : indices) {
      if (!valid(vertex)) {
        fail(element, "vertex index " + std::to_string(vertex.idx()) +
                          " (from 0) is out of range (" + std::to_string(points.size()) +
                          " vertices read)");
        return FaceHandle();
      }
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
      for (std::size_t j = i + 1; j < indices.size(); ++j) {
        if (indices[i] != indices[j]) continue;
        ++repeated_vertex_faces;
        repeated_vertex_triangles += indices.size() - 2;
        if (!first_repeated_vertex) {
          first_repeated_vertex = element + " uses vertex " + std::to_string(indices[i].idx()) +
                                  " (from 0) more than once";
        }
        return FaceHandle();
      }
    }
    for (const VertexHandle vertex : indices)
      corners.push_back(static_cast<std::uint32_t>(vertex.idx()));
    face_corners.push_back(static_cast<std::uint32_t>(indices.size()));
    return FaceHandle(static_cast<int>(face_corners.size() - 1));
  }
  // Only OpenMesh's own .om format builds faces from halfedges; the loader does not read it.
  FaceHandle add_face(HalfedgeHandle) override {
    fail("face " + std::to_string(faces_read++), "given as halfedges, which is not supported");
    return FaceHandle();
  }
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }

  // Like OpenMesh's importer for its TriMesh, so that each reader takes the path it took before.
  bool is_triangle_mesh() const override { return true; }
  // The declared counts are not trusted with memory: nothing is reserved.
  void reserve(unsigned int, unsigned int, unsigned int) override {}
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
  bool valid(VertexHandle vertex) const {
    return vertex.idx() >= 0 && static_cast<std::size_t>(vertex.idx()) < points.size();
  }
  void fail(const std::string& element, std::string what) {
    if (!problem) problem.emplace(element, std::move(what));
  }
};

}  // namespace

LoadedScene load_mesh_file(const std::string& path) {
  const std::filesystem::path file(path);
  const std::string format = lowercase(file.extension().string());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");

  // Pre-checks: what OpenMesh's readers would hang on, over-allocate for, crash on, or silently
  // read as something else (an unparsable coordinate, an index out of range) is named here, with
  // its element and line.
  DeclaredCounts declared;
  if (format == ".obj") declared = scan_obj(path, in);
  if (format == ".stl") declared = scan_stl(path, in);
  if (format == ".off") declared = scan_off(path, in);
  if (format == ".ply") declared = scan_ply(path, in);
  in.close();

  FaceKeepingImporter importer;
  bool read_ok = false;
  {
    const OpenMeshQuiet quiet;
    OpenMesh::IO::Options options;
    try {
      read_ok = OpenMesh::IO::IOManager().read(path, importer, options);
    } catch (const std::exception& e) {
      throw InputError(path, "file", std::string("OpenMesh failed: ") + e.what());
    }
  }
  if (importer.problem) throw InputError(path, importer.problem->first, importer.problem->second);
  if (!read_ok) throw InputError(path, "file", "OpenMesh cannot read it as a " + format + " file");
  // Faces that repeat a corner: some readers drop them before the importer sees them (OBJ, STL),
  // the others hand them over. The pre-checks count and name them with their lines either way.
  const std::size_t repeated_vertex_faces =
      std::max(importer.repeated_vertex_faces, declared.repeated_vertex_faces);
  const std::optional<std::string> first_repeated_vertex = declared.first_repeated_vertex
                                                               ? declared.first_repeated_vertex
                                                               : importer.first_repeated_vertex;
  if (importer.face_corners.empty()) {
    // OpenMesh "loads" an invalid file as an empty mesh: empty is an error.
    const std::size_t faces = std::max(importer.faces_read, declared.faces);
    if (faces > 0 && repeated_vertex_faces == faces) {
      throw InputError(path, "faces",
                       "every face (" + std::to_string(faces) +
                           ") repeats a vertex, so none has area (first: " +
                           first_repeated_vertex.value_or("?") + ")");
    }
    throw InputError(path, "faces", "no faces: empty, or not a valid " + format + " file");
  }
  if (declared.vertices && importer.points.size() < *declared.vertices) {
    throw InputError(path, "vertices",
                     "the file declares " + std::to_string(*declared.vertices) +
                         " vertices, OpenMesh read " + std::to_string(importer.points.size()));
  }

  LoadedScene scene;
  scene.triangles = importer.triangles();
  if (repeated_vertex_faces > 0) {
    scene.warnings.push_back(path + ": faces: " + std::to_string(repeated_vertex_faces) +
                             " face(s) with a repeated vertex dropped (no area, no shadow)" +
                             (first_repeated_vertex ? "; first: " + *first_repeated_vertex : ""));
  }
  const std::size_t dropped_triangles =
      std::max(importer.repeated_vertex_triangles, declared.repeated_vertex_faces);
  if (declared.triangles && scene.triangles.size() + dropped_triangles < *declared.triangles) {
    scene.warnings.push_back(path + ": faces: the file has " + std::to_string(*declared.triangles) +
                             " triangles, OpenMesh read " + std::to_string(scene.triangles.size()));
  }
  if (!declared.skipped_words.empty()) {
    scene.warnings.push_back(path + ": header: words the reader does not know, skipped: " +
                             quoted_list(declared.skipped_words));
  }

  for (std::size_t vertex = 0; vertex < importer.points.size(); ++vertex) {
    const auto& p = importer.points[vertex];
    const std::string coordinates = "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
                                    ", " + std::to_string(p[2]) + ")";
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InputError(path, "vertex " + std::to_string(vertex),
                       "non-finite coordinate " + coordinates);
    }
    // Binary PLY coordinates are not scanned: this names them (0-based, as OpenMesh counts).
    if (std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])}) > max_scene_coordinate) {
      throw InputError(
          path, "vertex " + std::to_string(vertex),
          "coordinate beyond 1e30 (the largest coordinate a case accepts) " + coordinates);
    }
  }

  Mesh loaded_mesh;
  loaded_mesh.name = file.stem().string();
  loaded_mesh.closed = is_closed_surface(scene.triangles);
  scene.meshes.push_back(std::move(loaded_mesh));
  return scene;
}

}  // namespace shadowcts
