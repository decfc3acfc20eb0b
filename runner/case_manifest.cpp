#include "shadowcts/case_manifest.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "json_limits.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/manifest_direction.h"
#include "shadowcts/scene_file.h"

namespace shadowcts {
namespace {

using Json = nlohmann::json;

constexpr double degrees_to_radians = 3.14159265358979323846 / 180.0;

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// By type and a bounded prefix: dump() of 100,000 nested arrays overflowed the stack for a
// 40-character message.
std::string describe(const Json& value) {
  return describe_json(value);
}

// Duplicate keys: nlohmann keeps the last one silently, which hides a typo as well as an unknown
// key would. A SAX pass over the (already parsed, so well-formed) text finds the first one.
class DuplicateKeyCheck : public nlohmann::json_sax<Json> {
 public:
  std::optional<std::string> duplicate;  // the element, "camera.width"

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& name) override {
    Frame& frame = frames_.back();
    frame.key = name;
    if (!frame.keys.insert(name).second) {
      duplicate = path();
      return false;
    }
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;        // object: the key of the value being read
    std::size_t count = 0;  // array: values started so far
  };

  bool value() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().count;
    return true;
  }
  bool open(bool object) {
    value();
    frames_.push_back({object, {}, {}, 0});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
  std::string path() const {
    std::string text;
    for (const Frame& frame : frames_) {
      if (frame.object) {
        text += (text.empty() ? "" : ".") + frame.key;
      } else {
        text += "[" + std::to_string(frame.count - 1) + "]";
      }
    }
    return text;
  }

  std::vector<Frame> frames_;
};

// A JSON object of the manifest at `path` ("camera", "scenes[1]"); every typed read names the
// full JSON path in its error, and keys outside the allowed set are errors (typos would
// otherwise silently fall back to defaults).
class ManifestObject {
 public:
  ManifestObject(const std::string& source, const Json& value, std::string path,
                 std::initializer_list<const char*> allowed_keys)
      : source_(source), value_(value), path_(std::move(path)) {
    if (!value_.is_object()) {
      throw InputError(source_, path_.empty() ? "(root)" : path_,
                       "must be an object, is " + describe(value_));
    }
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    for (const auto& item : value_.items()) {
      const std::string& key = item.key();
      if (std::none_of(allowed_keys.begin(), allowed_keys.end(),
                       [&](const char* allowed) { return key == allowed; })) {
        std::string problem = "unknown key";
        const char* closest = nullptr;
        std::size_t closest_distance = 3;  // suggest only near misses
        std::string allowed_list;
        for (const char* allowed : allowed_keys) {
          allowed_list += (allowed_list.empty() ? "" : ", ") + std::string(allowed);
          const std::size_t distance = edit_distance(key, allowed);
          if (distance < closest_distance) {
            closest_distance = distance;
            closest = allowed;
          }
        }
        if (closest) problem += " (did you mean '" + std::string(closest) + "'?)";
        problem += "; allowed: " + allowed_list;
        throw InputError(source_, element(key), problem);
      }
    }
  }

