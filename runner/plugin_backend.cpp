#include "plugin_backend.h"

#include <dlfcn.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "sha256.h"
#include "shadowcts/errors.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts {
namespace {

const char* algorithm_name(std::uint32_t algorithm) {
  switch (algorithm) {
    case SHADOWCTS_ALGORITHM_PTSV:
      return "ptsv";
    case SHADOWCTS_ALGORITHM_PSV:
      return "psv";
    case SHADOWCTS_ALGORITHM_METRIC:
      return "metric";
    case SHADOWCTS_ALGORITHM_SOFTTILE:
      return "softtile";
    case SHADOWCTS_ALGORITHM_LIGHTASSIGN:
      return "lightassign";
    case SHADOWCTS_ALGORITHM_OTHER_HARD:
      return "other_hard";
    case SHADOWCTS_ALGORITHM_OTHER_SOFT:
      return "other_soft";
    case SHADOWCTS_ALGORITHM_OTHER_LIGHT_ASSIGNMENT:
      return "other_lightassign";
    default:
      return nullptr;
  }
}

// The output kind each algorithm writes.
std::uint32_t output_of_algorithm(std::uint32_t algorithm) {
  switch (algorithm) {
    case SHADOWCTS_ALGORITHM_SOFTTILE:
    case SHADOWCTS_ALGORITHM_OTHER_SOFT:
      return SHADOWCTS_OUTPUT_SOFT;
    case SHADOWCTS_ALGORITHM_LIGHTASSIGN:
    case SHADOWCTS_ALGORITHM_OTHER_LIGHT_ASSIGNMENT:
      return SHADOWCTS_OUTPUT_LIGHT_LISTS;
    default:
      return SHADOWCTS_OUTPUT_HARD;
  }
}

// The light kinds that make sense for an output kind.
std::uint32_t lights_of_output(std::uint32_t output) {
  switch (output) {
    case SHADOWCTS_OUTPUT_HARD:
      return SHADOWCTS_LIGHT_POINT | SHADOWCTS_LIGHT_DIRECTIONAL;
    case SHADOWCTS_OUTPUT_SOFT:
      return SHADOWCTS_LIGHT_SUN_DISK;
    default:
      return SHADOWCTS_LIGHT_RANGED;
  }
}

// What a static string of the library may hold: printable ASCII; names: [a-z0-9_-] (they become
// part of record names and paths); variant names also '+', as the suite's own ("explicit+planes").
enum class Characters { printable, name, variant };

// A static string of the library: non-null, non-empty, at most the ABI's length.
std::string checked_string(const std::string& library, const std::string& field, const char* text,
                           Characters allowed) {
  if (!text) throw InputError(library, field, "is a null pointer (must be a string)");
  const std::size_t length = ::strnlen(text, SHADOWCTS_MAX_NAME_LENGTH + 1);
  if (length == 0) throw InputError(library, field, "is empty");
  if (length > SHADOWCTS_MAX_NAME_LENGTH)
    throw InputError(library, field,
                     "is longer than " + std::to_string(SHADOWCTS_MAX_NAME_LENGTH) + " characters");
  std::string value(text, length);
  for (char ch : value) {
    const bool name_character = (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_' ||
                                ch == '-' || (allowed == Characters::variant && ch == '+');
    const bool ok = allowed == Characters::printable ? ch >= 0x20 && ch < 0x7f : name_character;
    if (!ok)
      throw InputError(library, field,
                       "'" + value + "' holds a character other than " +
                           (allowed == Characters::printable ? "printable ASCII"
                            : allowed == Characters::name    ? "a-z, 0-9, '_' and '-'"
                                                             : "a-z, 0-9, '_', '-' and '+'"));
  }
  return value;
}

OutputKind output_kind(std::uint32_t output) {
  return output == SHADOWCTS_OUTPUT_SOFT          ? OutputKind::soft_shadow
         : output == SHADOWCTS_OUTPUT_LIGHT_LISTS ? OutputKind::light_lists
                                                  : OutputKind::hard_shadow;
}

void append_u32s(Sha256& hash, const std::vector<std::uint32_t>& values) {
  for (std::uint32_t v : values) {
    const unsigned char bytes[4] = {
        static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
        static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 24)};
    hash.update(bytes, 4);
  }
}

void append_floats(Sha256& hash, const std::vector<float>& values) {
  std::vector<std::uint32_t> bits(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) std::memcpy(&bits[i], &values[i], 4);
  append_u32s(hash, bits);
}

}  // namespace

