#include "external_result.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "image_codec.h"
#include "json_limits.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

using Json = nlohmann::json;

std::string pixel_text(std::size_t i, std::uint32_t width) {
  return "pixel (" + std::to_string(i % width) + ", " + std::to_string(i / width) + ")";
}

// One-channel EXR of the camera's size, every pixel finite and in [0, 1].
std::vector<float> read_unit_channel(const std::string& path, const Camera& camera) {
  std::string error;
  const std::unique_ptr<ImageReader> in = image_codec().open(path, error);
  if (!in) throw InputError(path, "file", "cannot be read as an image: " + error);
  const ImageHeader& spec = in->header();
  if (spec.format != "openexr")
    throw InputError(path, "file", "is " + spec.format + ", not OpenEXR");
  if (spec.deep) throw InputError(path, "file", "deep images are not frame results");
  if (spec.x != spec.full_x || spec.y != spec.full_y || spec.width != spec.full_width ||
      spec.height != spec.full_height)
    throw InputError(path, "dataWindow",
                     "differs from the display window: one value per pixel is required");
  if (spec.width != int(camera.width) || spec.height != int(camera.height))
    throw InputError(path, "dataWindow",
                     std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                         " differs from the case camera's " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height));
  if (spec.channel_names.size() != 1) {
    std::string names;
    for (const auto& n : spec.channel_names) names += (names.empty() ? "" : " ") + n;
    throw InputError(path, "channels",
                     "expected exactly one channel, found " +
                         std::to_string(spec.channel_names.size()) +
                         (names.empty() ? std::string() : " (" + names + ")"));
  }
  const std::string channel = "channel " + spec.channel_names[0];
  if (spec.channel_types[0] != PixelType::float32 && spec.channel_types[0] != PixelType::half)
    throw InputError(path, channel, "must be FLOAT or HALF, is " + spec.channel_type_names[0]);
  std::vector<float> values(std::size_t(camera.width) * camera.height);
  if (!in->read_channel(0, values.data()))
    throw InputError(path, channel, "cannot be read: " + in->error());
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!(values[i] >= 0.0f && values[i] <= 1.0f))
      throw InputError(path, channel + ", " + pixel_text(i, camera.width),
                       std::isnan(values[i])
                           ? std::string("is NaN")
                           : "value " + std::to_string(values[i]) + " is outside [0, 1]");
  return values;
}

double positive_number(const std::string& path, const Json& object, const std::string& prefix,
                       const char* key) {
  if (!object.contains(key)) throw InputError(path, prefix + key, "is required");
  const Json& v = object.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0.0))
    throw InputError(path, prefix + key, "must be a positive number, is " + describe_json(v));
  return v.get<double>();
}

std::uint32_t positive_integer(const std::string& path, const Json& object,
                               const std::string& prefix, const char* key, std::uint32_t max) {
  if (!object.contains(key)) throw InputError(path, prefix + key, "is required");
  const Json& v = object.at(key);
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() == 0 || v.get<std::uint64_t>() > max)
    throw InputError(
        path, prefix + key,
        "must be an integer in [1, " + std::to_string(max) + "], is " + describe_json(v));
  return std::uint32_t(v.get<std::uint64_t>());
}

void only_keys(const std::string& path, const Json& object, const std::string& element,
               std::initializer_list<const char*> keys) {
  if (!object.is_object())
    throw InputError(path, element.empty() ? "(root)" : element,
                     "must be an object, is " + describe_json(object));
  for (const auto& item : object.items())
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return item.key() == k; })) {
      std::string known;
      for (const char* k : keys) known += (known.empty() ? "" : ", ") + std::string(k);
      throw InputError(path, (element.empty() ? "" : element + ".") + item.key(),
                       "unknown key (known: " + known + ")");
    }
}

