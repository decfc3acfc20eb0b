#include "mesh_prechecks.h"

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
#include <set>
#include <string_view>
#include <utility>

#include "shadowcts/errors.h"
#include "shadowcts/scene_file.h"

namespace shadowcts {

std::string quoted(const std::string& word) {
  return "'" + (word.size() > 24 ? word.substr(0, 24) + "..." : word) + "'";
}

std::optional<std::string> float_problem(const std::string& word) {
  double value = 0.0;
  const char* begin = word.data() + (!word.empty() && word[0] == '+' ? 1 : 0);
  const auto [rest, error] = std::from_chars(begin, word.data() + word.size(), value);
  if (error == std::errc::result_out_of_range ||
      (error == std::errc() && std::isfinite(value) &&
       std::fabs(value) > static_cast<double>(std::numeric_limits<float>::max())))
    return quoted(word) + " is out of float range";
  if (error != std::errc() || rest != word.data() + word.size())
    return quoted(word) + " is not a number";
  if (!std::isfinite(value)) return quoted(word) + " is not finite";
  return std::nullopt;
}

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

void check_coordinate_token(const std::string& path, const std::string& token,
                            const std::string& element) {
  if (const auto problem = float_problem(token))
    throw InputError(path, element, "coordinate " + *problem);
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

// One face of the file at `element`, by its corners' vertex numbers (as the file numbers
// them). Fewer than 3 corners is an error (OpenMesh drops the face without a word); fewer than
// 3 distinct ones make a face OpenMesh drops (it keeps a polygon as the polygon without the
// repeat), remembered for the messages.
void count_face(DeclaredCounts& counts, const std::string& path, const std::string& element,
                std::vector<long long> corners, const char* noun = "vertex") {
  ++counts.faces;
  if (corners.size() < 3) {
    throw InputError(
        path, element,
        "has " + std::to_string(corners.size()) + " corner(s); a face needs at least 3");
  }
  std::sort(corners.begin(), corners.end());
  const auto repeated = std::adjacent_find(corners.begin(), corners.end());
  const auto distinct = std::unique(corners.begin(), corners.end()) - corners.begin();
  if (distinct < 3) {
    ++counts.repeated_vertex_faces;
    if (!counts.first_repeated_vertex) {
      counts.first_repeated_vertex =
          element + " uses " + noun + " " + std::to_string(*repeated) + " more than once";
    }
  }
}

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
        count_face(counts, path, element, std::vector<long long>(tokens.size() - 1));  // throws
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
      count_face(counts, path, element, corners);
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
        count_face(counts, path, "facet " + std::to_string(f), same_point_ids(points),
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
      count_face(counts, path,
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

// ---- OFF and PLY: their readers read the values from the loader's checking stream, which ends
// them at the first value that does not parse (mesh_file_loader.cpp); what remains is what they
// misread before any value: the OFF keyword line and the PLY header.

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
  std::string at_line() const { return " (line " + std::to_string(token_line_) + ")"; }

 private:
  std::istream& in_;
  std::size_t line_;
  std::size_t token_line_ = 0;
};

// A count or index as `stream >> unsigned` reads it, restricted to plain digits (it would also
// take a sign and wrap "-1" to 4294967295).
std::optional<std::uint32_t> parse_u32(const std::string& token) {
  std::uint32_t value = 0;
  const auto [rest, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || rest != token.data() + token.size())
    return std::nullopt;
  return value;
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
    throw InputError(
        path, element + tokens.at_line(),
        "the " + what + " " + quoted(token) + " is not a whole number from 0 to 4294967295");
  }
  return *value;
}

// -- OFF ----------------------------------------------------------------------------------------

// OpenMesh's OFF reader skips the rest of the keyword line, so counts written there ("OFF 3 1 0")
// would make it take the first vertex for the counts. Returns whether the file is binary.
bool check_off_keyword_line(const std::string& path, std::istream& in) {
  std::string first_line;
  std::getline(in, first_line);
  const auto tokens = split_whitespace(first_line);
  const bool off = !tokens.empty() && tokens[0].size() >= 3 && tokens[0].ends_with("OFF");
  const bool binary = off && tokens.size() == 2 && tokens[1] == "BINARY";
  if (off && tokens.size() > 1 && !binary) {
    throw InputError(path, "line 1",
                     "text after the OFF keyword: the counts must be on the next line (the reader "
                     "skips the rest of the keyword line)");
  }
  return binary;
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

// The header, token by token as OpenMesh reads it: what its reader would misread without a failed
// read is refused (a property before any element, which it adds to an element that does not
// exist; a second vertex or face element; shapes and types its reader drops or reads as zeros).
PlyHeader read_ply_header(const std::string& path, TokenReader& tokens) {
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
    const auto keyword = tokens.next();
    if (!keyword) throw InputError(path, "header", "the PLY header has no end_header line");
    if (*keyword == "end_header") break;
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

// PLY: the header as OpenMesh's reader parses it, with what it would misread refused; the data
// are left to the reader.
PlyHeader check_ply_header(const std::string& path, std::istream& in) {
  std::string first_line;
  std::getline(in, first_line);
  const auto first = split_whitespace(first_line);
  if (first.size() != 1 || (first[0] != "ply" && first[0] != "PLY"))
    throw InputError(path, "line 1", "not a PLY file (the first line is not 'ply')");
  TokenReader tokens(in, 2);
  PlyHeader header = read_ply_header(path, tokens);
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
  // The reader loops over every instance even when it reads nothing for one (an element without
  // properties): a count beyond what the file could hold would spin it for minutes.
  std::error_code size_error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, size_error);
  for (const PlyElement& element : header.elements) {
    if (!size_error && element.count > file_size) {
      throw InputError(path, element.located,
                       "declares " + std::to_string(element.count) + " instances, more than the " +
                           std::to_string(file_size) + " bytes of the file can hold");
    }
  }
  return header;
}

}  // namespace

DeclaredCounts precheck_mesh_file(const std::string& path, const std::string& format) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");
  DeclaredCounts declared;
  if (format == ".obj") declared = scan_obj(path, in);
  if (format == ".stl") declared = scan_stl(path, in);
  if (format == ".off") declared.binary = check_off_keyword_line(path, in);
  if (format == ".ply") {
    const PlyHeader header = check_ply_header(path, in);
    declared.binary = header.binary;
    declared.skipped_words = header.skipped_words;
  }
  return declared;
}

}  // namespace shadowcts