PluginBackend::PluginBackend(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "library file", "does not exist");
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "library file", "is not a file");
  // A path without a slash would make dlopen search the library path instead of this file.
  const std::string load_path = fs::absolute(path, ec).string();
  handle_ = ::dlopen(load_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* why = ::dlerror();
    throw InputError(path, "library file",
                     std::string("cannot be loaded: ") + (why ? why : "unknown dlopen error"));
  }
  ::dlerror();
  void* symbol = ::dlsym(handle_, SHADOWCTS_BACKEND_NEGOTIATE_SYMBOL);
  if (!symbol)
    throw InputError(path, SHADOWCTS_BACKEND_NEGOTIATE_SYMBOL,
                     "the library does not export the entry point (see "
                     "include/shadowcts/backend_abi.h)");
  ShadowctsNegotiateFunction negotiate;
  static_assert(sizeof negotiate == sizeof symbol);
  std::memcpy(&negotiate, &symbol, sizeof negotiate);

  table_ = ShadowctsBackend{};
  table_.struct_size = sizeof(ShadowctsBackend);
  const std::int32_t status = negotiate(SHADOWCTS_BACKEND_ABI_VERSION, &table_);
  const std::string spoken = std::to_string(SHADOWCTS_BACKEND_ABI_VERSION);
  if (status == SHADOWCTS_STATUS_ABI_MISMATCH ||
      table_.abi_version != SHADOWCTS_BACKEND_ABI_VERSION)
    throw InputError(path, "abi_version",
                     "the library speaks ABI version " + std::to_string(table_.abi_version) +
                         ", this suite version " + spoken +
                         (status == SHADOWCTS_STATUS_ABI_MISMATCH
                              ? " (negotiation answered SHADOWCTS_STATUS_ABI_MISMATCH)"
                              : ""));
  if (status != SHADOWCTS_STATUS_OK)
    throw InputError(path, SHADOWCTS_BACKEND_NEGOTIATE_SYMBOL,
                     "returned status " + std::to_string(status) + " (expected 0, OK)");
  if (table_.struct_size != sizeof(ShadowctsBackend))
    throw InputError(path, "struct_size",
                     "the library changed it to " + std::to_string(table_.struct_size) +
                         " (the suite's table has " + std::to_string(sizeof(ShadowctsBackend)) +
                         " bytes)");
  name_ = checked_string(path, "name", table_.name, Characters::name);
  version_ = checked_string(path, "version", table_.version, Characters::printable);
  build_id_ = checked_string(path, "build_id", table_.build_id, Characters::printable);
  if (table_.variant_count == 0) throw InputError(path, "variant_count", "is 0 (at least 1)");
  if (table_.variant_count > 1024)
    throw InputError(path, "variant_count",
                     "is " + std::to_string(table_.variant_count) + " (at most 1024)");
  if (!table_.variants) throw InputError(path, "variants", "is a null pointer");
  for (std::uint32_t k = 0; k < table_.variant_count; ++k) {
    const ShadowctsVariant& v = table_.variants[k];
    const std::string at = "variants[" + std::to_string(k) + "]";
    PluginVariantInfo info;
    info.name = checked_string(path, at + ".name", v.name, Characters::variant);
    for (const PluginVariantInfo& earlier : variants_)
      if (earlier.name == info.name)
        throw InputError(path, at + ".name", "'" + info.name + "' is declared twice");
    const char* algorithm = algorithm_name(v.algorithm);
    if (!algorithm)
      throw InputError(path, at + ".algorithm",
                       "unknown algorithm " + std::to_string(v.algorithm) +
                           " (known: 1 ptsv, 2 psv, 3 metric, 4 softtile, 5 lightassign, 6 other "
                           "hard, 7 other soft, 8 other light assignment)");
    info.algorithm = algorithm;
    if (v.output_kind < SHADOWCTS_OUTPUT_HARD || v.output_kind > SHADOWCTS_OUTPUT_LIGHT_LISTS)
      throw InputError(path, at + ".output_kind",
                       "unknown output kind " + std::to_string(v.output_kind) +
                           " (known: 1 hard, 2 soft, 3 light lists)");
    if (v.output_kind != output_of_algorithm(v.algorithm))
      throw InputError(path, at + ".output_kind",
                       "is " + std::to_string(v.output_kind) + ", but " + info.algorithm +
                           " writes output kind " +
                           std::to_string(output_of_algorithm(v.algorithm)));
    info.output = output_kind(v.output_kind);
    if (v.light_kinds == 0)
      throw InputError(path, at + ".light_kinds", "is 0: declare the light kinds it handles");
    if ((v.light_kinds & ~lights_of_output(v.output_kind)) != 0)
      throw InputError(path, at + ".light_kinds",
                       "holds bits " +
                           std::to_string(v.light_kinds & ~lights_of_output(v.output_kind)) +
                           " that are not light kinds of its output (allowed: " +
                           std::to_string(lights_of_output(v.output_kind)) + ")");
    info.light_kinds = v.light_kinds;
    if ((v.flags & ~SHADOWCTS_VARIANT_ALL_FLAGS) != 0)
      throw InputError(
          path, at + ".flags",
          "holds unknown bits " + std::to_string(v.flags & ~SHADOWCTS_VARIANT_ALL_FLAGS));
    info.flags = v.flags;
    const std::pair<const char*, std::uint64_t> limits[] = {
        {".max_triangles", v.max_triangles},
        {".max_regular_samples", v.max_regular_samples},
        {".max_sample_triangle_pairs", v.max_sample_triangle_pairs}};
    for (const auto& [field, value] : limits)
      if (value == 0)
        throw InputError(path, at + field,
                         "is 0: a size limit must be at least 1 (UINT64_MAX for none)");
    info.max_triangles = v.max_triangles;
    info.max_regular_samples = v.max_regular_samples;
    info.max_sample_triangle_pairs = v.max_sample_triangle_pairs;
    const std::pair<const char*, double> budgets[] = {
        {".soft_error_per_sample", v.soft_error_per_sample},
        {".soft_error_mean", v.soft_error_mean}};
    for (const auto& [field, value] : budgets)
      if (!(value >= 0.0 && value <= 1.0))
        throw InputError(path, at + field, "is " + std::to_string(value) + " (must be in [0, 1])");
    if (v.output_kind != SHADOWCTS_OUTPUT_SOFT &&
        (v.soft_error_per_sample != 0.0 || v.soft_error_mean != 0.0))
      throw InputError(path, at + ".soft_error_per_sample",
                       "is a soft-shadow budget on a variant that does not write soft shadows");
    info.soft_error_per_sample = v.soft_error_per_sample;
    info.soft_error_mean = v.soft_error_mean;
    if (!v.run) throw InputError(path, at + ".run", "is a null function pointer");
    variants_.push_back(std::move(info));
  }
}