// Depth-slice boundaries along the view axis: slice k covers [b[k], b[k+1]).
std::vector<double> depth_boundaries(const std::string& path, const Json& slices) {
  const std::string prefix = "depth_slices.";
  if (!slices.is_object() || !slices.contains("function"))
    throw InputError(path, "depth_slices", "must be an object with a \"function\"");
  const Json& f = slices.at("function");
  const std::string function = f.is_string() ? f.get<std::string>() : "";
  std::vector<double> b;
  if (function == "boundaries") {
    only_keys(path, slices, "depth_slices", {"function", "boundaries"});
    if (!slices.contains("boundaries") || !slices.at("boundaries").is_array() ||
        slices.at("boundaries").size() < 2 || slices.at("boundaries").size() > 4097)
      throw InputError(path, "depth_slices.boundaries",
                       "must be an array of 2 to 4097 increasing depths");
    const Json& values = slices.at("boundaries");
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::string element = "depth_slices.boundaries[" + std::to_string(k) + "]";
      if (!values[k].is_number() || !std::isfinite(values[k].get<double>()))
        throw InputError(path, element, "must be a finite number, is " + describe_json(values[k]));
      b.push_back(values[k].get<double>());
      if (k > 0 && !(b[k] > b[k - 1]))
        throw InputError(path, element, "must be greater than the boundary before it");
    }
    return b;
  }
  if (function == "linear" || function == "exponential") {
    only_keys(path, slices, "depth_slices", {"function", "count", "near", "far"});
    const std::uint32_t n = positive_integer(path, slices, prefix, "count", 4096);
    const double near = positive_number(path, slices, prefix, "near");
    const double far = positive_number(path, slices, prefix, "far");
    if (!(far > near)) throw InputError(path, "depth_slices.far", "must be greater than near");
    for (std::uint32_t k = 0; k <= n; ++k)
      b.push_back(function == "linear" ? near + (far - near) * k / n
                                       : near * std::pow(far / near, double(k) / n));
    return b;
  }
  if (function == "exponential_with_near_slice") {
    // Filament's froxels: one slice [near, split], then count - 1 exponential slices to far.
    only_keys(path, slices, "depth_slices", {"function", "count", "near", "split", "far"});
    const std::uint32_t n = positive_integer(path, slices, prefix, "count", 4096);
    if (n < 2) throw InputError(path, "depth_slices.count", "must be at least 2");
    const double near = positive_number(path, slices, prefix, "near");
    const double split = positive_number(path, slices, prefix, "split");
    const double far = positive_number(path, slices, prefix, "far");
    if (!(split > near)) throw InputError(path, "depth_slices.split", "must be greater than near");
    if (!(far > split)) throw InputError(path, "depth_slices.far", "must be greater than split");
    b.push_back(near);
    for (std::uint32_t k = 0; k < n; ++k)
      b.push_back(split * std::pow(far / split, double(k) / (n - 1)));
    return b;
  }
  throw InputError(path, "depth_slices.function",
                   "must be \"linear\", \"exponential\", \"exponential_with_near_slice\" or "
                   "\"boundaries\", is " +
                       describe_json(f));
}

struct LightGrid {
  std::uint32_t tile_width = 1, tile_height = 1, tiles_x = 1, tiles_y = 1;
  bool rows_from_bottom = false;
  std::vector<double> boundaries;  // empty: 2D tiles over [near, far]
  std::vector<std::vector<std::uint32_t>> lists;

  std::uint32_t slices() const {
    return boundaries.empty() ? 1 : std::uint32_t(boundaries.size() - 1);
  }
};

LightGrid read_light_grid(const std::string& path, const Case& c) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  if (!file) throw InputError(path, "file", "cannot be read");
  check_json_nesting(text.str(), path, "JSON");
  Json root;
  try {
    root = Json::parse(text.str());
  } catch (const Json::exception& e) {
    throw InputError(path, "JSON", e.what());
  }
  only_keys(path, root, "",
            {"tile_width", "tile_height", "tile_rows_from", "depth_slices", "lists"});
  LightGrid grid;
  grid.tile_width = positive_integer(path, root, "", "tile_width", 16384);
  grid.tile_height = positive_integer(path, root, "", "tile_height", 16384);
  grid.tiles_x = (c.camera.width + grid.tile_width - 1) / grid.tile_width;
  grid.tiles_y = (c.camera.height + grid.tile_height - 1) / grid.tile_height;
  if (root.contains("tile_rows_from")) {
    const Json& v = root.at("tile_rows_from");
    if (v != "top" && v != "bottom")
      throw InputError(path, "tile_rows_from",
                       "must be \"top\" or \"bottom\", is " + describe_json(v));
    grid.rows_from_bottom = v == "bottom";
  }
  if (root.contains("depth_slices"))
    grid.boundaries = depth_boundaries(path, root.at("depth_slices"));
  const std::uint64_t expected = std::uint64_t(grid.tiles_x) * grid.tiles_y * grid.slices();
  if (!root.contains("lists") || !root.at("lists").is_array())
    throw InputError(path, "lists", "is required: an array of arrays of light indices");
  const Json& lists = root.at("lists");
  if (lists.size() != expected)
    throw InputError(path, "lists",
                     "has " + std::to_string(lists.size()) + " lists, the grid has " +
                         std::to_string(expected) + " (" + std::to_string(grid.tiles_x) + " x " +
                         std::to_string(grid.tiles_y) + " tiles x " +
                         std::to_string(grid.slices()) + " slices)");
  grid.lists.resize(lists.size());
  for (std::size_t k = 0; k < lists.size(); ++k) {
    const std::string element = "lists[" + std::to_string(k) + "]";
    if (!lists[k].is_array())
      throw InputError(path, element,
                       "must be an array of light indices, is " + describe_json(lists[k]));
    std::vector<std::uint32_t>& list = grid.lists[k];
    for (std::size_t j = 0; j < lists[k].size(); ++j) {
      const Json& v = lists[k][j];
      const std::string item = element + "[" + std::to_string(j) + "]";
      if (!v.is_number_unsigned())
        throw InputError(path, item, "must be a light index, is " + describe_json(v));
      if (v.get<std::uint64_t>() >= c.ranged_lights.size())
        throw InputError(path, item,
                         "light index " + std::to_string(v.get<std::uint64_t>()) +
                             " is out of range (the case has " +
                             std::to_string(c.ranged_lights.size()) + " ranged lights)");
      list.push_back(std::uint32_t(v.get<std::uint64_t>()));
    }
    std::sort(list.begin(), list.end());
    const auto repeated = std::adjacent_find(list.begin(), list.end());
    if (repeated != list.end())
      throw InputError(path, element, "lists light " + std::to_string(*repeated) + " twice");
  }
  return grid;
}