  bool has(const char* key) const { return value_.contains(key); }
  const Json& raw(const char* key) const { return value_.at(key); }
  std::string element(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  void require(const char* key) const {
    if (!has(key)) throw InputError(source_, element(key), "is required");
  }

  std::optional<std::string> string(const char* key) const {
    if (!has(key)) return std::nullopt;
    const Json& v = raw(key);
    if (!v.is_string())
      throw InputError(source_, element(key), "must be a string, is " + describe(v));
    return v.get<std::string>();
  }

  std::optional<double> number(const char* key) const {
    if (!has(key)) return std::nullopt;
    const Json& v = raw(key);
    if (!v.is_number())
      throw InputError(source_, element(key), "must be a number, is " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw InputError(source_, element(key), "must be finite");
    return d;
  }

  std::optional<std::uint64_t> unsigned_integer(const char* key, std::uint64_t max) const {
    if (!has(key)) return std::nullopt;
    const Json& v = raw(key);
    std::optional<std::uint64_t> value;
    if (v.is_number_unsigned()) {
      value = v.get<std::uint64_t>();
    } else if (v.is_number_float() && v.get<double>() >= 0.0 &&
               v.get<double>() < 18446744073709551616.0 &&
               std::floor(v.get<double>()) == v.get<double>()) {
      value = static_cast<std::uint64_t>(v.get<double>());
    }
    if (!value) {
      throw InputError(source_, element(key), "must be a non-negative integer, is " + describe(v));
    }
    if (*value > max) {
      throw InputError(source_, element(key),
                       std::to_string(*value) + " exceeds the maximum " + std::to_string(max));
    }
    return value;
  }

  std::optional<bool> boolean(const char* key) const {
    if (!has(key)) return std::nullopt;
    const Json& v = raw(key);
    if (!v.is_boolean())
      throw InputError(source_, element(key), "must be true or false, is " + describe(v));
    return v.get<bool>();
  }

  std::optional<glm::dvec3> vec3(const char* key) const {
    if (!has(key)) return std::nullopt;
    const Json& v = raw(key);
    if (!v.is_array() || v.size() != 3) {
      throw InputError(source_, element(key), "must be an array of 3 numbers, is " + describe(v));
    }
    glm::dvec3 result(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string component = element(key) + "[" + std::to_string(i) + "]";
      if (!v[i].is_number())
        throw InputError(source_, component, "must be a number, is " + describe(v[i]));
      result[static_cast<int>(i)] = v[i].get<double>();
      if (!std::isfinite(result[static_cast<int>(i)])) {
        throw InputError(source_, component, "must be finite");
      }
    }
    return result;
  }

  // A vector as a unit direction; zero length is an error. Divided by its largest component
  // first: the length of [1e300, 1e300, 0] overflows (and that of [1e-200, 0, 0] underflows).
  std::optional<glm::vec3> direction(const char* key) const {
    const auto v = vec3(key);
    if (!v) return std::nullopt;
    if (*v == glm::dvec3(0.0)) throw InputError(source_, element(key), "has zero length");
    return manifest_direction(*v);
  }

  const std::string& source() const { return source_; }
  const std::string& path() const { return path_; }

 private:
  const std::string& source_;
  const Json& value_;
  std::string path_;
};

glm::vec3 to_float(const glm::dvec3& v) {
  return glm::vec3(v);
}

void read_camera(const ManifestObject& parent, bool required, Camera& camera) {
  if (!parent.has("camera")) {
    if (required) {
      throw InputError(parent.source(), "camera",
                       "is required for file scenes (generators bring their own camera)");
    }
    return;
  }
  const ManifestObject object(
      parent.source(), parent.raw("camera"), "camera",
      {"position", "target", "up", "fov_y_degrees", "near", "far", "width", "height"});
  if (required) {
    object.require("position");
    object.require("target");
  }
  if (auto v = object.vec3("position")) camera.position = to_float(*v);
  if (auto v = object.vec3("target")) camera.target = to_float(*v);
  if (auto v = object.vec3("up")) camera.up = to_float(*v);
  if (auto v = object.number("fov_y_degrees")) camera.vertical_fov_degrees = static_cast<float>(*v);
  if (auto v = object.number("near")) camera.near_plane = static_cast<float>(*v);
  if (auto v = object.number("far")) camera.far_plane = static_cast<float>(*v);
  constexpr std::uint64_t max_side = std::numeric_limits<std::uint32_t>::max();
  if (auto v = object.unsigned_integer("width", max_side))
    camera.width = static_cast<std::uint32_t>(*v);
  if (auto v = object.unsigned_integer("height", max_side))
    camera.height = static_cast<std::uint32_t>(*v);
}

// Lights are tagged unions: the type decides which keys are allowed, so it is checked first.
void require_type(const std::string& source, const Json& value, const std::string& path) {
  if (!value.is_object()) {
    throw InputError(source, path, "must be an object, is " + describe(value));
  }
  if (!value.contains("type")) throw InputError(source, path + ".type", "is required");
}

ShadowLight read_light(const std::string& source, const Json& value) {
  require_type(source, value, "light");
  const Json& type_value = value.at("type");
  if (!type_value.is_string()) {
    throw InputError(source, "light.type", "must be a string, is " + describe(type_value));
  }
  const std::string type = type_value.get<std::string>();
  ShadowLight light;
  if (type == "point") {
    const ManifestObject object(source, value, "light", {"type", "position"});
    object.require("position");
    light.kind = ShadowLightKind::point;
    light.position = to_float(*object.vec3("position"));
  } else if (type == "directional") {
    const ManifestObject object(source, value, "light", {"type", "direction"});
    object.require("direction");
    light.kind = ShadowLightKind::directional;
    light.direction = *object.direction("direction");
  } else if (type == "sun") {
    const ManifestObject object(source, value, "light",
                                {"type", "direction", "angular_radius_degrees"});
    object.require("direction");
    object.require("angular_radius_degrees");
    light.kind = ShadowLightKind::sun_disk;
    light.direction = *object.direction("direction");
    const double degrees = *object.number("angular_radius_degrees");
    if (!(degrees > 0.0 && degrees < 90.0)) {
      throw InputError(source, "light.angular_radius_degrees",
                       "must lie in (0, 90), is " + std::to_string(degrees));
    }
    light.angular_radius = static_cast<float>(degrees * degrees_to_radians);
  } else {
    throw InputError(source, "light.type", "'" + type + "' is not one of point, directional, sun");
  }
  return light;
}

RangedLight read_ranged_light(const std::string& source, const Json& value,
                              const std::string& path) {
  require_type(source, value, path);
  const Json& type_value = value.at("type");
  if (!type_value.is_string()) {
    throw InputError(source, path + ".type", "must be a string, is " + describe(type_value));
  }
  const std::string type = type_value.get<std::string>();
  RangedLight light;
  auto read_sphere_part = [&](const ManifestObject& object) {
    object.require("centre");
    object.require("range");
    light.centre = to_float(*object.vec3("centre"));
    const double range = *object.number("range");
    if (!(range > 0.0)) {
      throw InputError(source, path + ".range", "must be positive, is " + std::to_string(range));
    }
    light.range = static_cast<float>(range);
  };
  if (type == "sphere") {
    const ManifestObject object(source, value, path, {"type", "centre", "range"});
    light.kind = RangedLightKind::sphere;
    read_sphere_part(object);
  } else if (type == "spot") {
    const ManifestObject object(
        source, value, path, {"type", "centre", "range", "direction", "cone_half_angle_degrees"});
    light.kind = RangedLightKind::spot;
    read_sphere_part(object);
    object.require("direction");
    object.require("cone_half_angle_degrees");
    light.direction = *object.direction("direction");
    const double degrees = *object.number("cone_half_angle_degrees");
    if (!(degrees > 0.0 && degrees < 180.0)) {
      throw InputError(source, path + ".cone_half_angle_degrees",
                       "must lie in (0, 180), is " + std::to_string(degrees));
    }
    light.cone_half_angle = static_cast<float>(degrees * degrees_to_radians);
  } else {
    throw InputError(source, path + ".type", "'" + type + "' is not one of sphere, spot");
  }
  return light;
}

// Placement of a scene file: p' = translate + scale * R_y(angle) * p, in double, then rounded.
struct Placement {
  glm::dvec3 translate{0.0};
  double scale = 1.0;
  double cos_angle = 1.0, sin_angle = 0.0;

  glm::dvec3 rotate(const glm::dvec3& v) const {
    return {cos_angle * v.x + sin_angle * v.z, v.y, -sin_angle * v.x + cos_angle * v.z};
  }
  glm::dvec3 exact_point(const glm::vec3& p) const {
    return translate + scale * rotate(glm::dvec3(p));
  }
  // Without a placement the file's floats stay as they are, -0 included (the arithmetic of
  // exact_point would turn -0 into +0, and a reproducer must give back the very floats).
  glm::vec3 point(const glm::vec3& p) const {
    const bool identity =
        translate == glm::dvec3(0.0) && scale == 1.0 && cos_angle == 1.0 && sin_angle == 0.0;
    return identity ? p : glm::vec3(exact_point(p));
  }
  glm::vec3 direction(const glm::vec3& d) const {
    return glm::vec3(glm::normalize(rotate(glm::dvec3(d))));
  }
};

Placement read_placement(const ManifestObject& object) {
  Placement placement;
  if (auto v = object.vec3("translate")) placement.translate = *v;
  if (auto v = object.number("scale")) {
    // Positive only: a mirror would flip the winding that closedness and culling rely on.
    if (!(*v > 0.0)) {
      throw InputError(object.source(), object.element("scale"),
                       "must be positive, is " + std::to_string(*v));
    }
    placement.scale = *v;
  }
  if (auto v = object.number("rotate_y_degrees")) {
    // Quarter turns are exact, so axis-aligned scenes stay axis-aligned to the last bit.
    const double quarter_turns = *v / 90.0;
    if (std::floor(quarter_turns) == quarter_turns) {
      static constexpr double cosines[4] = {1.0, 0.0, -1.0, 0.0};
      static constexpr double sines[4] = {0.0, 1.0, 0.0, -1.0};
      const auto k = static_cast<std::size_t>(
          ((static_cast<long long>(std::fmod(quarter_turns, 4.0)) % 4) + 4) % 4);
      placement.cos_angle = cosines[k];
      placement.sin_angle = sines[k];
    } else {
      placement.cos_angle = std::cos(*v * degrees_to_radians);
      placement.sin_angle = std::sin(*v * degrees_to_radians);
    }
  }
  return placement;
}

std::string read_text_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    // /dev/zero, a folder, a FIFO: they exist, and reading them would never end or mean nothing.
    throw InputError(path, "file",
                     std::filesystem::exists(path, error) ? "not a regular file" : "not found");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "file", "read error");
  return text.str();
}

// The largest |coordinate| of a placed point, in double before rounding to float.
double placed_magnitude(const glm::dvec3& p) {
  return std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
}

std::filesystem::path resolve(const std::filesystem::path& manifest_folder,
                              const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : manifest_folder / p;
}

// "result": exactly one of mask / visibility / light_lists, a file beside the manifest.
ExternalResultFile read_result(const std::string& path, const ManifestObject& manifest,
                               const std::filesystem::path& manifest_folder) {
  const ManifestObject result(path, manifest.raw("result"), "result",
                              {"mask", "visibility", "light_lists", "mask_values", "budget"});
  ExternalResultFile file;
  const char* key = nullptr;
  for (const auto& [name, kind] : {std::pair{"mask", ExternalResultKind::mask},
                                   std::pair{"visibility", ExternalResultKind::visibility},
                                   std::pair{"light_lists", ExternalResultKind::light_lists}}) {
    if (!result.has(name)) continue;
    if (key) {
      throw InputError(path, "result",
                       std::string("give exactly one of mask, visibility, light_lists (has ") +
                           key + " and " + name + ")");
    }
    key = name;
    file.kind = kind;
  }
  if (!key) throw InputError(path, "result", "give exactly one of mask, visibility, light_lists");
  file.path = resolve(manifest_folder, *result.string(key)).string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(file.path, error)) {
    throw InputError(
        path, result.element(key),
        "file " + file.path +
            (std::filesystem::exists(file.path, error) ? " is not a regular file" : " not found"));
  }
  if (auto values = result.string("mask_values")) {
    if (file.kind != ExternalResultKind::mask)
      throw InputError(path, "result.mask_values", "belongs to a mask result only");
    if (*values != "shadowed" && *values != "visible") {
      throw InputError(
          path, "result.mask_values",
          "must be \"shadowed\" (1 = shadowed) or \"visible\" (1 = lit), is \"" + *values + "\"");
    }
    file.mask_is_visibility = *values == "visible";
  }
  if (result.has("budget")) {
    if (file.kind != ExternalResultKind::visibility)
      throw InputError(path, "result.budget", "belongs to a visibility result only");
    const ManifestObject budget(path, result.raw("budget"), "result.budget",
                                {"per_sample", "mean"});
    for (const auto& [name, target] :
         {std::pair{"per_sample", &file.budget_per_sample}, std::pair{"mean", &file.budget_mean}}) {
      if (auto v = budget.number(name)) {
        if (!(*v >= 0.0 && *v <= 1.0))
          throw InputError(path, budget.element(name), "must lie in [0, 1]");
        *target = *v;
      }
    }
  }
  return file;
}

