#pragma once
// A port the suite has never seen, loaded from a shared library through the C ABI
// (include/shadowcts/backend_abi.h) and offered to the runner as ordinary Algorithms, so that its
// outputs are judged exactly like a registered algorithm's.
#include <memory>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/backend_abi.h"

namespace shadowcts {

// One variant of a loaded library, as the certificate and `list` describe it.
struct PluginVariantInfo {
  std::string name;
  std::string algorithm;  // ptsv, psv, metric, softtile, lightassign, other_hard, ...
  OutputKind output = OutputKind::hard_shadow;
  std::uint32_t light_kinds = 0;
  std::uint32_t flags = 0;
  std::uint64_t max_triangles = 0, max_regular_samples = 0, max_sample_triangle_pairs = 0;
  double soft_error_per_sample = 0, soft_error_mean = 0;
};

class PluginAlgorithm;

// A loaded and validated library. The library stays loaded for the life of the process (its
// static strings and functions are referenced by the table).
class PluginBackend {
 public:
  // Loads `path` and validates the table its negotiation fills. Throws InputError naming the
  // library and the field: a missing or unloadable file, no entry point, another ABI version,
  // an identity string that is empty or not printable, no variants, an unknown algorithm or
  // output kind, an output kind that does not fit the algorithm, no or unknown light kinds, a
  // zero size limit, a null run function, a soft-error budget outside [0, 1].
  explicit PluginBackend(const std::string& path);
  ~PluginBackend();
  PluginBackend(const PluginBackend&) = delete;
  PluginBackend& operator=(const PluginBackend&) = delete;

  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }
  const std::string& version() const { return version_; }
  const std::string& build_id() const { return build_id_; }
  const std::vector<PluginVariantInfo>& variants() const { return variants_; }

  // One Algorithm per variant (id: the algorithm's name; backend: the library's name; one
  // variant). They refer to this object, which must outlive them.
  std::unique_ptr<PluginAlgorithm> algorithm(std::size_t variant) const;

 private:
  std::string path_, name_, version_, build_id_;
  void* handle_ = nullptr;
  ShadowctsBackend table_{};
  std::vector<PluginVariantInfo> variants_;
  friend class PluginAlgorithm;
};

class PluginAlgorithm final : public Algorithm {
 public:
  PluginAlgorithm(const PluginBackend& backend, std::size_t variant);
  const AlgorithmInfo& info() const override { return info_; }
  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override;
  SoftErrorBudget soft_error_budget(const std::string& variant) const override;
  // Calls the library's run function with the prepared scene as flat arrays; a status other than
  // OK, or outputs that break the ABI's rules (a shadow bit other than 0/1, a fraction outside
  // [0, 1], a light index out of range, an unterminated counter name), throw: a Crash verdict.
  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override;

  // The SHA-256 of the outputs of every run() call so far, in order (the certificate's output
  // hash; calls that threw have none).
  const std::vector<std::string>& output_hashes() const { return output_hashes_; }

 private:
  const PluginBackend& backend_;
  std::size_t variant_;
  AlgorithmInfo info_;
  mutable std::vector<std::string> output_hashes_;
};

// The SHA-256 of an output's answers (shadow bits, visible fractions or light lists; counters
// included), in a fixed byte order.
std::string output_sha256(const AlgorithmOutput& output);

}  // namespace shadowcts