class ExternalResult : public Algorithm {
 public:
  ExternalResult(const Case& c, OutputKind kind, std::string variant)
      : camera_(c.camera), result_(c.external_result) {
    info_.id = "frame";
    info_.backend = "external";
    info_.variants = {std::move(variant)};
    info_.summary = "the engine's own result, read from " + c.external_result.path;
    info_.capabilities.output = kind;
    info_.capabilities.point_light = kind == OutputKind::hard_shadow;
    info_.capabilities.directional_light = kind == OutputKind::hard_shadow;
    info_.capabilities.sun_disk = kind != OutputKind::light_lists;
    info_.capabilities.ranged_lights = kind == OutputKind::light_lists;
  }

  std::vector<float> values;  // mask / visibility, per pixel
  LightGrid grid;

  const AlgorithmInfo& info() const override { return info_; }

  SoftErrorBudget soft_error_budget(const std::string&) const override {
    return {result_.budget_per_sample, result_.budget_mean};
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string&) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    AlgorithmOutput out;
    const std::size_t n = samples.samples.size();
    auto pixel = [&](const ViewSample& s) {
      return std::size_t(s.pixel_y) * camera_.width + s.pixel_x;
    };
    switch (info_.capabilities.output) {
      case OutputKind::hard_shadow:
        out.shadowed.assign(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
          const ViewSample& s = samples.samples[i];
          if (s.sample_class != SampleClass::regular) continue;
          // Exactly 0.5 counts as lit in both conventions.
          const float v = values[pixel(s)];
          out.shadowed[i] = result_.mask_is_visibility ? v < 0.5f : v > 0.5f;
        }
        break;
      case OutputKind::soft_shadow:
        out.visible_fraction.assign(n, 0.0f);
        for (std::size_t i = 0; i < n; ++i)
          if (samples.samples[i].sample_class == SampleClass::regular)
            out.visible_fraction[i] = values[pixel(samples.samples[i])];
        break;
      case OutputKind::light_lists:
        out.light_lists = light_lists(c, samples);
        break;
    }
    return out;
  }

 private:
  std::uint32_t list_of_pixel(std::uint32_t x, std::uint32_t y, double depth) const {
    const std::uint32_t tx = x / grid.tile_width;
    const std::uint32_t row = grid.rows_from_bottom ? camera_.height - 1 - y : y;
    const std::uint32_t ty = row / grid.tile_height;
    std::uint32_t slice = 0;
    if (!grid.boundaries.empty()) {
      // Depths before the first or beyond the last boundary use the first or last slice.
      const auto above = std::upper_bound(grid.boundaries.begin(), grid.boundaries.end(), depth);
      const std::ptrdiff_t k = (above - grid.boundaries.begin()) - 1;
      slice = std::uint32_t(std::clamp<std::ptrdiff_t>(k, 0, grid.slices() - 1));
    }
    return tx + grid.tiles_x * (ty + grid.tiles_y * slice);
  }

  LightLists light_lists(const Case& c, const ViewSamples& samples) const {
    const CameraFrame f = camera_frame(c.camera);
    LightLists lists;
    lists.offsets.assign(1, 0);
    for (const auto& list : grid.lists) {
      lists.lights.insert(lists.lights.end(), list.begin(), list.end());
      lists.offsets.push_back(std::uint32_t(lists.lights.size()));
    }
    // Each list's box: its cell of the view frustum (pixel rectangle x depth range), grown to
    // hold every sample assigned to it (a G-buffer sample may lie outside near/far, or in a
    // clamped slice), rounded outwards to float. Listed lights are judged sound against it.
    std::vector<glm::dvec3> lo(grid.lists.size()), hi(grid.lists.size());
    const double W = camera_.width, H = camera_.height;
    for (std::uint32_t slice = 0; slice < grid.slices(); ++slice)
      for (std::uint32_t ty = 0; ty < grid.tiles_y; ++ty)
        for (std::uint32_t tx = 0; tx < grid.tiles_x; ++tx) {
          const std::size_t k = tx + grid.tiles_x * (ty + std::size_t(grid.tiles_y) * slice);
          const double x0 = double(tx) * grid.tile_width;
          const double x1 = std::min(W, double(tx + 1) * grid.tile_width);
          double y0 = double(ty) * grid.tile_height,
                 y1 = std::min(H, double(ty + 1) * grid.tile_height);
          if (grid.rows_from_bottom) std::tie(y0, y1) = std::pair(H - y1, H - y0);
          const double d0 = grid.boundaries.empty() ? c.camera.near_plane : grid.boundaries[slice];
          const double d1 =
              grid.boundaries.empty() ? c.camera.far_plane : grid.boundaries[slice + 1];
          lo[k] = glm::dvec3(std::numeric_limits<double>::infinity());
          hi[k] = -lo[k];
          for (double x : {x0, x1})
            for (double y : {y0, y1})
              for (double d : {d0, d1}) {
                const double sx = (2.0 * x / W - 1.0) * f.tan_half_fov * f.aspect;
                const double sy = (1.0 - 2.0 * y / H) * f.tan_half_fov;
                const glm::dvec3 p = f.origin + d * (f.forward + sx * f.right + sy * f.up);
                lo[k] = glm::min(lo[k], p);
                hi[k] = glm::max(hi[k], p);
              }
        }
    lists.list_of_sample.assign(samples.samples.size(), LightLists::no_list);
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      const ViewSample& s = samples.samples[i];
      if (s.sample_class != SampleClass::regular) continue;
      const glm::dvec3 p(s.position);
      const std::uint32_t k =
          list_of_pixel(s.pixel_x, s.pixel_y, glm::dot(p - f.origin, f.forward));
      lists.list_of_sample[i] = k;
      lo[k] = glm::min(lo[k], p);
      hi[k] = glm::max(hi[k], p);
    }
    for (std::size_t k = 0; k < lo.size(); ++k) {
      Aabb box;
      for (int a = 0; a < 3; ++a) {
        box.min[a] = float_below(lo[k][a]);
        box.max[a] = float_above(hi[k][a]);
      }
      lists.bounds.push_back(box);
    }
    return lists;
  }

  AlgorithmInfo info_;
  Camera camera_;
  ExternalResultFile result_;
};

}  // namespace

