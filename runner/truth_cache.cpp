#include "truth_cache.h"

#include <elf.h>
#include <link.h>
#include <unistd.h>

#include <chrono>
#include <concepts>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>

#include "atomic_file.h"
#include "interrupt_cleanup.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

constexpr std::string_view entry_magic = "shadowcts truth cache 1\n";

// Plain little-endian bytes of trivially copyable values (the cache never leaves the machine and
// build that wrote it: the build id is part of every entry).
class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put_string(std::string_view text) {
    put<std::uint64_t>(text.size());
    bytes_.append(text);
  }
  // One field of a truth (each_field below lists them once for writing and reading).
  template <class T>
  void field(const T& value) {
    put(value);
  }
  template <class T>
  void field(const std::vector<T>& values) {
    put_vector(values);
  }
  void field(const std::string& text) { put_string(text); }
  void field(bool flag) { put<std::uint8_t>(flag); }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what ByteWriter wrote; throws std::runtime_error past the end (a damaged entry).
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> get_vector() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(T)) throw std::runtime_error("truncated");
    std::vector<T> values(n);
    if (n) std::memcpy(values.data(), take(n * sizeof(T)).data(), n * sizeof(T));
    return values;
  }
  std::string get_string() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > bytes_.size() - at_) throw std::runtime_error("truncated");
    return std::string(take(n));
  }
  template <class T>
  void field(T& value) {
    value = get<T>();
  }
  template <class T>
  void field(std::vector<T>& values) {
    values = get_vector<T>();
  }
  void field(std::string& text) { text = get_string(); }
  void field(bool& flag) { flag = get<std::uint8_t>() != 0; }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::string_view take(std::size_t n) {
    if (n > bytes_.size() - at_) throw std::runtime_error("truncated");
    const std::string_view part = bytes_.substr(at_, n);
    at_ += n;
    return part;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 1469598103934665603ull) {
  for (unsigned char b : bytes) {
    hash ^= b;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

void put_vec3(ByteWriter& w, const glm::vec3& v) {
  w.put(v.x);
  w.put(v.y);
  w.put(v.z);
}

// Everything the oracles may read, field by field (no struct padding in the bytes): the
// oracle, the case's geometry, lights, camera and band, and every sample.
std::string truth_inputs(std::string_view oracle, const Case& c, const ViewSamples& samples) {
  ByteWriter w;
  w.put_string(oracle);
  w.put<std::uint64_t>(c.meshes.size());
  for (const Mesh& m : c.meshes) {
    w.put<std::uint8_t>(m.closed);
    w.put<std::uint8_t>(m.caster);
  }
  w.put<std::uint64_t>(c.triangles.size());
  for (const Triangle& t : c.triangles) {
    put_vec3(w, t.v0);
    put_vec3(w, t.v1);
    put_vec3(w, t.v2);
    w.put(t.mesh);
  }
  w.put<std::uint8_t>(c.light.has_value());
  if (c.light) {
    w.put<std::uint8_t>(std::uint8_t(c.light->kind));
    put_vec3(w, c.light->position);
    put_vec3(w, c.light->direction);
    w.put(c.light->angular_radius);
  }
  w.put<std::uint64_t>(c.ranged_lights.size());
  for (const RangedLight& l : c.ranged_lights) {
    w.put<std::uint8_t>(std::uint8_t(l.kind));
    put_vec3(w, l.centre);
    w.put(l.range);
    put_vec3(w, l.direction);
    w.put(l.cone_half_angle);
  }
  put_vec3(w, c.camera.position);
  put_vec3(w, c.camera.target);
  put_vec3(w, c.camera.up);
  w.put(c.camera.vertical_fov_degrees);
  w.put(c.camera.near_plane);
  w.put(c.camera.far_plane);
  w.put(c.camera.width);
  w.put(c.camera.height);
  w.put(c.parameters.eps_rel);
  w.put(c.parameters.seed);
  w.put(samples.width);
  w.put(samples.height);
  w.put<std::uint64_t>(samples.samples.size());
  for (const ViewSample& s : samples.samples) {
    put_vec3(w, s.position);
    put_vec3(w, s.normal);
    w.put(s.receiver);
    w.put(s.pixel_x);
    w.put(s.pixel_y);
    w.put<std::uint8_t>(std::uint8_t(s.sample_class));
  }
  return std::move(w.bytes());
}

// Each truth's fields, in entry order, for ByteWriter (const truth) and ByteReader alike.
template <class T, class Truth>
concept truth_of = std::same_as<std::remove_const_t<T>, Truth>;

template <class Io, truth_of<HardShadowTruth> T>
void each_field(Io& io, T& t) {
  io.field(t.method);
  io.field(t.exact);
  io.field(t.eps_rel);
  io.field(t.tau);
  io.field(t.shadowed);
  io.field(t.band);
  io.field(t.robust_exponent);
}

template <class Io, truth_of<SoftShadowTruth> T>
void each_field(Io& io, T& t) {
  io.field(t.method);
  io.field(t.exact);
  io.field(t.eps_rel);
  io.field(t.tau);
  io.field(t.visible_fraction);
  io.field(t.error_bound);
  io.field(t.band_sensitivity);
  io.field(t.robust);
  io.field(t.compared);
  io.field(t.candidate_triangles);
  io.field(t.fast_path_samples);
}

template <class Io, truth_of<LightAssignmentTruth> T>
void each_field(Io& io, T& t) {
  io.field(t.method);
  io.field(t.exact);
  io.field(t.normal_rule);
  io.field(t.eps_rel);
  io.field(t.tau);
  io.field(t.offsets);
  io.field(t.lights);
  io.field(t.ambiguous_offsets);
  io.field(t.ambiguous_lights);
  io.field(t.candidate_pairs);
  io.field(t.band_move_pairs);
}

// Entry layout: magic, build id, inputs, oracle time, truth, checksum of everything before it.
template <class Truth>
Truth cached_truth(const std::filesystem::path& dir, std::string_view oracle, const Case& c,
                   const ViewSamples& samples, const std::function<Truth()>& compute,
                   TruthCacheUse& use) {
  use.used = true;
  const std::string build_id = program_build_id();
  auto timed_compute = [&] {
    const auto start = std::chrono::steady_clock::now();
    Truth truth = compute();
    use.computed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return truth;
  };
  if (build_id.empty()) {
    use.note = "off: the program has no GNU build id to tie entries to";
    return timed_compute();
  }
  const std::string inputs = truth_inputs(oracle, c, samples);
  // The name leaves the build id out, so a rebuilt program replaces its predecessor's entry for
  // the same case instead of piling up stale ones.
  use.entry = std::string(oracle) + "." + hex64(fnv1a(inputs)) + ".truth";
  const std::filesystem::path path = dir / use.entry;

  std::ifstream in(path, std::ios::binary);
  if (in) {
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      if (bytes.size() < entry_magic.size() + 8 ||
          std::string_view(bytes).substr(0, entry_magic.size()) != entry_magic)
        throw std::runtime_error("not an entry");
      const std::string_view body = std::string_view(bytes).substr(0, bytes.size() - 8);
      std::uint64_t checksum;
      std::memcpy(&checksum, bytes.data() + bytes.size() - 8, 8);
      if (checksum != fnv1a(body)) throw std::runtime_error("checksum");
      ByteReader r(body.substr(entry_magic.size()));
      if (r.get_string() != build_id || r.get_string() != inputs) {
        use.note = "entry of another build or other inputs replaced";
      } else {
        const double computed_ms = r.get<double>();
        Truth truth;
        each_field(r, truth);
        if (!r.done()) throw std::runtime_error("trailing bytes");
        use.hit = true;
        use.computed_ms = computed_ms;
        return truth;
      }
    } catch (const std::exception&) {
      use.note = "damaged entry recomputed";
    }
  }

  Truth truth = timed_compute();
  ByteWriter w;
  w.bytes().append(entry_magic);
  w.put_string(build_id);
  w.put_string(inputs);
  w.put(use.computed_ms);
  each_field(w, truth);
  w.put(fnv1a(w.bytes()));
  // A private temporary per process, then one rename: concurrent runs of the same case each
  // write a complete entry and the last rename wins.
  std::filesystem::path temporary = path;
  temporary += "." + std::to_string(::getpid());
  const InterruptCleanup temporary_on_interrupt = InterruptCleanup::remove_path(temporary);
  try {
    write_file_atomically(temporary, w.bytes());
    std::filesystem::rename(temporary, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    use.note = std::string("not stored: ") + e.what();
  }
  return truth;
}

}  // namespace

std::string program_build_id() {
  static const std::string id = [] {
    std::string found;
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* data) -> int {
          // The first object is the program itself.
          auto& out = *static_cast<std::string*>(data);
          for (int k = 0; k < info->dlpi_phnum; ++k) {
            const ElfW(Phdr)& segment = info->dlpi_phdr[k];
            if (segment.p_type != PT_NOTE) continue;
            const char* at = reinterpret_cast<const char*>(info->dlpi_addr + segment.p_vaddr);
            const char* end = at + segment.p_memsz;
            while (at + sizeof(ElfW(Nhdr)) <= end) {
              ElfW(Nhdr) note;
              std::memcpy(&note, at, sizeof note);
              const char* name = at + sizeof note;
              const char* desc = name + ((note.n_namesz + 3) & ~3u);
              if (note.n_type == NT_GNU_BUILD_ID && note.n_namesz == 4 &&
                  std::memcmp(name, "GNU", 4) == 0 && desc + note.n_descsz <= end) {
                for (std::uint32_t b = 0; b < note.n_descsz; ++b) {
                  char hex[3];
                  std::snprintf(hex, sizeof hex, "%02x", static_cast<unsigned char>(desc[b]));
                  out += hex;
                }
                return 1;
              }
              at = desc + ((note.n_descsz + 3) & ~3u);
            }
          }
          return 1;
        },
        &found);
    return found;
  }();
  return id;
}