// "gbuffer": a file name (world positions, triangle ids), or an object saying how the engine wrote
// it (docs/case-manifest.md).
std::string read_gbuffer(const std::string& path, const ManifestObject& manifest,
                         GBufferFormat& format) {
  format = GBufferFormat{};
  const Json& value = manifest.raw("gbuffer");
  if (value.is_string()) return *manifest.string("gbuffer");
  const ManifestObject gbuffer(path, value, "gbuffer",
                               {"file", "positions", "receivers", "inverse_view_projection",
                                "depth_range", "reversed_z", "row_0_ndc_y"});
  gbuffer.require("file");
  auto choice = [&](const char* key, std::initializer_list<const char*> names) -> int {
    const auto name = gbuffer.string(key);
    if (!name) return 0;
    int index = 0;
    std::string known;
    for (const char* n : names) {
      if (*name == n) return index;
      known += (known.empty() ? "\"" : ", \"") + std::string(n) + "\"";
      ++index;
    }
    throw InputError(path, gbuffer.element(key),
                     "must be one of " + known + ", is \"" + *name + "\"");
  };
  format.positions = GBufferPositions(choice("positions", {"world", "depth"}));
  format.receivers =
      GBufferReceivers(choice("receivers", {"triangle_id", "mesh_primitive", "search"}));
  const bool depth = format.positions == GBufferPositions::depth;
  for (const char* key : {"inverse_view_projection", "depth_range", "reversed_z", "row_0_ndc_y"})
    if (gbuffer.has(key) && !depth)
      throw InputError(path, gbuffer.element(key), "belongs to \"positions\": \"depth\" only");
  if (!depth) return *gbuffer.string("file");

  format.depth_range = NdcDepthRange(choice("depth_range", {"zero_to_one", "minus_one_to_one"}));
  format.reversed_z = gbuffer.boolean("reversed_z").value_or(false);
  if (gbuffer.has("row_0_ndc_y")) {
    const Json& row = gbuffer.raw("row_0_ndc_y");
    if (!row.is_number_integer() || (row.get<std::int64_t>() != 1 && row.get<std::int64_t>() != -1))
      throw InputError(path, gbuffer.element("row_0_ndc_y"),
                       "must be 1 or -1, is " + describe(row));
    format.row_0_ndc_y = int(row.get<std::int64_t>());
  }
  gbuffer.require("inverse_view_projection");
  const std::string matrix_element = gbuffer.element("inverse_view_projection");
  const Json& matrix = gbuffer.raw("inverse_view_projection");
  if (!matrix.is_array() || matrix.size() != 4)
    throw InputError(
        path, matrix_element,
        "must be 4 rows of 4 numbers ([[m00, m01, m02, m03], ...]), is " + describe(matrix));
  glm::dmat4 m(0.0);  // glm: m[column][row]
  for (std::size_t r = 0; r < 4; ++r) {
    const std::string row_element = matrix_element + "[" + std::to_string(r) + "]";
    if (!matrix[r].is_array() || matrix[r].size() != 4)
      throw InputError(path, row_element, "must be a row of 4 numbers, is " + describe(matrix[r]));
    for (std::size_t k = 0; k < 4; ++k) {
      const Json& v = matrix[r][k];
      const std::string element = row_element + "[" + std::to_string(k) + "]";
      if (!v.is_number()) throw InputError(path, element, "must be a number, is " + describe(v));
      if (!std::isfinite(v.get<double>())) throw InputError(path, element, "must be finite");
      format.inverse_view_projection[r][k] = v.get<double>();
      m[int(k)][int(r)] = v.get<double>();
    }
  }
  const double determinant = glm::determinant(m);
  if (!(std::isfinite(determinant) && determinant != 0.0))
    throw InputError(path, matrix_element,
                     "is singular (determinant " + std::to_string(determinant) +
                         "): give the inverse of the engine's view-projection matrix");
  return *gbuffer.string("file");
}

}  // namespace