std::unique_ptr<Algorithm> load_external_result(const Case& c) {
  const ExternalResultFile& r = c.external_result;
  switch (r.kind) {
    case ExternalResultKind::none:
      throw InputError(c.source, "result",
                       "is required: the mask, visibility or light_lists file to check");
    case ExternalResultKind::mask: {
      auto a = std::make_unique<ExternalResult>(c, OutputKind::hard_shadow, "mask");
      a->values = read_unit_channel(r.path, c.camera);
      return a;
    }
    case ExternalResultKind::visibility: {
      auto a = std::make_unique<ExternalResult>(c, OutputKind::soft_shadow, "visibility");
      a->values = read_unit_channel(r.path, c.camera);
      return a;
    }
    case ExternalResultKind::light_lists: {
      auto a = std::make_unique<ExternalResult>(c, OutputKind::light_lists, "light_lists");
      a->grid = read_light_grid(r.path, c);
      return a;
    }
  }
  throw std::logic_error("unknown external result kind");
}

int check_frame(const std::string& manifest, const std::string& out_dir, bool progress,
                std::ostream& out, std::ostream& err) {
  const Case c = load_case_manifest(manifest);
  Registry registry;
  registry.add(load_external_result(c));
  RunOptions options;
  options.case_files = {manifest};
  options.out_dir = out_dir;
  // The result is read once, up front: repeating it measures nothing but a copy.
  options.repeats = 1;
  options.progress = progress;
  return run_suite(options, registry, out, err);
}

}  // namespace shadowcts