// The library stays loaded: Algorithms made from it may be destroyed in any order, and its static
// strings are referenced by the table. The process ends soon after a certification anyway.
PluginBackend::~PluginBackend() = default;

std::unique_ptr<PluginAlgorithm> PluginBackend::algorithm(std::size_t variant) const {
  return std::make_unique<PluginAlgorithm>(*this, variant);
}

PluginAlgorithm::PluginAlgorithm(const PluginBackend& backend, std::size_t variant)
    : backend_(backend), variant_(variant) {
  const PluginVariantInfo& v = backend.variants().at(variant);
  info_.id = v.algorithm;
  info_.backend = backend.name();
  info_.variants = {v.name};
  info_.summary = "plugin " + backend.name() + " " + backend.version() + " (" + backend.build_id() +
                  ") from " + backend.path();
  Capabilities& caps = info_.capabilities;
  caps.output = v.output;
  caps.point_light = (v.light_kinds & SHADOWCTS_LIGHT_POINT) != 0;
  caps.directional_light = (v.light_kinds & SHADOWCTS_LIGHT_DIRECTIONAL) != 0;
  caps.sun_disk = (v.light_kinds & SHADOWCTS_LIGHT_SUN_DISK) != 0;
  caps.ranged_lights = (v.light_kinds & SHADOWCTS_LIGHT_RANGED) != 0;
  caps.needs_closed_meshes = (v.flags & SHADOWCTS_VARIANT_NEEDS_CLOSED_MESHES) != 0;
  caps.approximate = (v.flags & SHADOWCTS_VARIANT_APPROXIMATE) != 0;
  caps.needs_samples_in_their_pixels =
      (v.flags & SHADOWCTS_VARIANT_NEEDS_SAMPLES_IN_THEIR_PIXELS) != 0;
  caps.max_sample_triangle_pairs =
      v.max_sample_triangle_pairs == std::numeric_limits<std::uint64_t>::max()
          ? 0
          : v.max_sample_triangle_pairs;
}