Case load_case_manifest(const std::string& path) {
  GBufferFormat ignored;
  return load_case_manifest(path, ignored);
}

Case load_case_manifest(const std::string& path, GBufferFormat& gbuffer_format) {
  const std::string text = read_text_file(path);
  // nlohmann parses and destroys iteratively, but nothing of a manifest nests this deep.
  check_json_nesting(text, path, "JSON");
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range (found by
    // fuzz_case_manifest: "4e938" escaped as a non-InputError).
    throw InputError(path, "JSON", e.what());
  }
  DuplicateKeyCheck duplicates;
  Json::sax_parse(text, &duplicates);
  if (duplicates.duplicate) {
    throw InputError(path, *duplicates.duplicate,
                     "duplicate key (JSON keeps only the last; give each key once)");
  }
  const ManifestObject manifest(path, root, "",
                                {"name", "scene", "scenes", "gbuffer", "result", "camera", "light",
                                 "ranged_lights", "parameters"});
  const std::filesystem::path manifest_folder = std::filesystem::path(path).parent_path();

  if (manifest.has("scene") == manifest.has("scenes")) {
    throw InputError(path, "scene/scenes",
                     "give exactly one: \"scene\" (a generator) or \"scenes\" (files)");
  }

  Case c;
  std::vector<ShadowLight> file_shadow_lights;
  std::vector<RangedLight> file_ranged_lights;
  if (manifest.has("scene")) {
    const ManifestObject scene(path, manifest.raw("scene"), "scene",
                               {"generator", "triangles", "seed"});
    scene.require("generator");
    const std::string generator = *scene.string("generator");
    const auto& generators = fixture_generators();
    const auto known = std::find_if(generators.begin(), generators.end(),
                                    [&](const FixtureGenerator& g) { return g.name == generator; });
    if (known == generators.end()) {
      std::string names;
      for (const auto& g : generators) names += (names.empty() ? "" : ", ") + g.name;
      throw InputError(path, "scene.generator",
                       "unknown generator '" + generator + "' (known: " + names + ")");
    }
    const auto triangles = scene.unsigned_integer("triangles", 100'000'000);
    if (known->scalable && !triangles) {
      throw InputError(path, "scene.triangles",
                       "is required for the procedural generator '" + generator + "'");
    }
    const std::uint64_t seed = scene.unsigned_integer("seed", UINT64_MAX).value_or(1);
    try {
      // Model generators have a fixed size: the target is ignored by them.
      c = make_fixture(generator, triangles.value_or(1), seed);
    } catch (const InputError& e) {
      throw InputError(path, "scene", e.what());
    }
    read_camera(manifest, false, c.camera);
  } else {
    const Json& scenes = manifest.raw("scenes");
    if (!scenes.is_array() || scenes.empty()) {
      throw InputError(path, "scenes", "must be a non-empty array, is " + describe(scenes));
    }
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const ManifestObject entry(path, scenes[i], "scenes[" + std::to_string(i) + "]",
                                 {"file", "translate", "scale", "rotate_y_degrees", "caster"});
      entry.require("file");
      const std::string file = resolve(manifest_folder, *entry.string("file")).string();
      const Placement placement = read_placement(entry);
      const bool caster = entry.boolean("caster").value_or(true);
      // The file's own errors name the file and its element.
      LoadedScene loaded = load_scene_file(file);
      // A Case carries no warnings: they go where a person sees them.
      for (const auto& warning : loaded.warnings) std::cerr << "warning: " << warning << "\n";
      const auto mesh_offset = static_cast<std::uint32_t>(c.meshes.size());
      for (Mesh& mesh : loaded.meshes) {
        mesh.caster = caster;
        c.meshes.push_back(std::move(mesh));
      }
      const std::string entry_path = "scenes[" + std::to_string(i) + "]";
      for (std::size_t t = 0; t < loaded.triangles.size(); ++t) {
        const Triangle& triangle = loaded.triangles[t];
        for (const glm::vec3& corner : {triangle.v0, triangle.v1, triangle.v2}) {
          // The loaders refuse such vertices with their line or accessor: this is the backstop.
          if (placed_magnitude(glm::dvec3(corner)) > max_scene_coordinate) {
            throw InputError(file, "triangle " + std::to_string(t),
                             "a corner lies beyond 1e30 (the largest coordinate a case accepts)");
          }
          const glm::dvec3 placed = placement.exact_point(corner);
          if (!(placed_magnitude(placed) <= max_scene_coordinate)) {
            // The file's vertex is fine: the placement carries it out of range.
            const char* culprit =
                placed_magnitude(placement.translate) > max_scene_coordinate ? ".translate"
                : placement.scale > 1.0                                      ? ".scale"
                : placed_magnitude(placement.translate) > 0.0                ? ".translate"
                                                                             : ".rotate_y_degrees";
            throw InputError(path, entry_path + culprit,
                             "places triangle " + std::to_string(t) + " of " + file +
                                 " beyond 1e30 (the largest coordinate a case accepts)");
          }
        }
        c.triangles.push_back(Triangle{placement.point(triangle.v0), placement.point(triangle.v1),
                                       placement.point(triangle.v2), triangle.mesh + mesh_offset});
      }
      for (ShadowLight light : loaded.shadow_lights) {
        light.position = placement.point(light.position);
        if (light.kind != ShadowLightKind::point)
          light.direction = placement.direction(light.direction);
        file_shadow_lights.push_back(light);
      }
      for (RangedLight light : loaded.ranged_lights) {
        // The placement resizes the file's whole content, light ranges included.
        light.centre = placement.point(light.centre);
        light.range = static_cast<float>(light.range * placement.scale);
        light.direction = placement.direction(light.direction);
        file_ranged_lights.push_back(light);
      }
    }
    c.name = std::filesystem::path(path).stem().string();
    read_camera(manifest, true, c.camera);
    // Lights in the files are used when the manifest names none; a case has one shadow light,
    // the first one found.
    if (!file_shadow_lights.empty()) c.light = file_shadow_lights.front();
    c.ranged_lights = file_ranged_lights;
  }
  c.source = path;

  if (auto name = manifest.string("name")) {
    if (name->empty()) throw InputError(path, "name", "must not be empty");
    c.name = *name;
  }
  gbuffer_format = GBufferFormat{};
  if (manifest.has("gbuffer")) {
    const std::string gbuffer = read_gbuffer(path, manifest, gbuffer_format);
    c.gbuffer_path = resolve(manifest_folder, gbuffer).string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(c.gbuffer_path, error)) {
      throw InputError(
          path, "gbuffer",
          "file " + c.gbuffer_path +
              (std::filesystem::exists(c.gbuffer_path, error) ? " is not a regular file"
                                                              : " not found"));
    }
  }
  if (manifest.has("result")) c.external_result = read_result(path, manifest, manifest_folder);
  if (manifest.has("light")) c.light = read_light(path, manifest.raw("light"));
  if (manifest.has("ranged_lights")) {
    const Json& lights = manifest.raw("ranged_lights");
    if (!lights.is_array()) {
      throw InputError(path, "ranged_lights", "must be an array, is " + describe(lights));
    }
    c.ranged_lights.clear();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      c.ranged_lights.push_back(
          read_ranged_light(path, lights[i], "ranged_lights[" + std::to_string(i) + "]"));
    }
  }
  if (manifest.has("parameters")) {
    const ManifestObject parameters(path, manifest.raw("parameters"), "parameters",
                                    {"eps_rel", "repeats", "threads", "seed"});
    if (auto v = parameters.number("eps_rel")) {
      // validate()'s range: below 2^-24 the band is narrower than float resolution, above 2^-4
      // it covers most of the scene.
      if (!(*v >= 0x1p-24 && *v <= 0x1p-4)) {
        throw InputError(
            path, "parameters.eps_rel",
            "must lie in [2^-24, 2^-4] (5.96e-08 to 0.0625), is " + std::to_string(*v));
      }
      c.parameters.eps_rel = *v;
    }
    if (auto v = parameters.unsigned_integer("repeats", 1000)) {
      if (*v == 0) throw InputError(path, "parameters.repeats", "must be at least 1");
      c.parameters.repeats = static_cast<std::uint32_t>(*v);
    }
    if (auto v = parameters.unsigned_integer("threads", 4096)) {
      c.parameters.threads = static_cast<std::uint32_t>(*v);
    }
    if (auto v = parameters.unsigned_integer("seed", UINT64_MAX)) c.parameters.seed = *v;
  }

  validate(c);
  if (!c.gbuffer_path.empty()) {
    // Against the camera now, before a runner allocates or writes anything for this case.
    check_gbuffer_exr_header(c.gbuffer_path, c.camera.width, c.camera.height);
  }
  return c;
}

}  // namespace shadowcts