TruthCache::TruthCache(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error || !std::filesystem::is_directory(dir_))
    throw UsageError("--truth-cache " + dir_.string() + ": cannot create the folder" +
                     (error ? ": " + error.message() : std::string(": a file is in the way")));
}

void record_truth_cache_use(const std::vector<TruthCacheUse>& uses, OracleSummary& oracle) {
  if (uses.empty() || !uses.front().used) return;
  nlohmann::ordered_json entries = nlohmann::ordered_json::array();
  std::size_t hits = 0;
  double computed_ms = 0;
  std::string notes;
  for (const TruthCacheUse& use : uses) {
    entries.push_back({{"entry", use.entry},
                       {"hit", use.hit},
                       {"computed_ms", use.computed_ms},
                       {"note", use.note}});
    hits += use.hit;
    if (use.hit) computed_ms += use.computed_ms;
    if (!use.note.empty()) notes += "; " + use.note;
  }
  oracle.details["truth_cache"] = entries;
  std::ostringstream line;
  line << "; truth cache: " << hits << " of " << uses.size() << " from the cache";
  if (hits)
    line << " (computed earlier in " << std::fixed << std::setprecision(1) << computed_ms << " ms)";
  oracle.plan_line += line.str() + notes;
}

HardShadowTruth TruthCache::get(std::string_view oracle, const Case& c, const ViewSamples& samples,
                                const std::function<HardShadowTruth()>& compute,
                                TruthCacheUse& use) const {
  return cached_truth(dir_, oracle, c, samples, compute, use);
}

SoftShadowTruth TruthCache::get(std::string_view oracle, const Case& c, const ViewSamples& samples,
                                const std::function<SoftShadowTruth()>& compute,
                                TruthCacheUse& use) const {
  return cached_truth(dir_, oracle, c, samples, compute, use);
}

LightAssignmentTruth TruthCache::get(std::string_view oracle, const Case& c,
                                     const ViewSamples& samples,
                                     const std::function<LightAssignmentTruth()>& compute,
                                     TruthCacheUse& use) const {
  return cached_truth(dir_, oracle, c, samples, compute, use);
}

}  // namespace shadowcts