std::optional<std::string> PluginAlgorithm::unsupported_reason(const Case& c,
                                                               const ViewSamples& samples,
                                                               const std::string& variant) const {
  if (auto why = Algorithm::unsupported_reason(c, samples, variant)) return why;
  const PluginVariantInfo& v = backend_.variants()[variant_];
  if (c.triangles.size() > v.max_triangles)
    return "too large for this variant: " + std::to_string(c.triangles.size()) +
           " triangles (declared limit " + std::to_string(v.max_triangles) + ")";
  const std::uint64_t regular = samples.count(SampleClass::regular);
  if (regular > v.max_regular_samples)
    return "too large for this variant: " + std::to_string(regular) +
           " regular samples (declared limit " + std::to_string(v.max_regular_samples) + ")";
  return std::nullopt;
}

SoftErrorBudget PluginAlgorithm::soft_error_budget(const std::string&) const {
  const PluginVariantInfo& v = backend_.variants()[variant_];
  return {v.soft_error_per_sample, v.soft_error_mean};
}

AlgorithmOutput PluginAlgorithm::run(const PreparedScene& scene, const std::string& variant) const {
  const PluginVariantInfo& v = backend_.variants()[variant_];
  const std::string who = "plugin " + backend_.name() + ":" + v.name;
  if (variant != v.name) throw std::invalid_argument(who + ": unknown variant '" + variant + "'");
  const CasterArrays& tris = scene.casters;
  const RegularSamples& samples = scene.samples;
  const Case& c = scene.source;

  ShadowctsScene s{};
  s.struct_size = sizeof s;
  s.case_name = c.name.c_str();
  s.triangle_count = tris.size();
  for (int k = 0; k < 3; ++k) {
    s.x[k] = tris.x[k].data();
    s.y[k] = tris.y[k].data();
    s.z[k] = tris.z[k].data();
  }
  s.mesh = tris.mesh.data();
  s.casts = tris.casts.data();
  s.mesh_count = tris.mesh_closed.size();
  s.mesh_closed = tris.mesh_closed.data();
  s.mesh_casts = tris.mesh_casts.data();
  s.sample_count = samples.size();
  s.sample_pixel = samples.index.data();
  s.px = samples.px.data();
  s.py = samples.py.data();
  s.pz = samples.pz.data();
  s.nx = samples.nx.data();
  s.ny = samples.ny.data();
  s.nz = samples.nz.data();
  s.receiver = samples.receiver.data();
  if (scene.light) {
    const ShadowLight& l = *scene.light;
    s.light.kind = l.kind == ShadowLightKind::point         ? SHADOWCTS_LIGHT_POINT
                   : l.kind == ShadowLightKind::directional ? SHADOWCTS_LIGHT_DIRECTIONAL
                                                            : SHADOWCTS_LIGHT_SUN_DISK;
    for (int k = 0; k < 3; ++k) {
      s.light.position[k] = l.position[k];
      s.light.direction[k] = l.direction[k];
    }
    s.light.angular_radius = l.angular_radius;
  }
  s.scale = scene.scale;
  s.tau = scene.tau;
  for (int k = 0; k < 3; ++k) {
    s.camera_position[k] = c.camera.position[k];
    s.camera_target[k] = c.camera.target[k];
    s.camera_up[k] = c.camera.up[k];
  }
  s.vertical_fov_degrees = c.camera.vertical_fov_degrees;
  s.near_plane = c.camera.near_plane;
  s.far_plane = c.camera.far_plane;
  s.width = c.camera.width;
  s.height = c.camera.height;
  const std::size_t lights = c.ranged_lights.size();
  std::vector<std::uint32_t> ranged_kind(lights);
  std::vector<float> ranged[8];
  for (auto& a : ranged) a.resize(lights);
  for (std::size_t i = 0; i < lights; ++i) {
    const RangedLight& l = c.ranged_lights[i];
    ranged_kind[i] = l.kind == RangedLightKind::spot ? 1 : 0;
    const float values[8] = {l.centre.x,    l.centre.y,    l.centre.z,    l.range,
                             l.direction.x, l.direction.y, l.direction.z, l.cone_half_angle};
    for (int k = 0; k < 8; ++k) ranged[k][i] = values[k];
  }
  s.ranged_light_count = lights;
  s.ranged_kind = ranged_kind.data();
  s.ranged_cx = ranged[0].data();
  s.ranged_cy = ranged[1].data();
  s.ranged_cz = ranged[2].data();
  s.ranged_range = ranged[3].data();
  s.ranged_dx = ranged[4].data();
  s.ranged_dy = ranged[5].data();
  s.ranged_dz = ranged[6].data();
  s.ranged_cone_half_angle = ranged[7].data();
  s.threads = c.parameters.threads;

  const std::size_t n = samples.size();
  std::vector<std::uint8_t> shadowed;
  std::vector<float> visible;
  std::vector<std::uint32_t> offsets, list_lights, list_of_sample;
  // The ABI promises a non-null array for the variant's output kind, also for a case without
  // regular samples (every sample back-facing or sky): storage reserved, so data() is not null.
  shadowed.reserve(std::max<std::size_t>(n, 1));
  visible.reserve(std::max<std::size_t>(n, 1));
  list_of_sample.reserve(std::max<std::size_t>(n, 1));
  std::vector<float> bounds;
  std::vector<ShadowctsCounter> counters(64);
  ShadowctsOutputs o{};
  std::vector<char> message(1024, '\0');
  std::int32_t status = SHADOWCTS_STATUS_OK;
  std::uint64_t list_capacity = std::max<std::uint64_t>(n, 64), light_capacity = 4 * list_capacity;
  for (int attempt = 0;; ++attempt) {
    o = ShadowctsOutputs{};
    o.struct_size = sizeof o;
    switch (v.output) {
      case OutputKind::hard_shadow:
        shadowed.assign(n, 0);
        o.shadowed = shadowed.data();
        break;
      case OutputKind::soft_shadow:
        visible.assign(n, 0.0f);
        o.visible_fraction = visible.data();
        break;
      case OutputKind::light_lists:
        offsets.assign(list_capacity + 1, 0);
        bounds.assign(6 * list_capacity, 0.0f);
        list_lights.assign(light_capacity, 0);
        list_of_sample.assign(n, SHADOWCTS_NO_LIST);
        o.list_capacity = list_capacity;
        o.light_capacity = light_capacity;
        o.list_offsets = offsets.data();
        o.list_bounds = bounds.data();
        o.list_lights = list_lights.data();
        o.list_of_sample = list_of_sample.data();
        break;
    }
    counters.assign(64, ShadowctsCounter{});
    o.counter_capacity = std::uint32_t(counters.size());
    o.counters = counters.data();
    std::fill(message.begin(), message.end(), '\0');
    const ShadowctsVariant& fn = backend_.table_.variants[variant_];
    status = fn.run(backend_.table_.context, &s, &o, message.data(), message.size() - 1);
    if (status != SHADOWCTS_STATUS_OUTPUT_TOO_SMALL || v.output != OutputKind::light_lists ||
        attempt == 3)
      break;
    if (o.list_count <= list_capacity && o.light_count <= light_capacity)
      throw std::runtime_error(who + ": answered OUTPUT_TOO_SMALL but needs no more than it got");
    if (o.list_count > (std::uint64_t(1) << 32) || o.light_count > (std::uint64_t(1) << 32))
      throw std::runtime_error(who + ": asks for more than 2^32 lists or light entries");
    list_capacity = std::max(list_capacity, o.list_count);
    light_capacity = std::max(light_capacity, o.light_count);
  }
  message.back() = '\0';
  if (status != SHADOWCTS_STATUS_OK)
    throw std::runtime_error(who + ": returned status " + std::to_string(status) + ": " +
                             (message[0] ? message.data() : "(no message)"));

  AlgorithmOutput output;
  switch (v.output) {
    case OutputKind::hard_shadow:
      for (std::size_t i = 0; i < n; ++i)
        if (shadowed[i] > 1)
          throw std::runtime_error(who + ": shadowed[" + std::to_string(i) + "] is " +
                                   std::to_string(shadowed[i]) + " (0 or 1)");
      output.shadowed = scene.per_view_sample(shadowed, std::uint8_t(0));
      break;
    case OutputKind::soft_shadow:
      for (std::size_t i = 0; i < n; ++i)
        if (!(visible[i] >= 0.0f && visible[i] <= 1.0f))
          throw std::runtime_error(who + ": visible_fraction[" + std::to_string(i) + "] is " +
                                   std::to_string(visible[i]) + " (must be in [0, 1])");
      output.visible_fraction = scene.per_view_sample(visible, 1.0f);
      break;
    case OutputKind::light_lists: {
      if (o.list_count > list_capacity || o.light_count > light_capacity)
        throw std::runtime_error(who + ": list_count or light_count exceeds the capacity");
      LightLists& lists = output.light_lists;
      lists.offsets.assign(offsets.begin(), offsets.begin() + std::ptrdiff_t(o.list_count + 1));
      if (lists.offsets.front() != 0 || lists.offsets.back() != o.light_count)
        throw std::runtime_error(who + ": list_offsets must start at 0 and end at light_count");
      for (std::size_t k = 0; k + 1 < lists.offsets.size(); ++k)
        if (lists.offsets[k] > lists.offsets[k + 1])
          throw std::runtime_error(who + ": list_offsets[" + std::to_string(k + 1) + "] decreases");
      lists.lights.assign(list_lights.begin(), list_lights.begin() + std::ptrdiff_t(o.light_count));
      for (std::size_t k = 0; k < lists.lights.size(); ++k)
        if (lists.lights[k] >= lights)
          throw std::runtime_error(who + ": list_lights[" + std::to_string(k) + "] is " +
                                   std::to_string(lists.lights[k]) + ", not a ranged light");
      for (std::uint64_t k = 0; k < o.list_count; ++k)
        lists.bounds.push_back(Aabb{{bounds[6 * k], bounds[6 * k + 1], bounds[6 * k + 2]},
                                    {bounds[6 * k + 3], bounds[6 * k + 4], bounds[6 * k + 5]}});
      for (std::size_t i = 0; i < n; ++i)
        if (list_of_sample[i] != SHADOWCTS_NO_LIST && list_of_sample[i] >= o.list_count)
          throw std::runtime_error(who + ": list_of_sample[" + std::to_string(i) + "] is " +
                                   std::to_string(list_of_sample[i]) + ", not a list");
      lists.list_of_sample = scene.per_view_sample(list_of_sample, LightLists::no_list);
      break;
    }
  }
  if (o.counter_count > o.counter_capacity)
    throw std::runtime_error(who + ": counter_count " + std::to_string(o.counter_count) +
                             " exceeds the capacity " + std::to_string(o.counter_capacity));
  for (std::uint32_t k = 0; k < o.counter_count; ++k) {
    const ShadowctsCounter& counter = counters[k];
    const std::size_t length = ::strnlen(counter.name, sizeof counter.name);
    if (length == 0 || length == sizeof counter.name)
      throw std::runtime_error(who + ": counters[" + std::to_string(k) +
                               "].name is empty or not 0-terminated");
    output.counters.push_back({std::string(counter.name, length), counter.value});
  }
  output_hashes_.push_back(output_sha256(output));
  return output;
}

std::string output_sha256(const AlgorithmOutput& output) {
  Sha256 hash;
  hash.update(output.shadowed.data(), output.shadowed.size());
  append_floats(hash, output.visible_fraction);
  append_u32s(hash, output.light_lists.offsets);
  append_u32s(hash, output.light_lists.lights);
  append_u32s(hash, output.light_lists.list_of_sample);
  for (const Aabb& box : output.light_lists.bounds)
    append_floats(hash, {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z});
  for (const auto& [name, value] : output.counters) {
    hash.update(name);
    hash.update("=", 1);
    hash.update(std::to_string(value));
    hash.update("\n", 1);
  }
  return hash.hex_digest();
}

}  // namespace shadowcts
