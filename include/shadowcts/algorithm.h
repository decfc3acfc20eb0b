#pragma once
// The one interface through which every algorithm x variant x backend plugs into the runner.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

enum class OutputKind { hard_shadow, soft_shadow, light_lists };

struct Capabilities {
  OutputKind output = OutputKind::hard_shadow;
  bool point_light = false;
  bool directional_light = false;
  bool sun_disk = false;
  bool ranged_lights = false;
  bool needs_closed_meshes = false;
  // Every regular view sample must lie inside its own pixel's view frustum (geometry::
  // in_pixel_wedge): bounds built from pixel coordinates (implicit cluster bounds) need it.
  bool needs_samples_in_their_pixels = false;
  // Approximate by design (shadow maps): robust mismatches are its error figures, reported as
  // QualityWarning instead of Fail while their rate stays within the variant's declared ceiling
  // (Algorithm::robust_mismatch_ceiling); beyond it the verdict is Fail.
  bool approximate = false;
  // Upper bound on (regular samples x caster triangles) the algorithm is run on; 0 means none.
  // Brute force uses it so that the plan leaves it out of cases it would take minutes on.
  std::uint64_t max_sample_triangle_pairs = 0;
};

struct AlgorithmInfo {
  std::string id;                     // e.g. "bruteforce", "ptsv"
  std::string backend;                // "reference", "simd", "cuda", "embree", ...
  std::vector<std::string> variants;  // first one is the default; never empty
  std::string summary;
  Capabilities capabilities;
  // A device backend's kernels run by the CUDA-subset emulator (gpu/emulator): its outputs are
  // the kernels', its times the emulator's, which say nothing about a GPU. The runner times it
  // once.
  bool emulated = false;
};

struct Aabb {
  glm::vec3 min{0.0f}, max{0.0f};
};

// Light assignment output: lists of ranged lights per tile or cluster, and which list each sample
// uses. Completeness is checked per sample against the exact oracle; soundness per list against
// the volume the list was culled with.
struct LightLists {
  static constexpr std::uint32_t no_list = 0xFFFFFFFFu;
  // List k holds lights[offsets[k] .. offsets[k + 1]) (indices into Case::ranged_lights);
  // offsets.size() == number of lists + 1.
  std::vector<std::uint32_t> offsets{0};
  std::vector<std::uint32_t> lights;
  // Per list: the axis-aligned box its lights were culled against (it must contain the list's
  // samples; a listed light that cannot touch it is unsound).
  std::vector<Aabb> bounds;
  // Per view sample: its list, or no_list for samples that are not regular.
  std::vector<std::uint32_t> list_of_sample;
};

// The error a soft-shadow variant declares it may make (visible fraction, in [0, 1]); its
// verdict is Fail beyond it.
struct SoftErrorBudget {
  double per_sample = 0.0;  // largest |e| allowed on a robust sample
  double mean = 0.0;        // largest mean |e| over the compared samples
};

// Work counters, in the order the algorithm reports them (deterministic).
using Counters = std::vector<std::pair<std::string, std::uint64_t>>;

// Wall-clock milliseconds of named phases of one run() call, in the order the algorithm declares
// them (Algorithm::timed_phases); measured inside run() with a steady clock (PhaseClock,
// shadowcts/phase_clock.h), so each phase, and their sum, lies within the runner's time of the
// whole call.
using PhaseTimes = std::vector<std::pair<std::string, double>>;

struct AlgorithmOutput {
  // hard_shadow: one entry per view sample, 1 = shadowed; entries of non-regular samples are 0.
  std::vector<std::uint8_t> shadowed;
  // soft_shadow: visible fraction of the sun disk per view sample, in [0, 1].
  std::vector<float> visible_fraction;
  // light_lists.
  LightLists light_lists;
  Counters counters;
  // Optional per-sample work counters (e.g. test-and-set operations, nodes visited), one vector
  // of samples.size() entries per named counter: the report draws them as heat maps.
  std::vector<std::pair<std::string, std::vector<std::uint32_t>>> per_sample_counters;
  // Exactly the phases timed_phases(variant) declares, in that order; empty when it declares none.
  PhaseTimes phase_ms;
};

// Why not every regular sample lies inside its own pixel's view frustum (the check of
// Capabilities::needs_samples_in_their_pixels, for a backend that needs it for some variants
// only), or nullopt.
std::optional<std::string> sample_outside_its_pixel(const Case& c, const ViewSamples& samples);

class Algorithm {
 public:
  virtual ~Algorithm() = default;
  virtual const AlgorithmInfo& info() const = 0;

  // Why the algorithm cannot run this case (NotSupported), or nullopt. The default checks the
  // capabilities against the case's lights and meshes.
  virtual std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                        const std::string& variant) const;

  // soft_shadow outputs: the variant's declared error budget. The default claims exactness.
  virtual SoftErrorBudget soft_error_budget(const std::string& variant) const;

  // Approximate hard-shadow algorithms (Capabilities::approximate): the largest robust mismatch
  // rate (robust mismatches / robust samples, results.json's robust_mismatch_rate) the variant
  // declares it stays within; above it the verdict is Fail, at or below it QualityWarning. The
  // default, 0, allows no robust mismatch (an approximate algorithm must declare its ceiling).
  virtual double robust_mismatch_ceiling(const std::string& variant) const;

  // The phases run() times separately for this variant, e.g. {"build", "query"}: "build" makes
  // the structure the samples are answered with (acceleration structure, hierarchy, tree,
  // clustering, shadow-map rasterization, light BVH), "query" answers the samples with it. The
  // default declares none: only the whole call is timed. The runner checks that every output
  // reports exactly these.
  virtual std::vector<std::string> timed_phases(const std::string& variant) const;

  // Runs on every regular sample of the prepared scene (the runner builds it once per case).
  // Deterministic for any thread count (the outputs; phase_ms are times).
  virtual AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const = 0;

  // Prepares the scene of `c` and `samples`, then runs: for tools and tests that run one
  // algorithm on one case.
  AlgorithmOutput run(const Case& c, const ViewSamples& samples, const std::string& variant) const;
};

}  // namespace shadowcts
