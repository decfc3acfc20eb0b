#include "conformance_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>

#include "reproducer.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"

namespace shadowcts::fuzzing {
namespace {

bool robust(BandClass band) {
  return band == BandClass::robust_lit || band == BandClass::robust_shadowed;
}

struct Subject {
  const Algorithm* algorithm;
  std::string variant;
  std::string label() const {
    return algorithm->info().id + ":" + variant + " [" + algorithm->info().backend + "]";
  }
};

// What went wrong for one algorithm on one case, or nullopt. `sample` is the first failing
// sample where one exists (a throw has none).
struct Violation {
  std::string what;
  std::optional<std::size_t> sample;
};

std::optional<Violation> find_violation(const Subject& subject, const Case& original,
                                        const ViewSamples& samples,
                                        const std::optional<HardShadowTruth>& truth) {
  const OutputKind kind = subject.algorithm->info().capabilities.output;
  const Case c = kind == OutputKind::hard_shadow ? hard_shadow_view(original) : original;
  if (subject.algorithm->unsupported_reason(c, samples, subject.variant)) return std::nullopt;
  AlgorithmOutput output;
  try {
    output = subject.algorithm->run(c, samples, subject.variant);
  } catch (const std::exception& e) {
    return Violation{std::string("threw on a valid case: ") + e.what(), std::nullopt};
  }
  if (kind == OutputKind::soft_shadow) {
    if (output.visible_fraction.size() != samples.samples.size())
      return Violation{"visible_fraction has the wrong size", std::nullopt};
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      const float f = output.visible_fraction[i];
      if (!(f >= 0.0f && f <= 1.0f))
        return Violation{"visible fraction " + std::to_string(f) + " is not in [0, 1]", i};
    }
    return std::nullopt;
  }
  if (kind != OutputKind::hard_shadow || !truth) return std::nullopt;
  if (output.shadowed.size() != samples.samples.size())
    return Violation{"shadow mask has the wrong size", std::nullopt};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (!robust(truth->band[i]) || output.shadowed[i] == truth->shadowed[i]) continue;
    std::ostringstream what;
    const ViewSample& s = samples.samples[i];
    what.precision(9);
    what << (truth->shadowed[i] ? "leak" : "false shadow") << " at robust sample " << i << " ("
         << s.position.x << ", " << s.position.y << ", " << s.position.z << "), receiver "
         << s.receiver << ": exact oracle says " << (truth->shadowed[i] ? "shadowed" : "lit");
    return Violation{what.str(), i};
  }
  return std::nullopt;
}

// The hard-shadow truth, of the sun disk's centre direction for a sun disk (as the runner
// compares hard-shadow algorithms there).
std::optional<HardShadowTruth> exact_truth(const Case& c, const ViewSamples& samples) {
  if (!c.light) return std::nullopt;
  // The view is a temporary: drop the lazy exponents that would refer to it (no check here
  // needs the mismatch curve).
  HardShadowTruth truth = exact_hard_shadow_oracle(hard_shadow_view(c), samples);
  truth.lazy.reset();
  return truth;
}

std::optional<Violation> violation_on(const Subject& subject, const SampleCase& candidate) {
  return find_violation(subject, candidate.c, candidate.samples,
                        exact_truth(candidate.c, candidate.samples));
}

// Greedy shrinking: keep only the failing sample, then drop every triangle (and the samples'
// dependence on it) whose removal keeps the violation. Quadratic, but fuzz cases are small.
SampleCase shrink(const SampleCase& original, const Subject& subject, const Violation& violation) {
  SampleCase best = original;
  if (violation.sample && original.explicit_samples) {
    SampleCase single = original;
    single.samples.samples = {original.samples.samples[*violation.sample]};
    single.samples.samples[0].pixel_x = 0;
    single.finish();
    if (violation_on(subject, single)) best = single;
  }
  for (std::size_t t = best.c.triangles.size(); t-- > 0;) {
    bool is_receiver = false;
    for (const ViewSample& s : best.samples.samples) is_receiver |= s.receiver == t;
    if (is_receiver || best.c.triangles.size() == 1) continue;
    SampleCase candidate = best;
    // A mesh that loses a triangle is no longer closed (and the reproducer's loader agrees).
    candidate.c.meshes[candidate.c.triangles[t].mesh].closed = false;
    candidate.c.triangles.erase(candidate.c.triangles.begin() + std::ptrdiff_t(t));
    for (ViewSample& s : candidate.samples.samples)
      if (s.receiver != no_receiver && s.receiver > t) --s.receiver;
    candidate.finish();
    if (violation_on(subject, candidate)) best = std::move(candidate);
  }
  return best;
}

std::string reproducer_folder(const std::string& target, const SampleCase& minimal) {
  const char* root = std::getenv("SHADOWCTS_FUZZ_REPRODUCERS");
  // Named by a hash of the minimal case's triangles and samples: the same finding lands in the
  // same folder on every run.
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](const void* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
      hash ^= static_cast<const unsigned char*>(data)[i];
      hash *= 1099511628211ull;
    }
  };
  mix(minimal.c.triangles.data(), minimal.c.triangles.size() * sizeof(Triangle));
  for (const ViewSample& s : minimal.samples.samples) mix(&s.position, sizeof(s.position));
  char name[32];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(hash));
  return std::string(root ? root : "fuzz-reproducers") + "/" + target + "-" + name;
}

// Loads the written reproducer the way `shadowcts run --case` does and checks it again.
bool replay_reproduces(const std::string& manifest, const Subject& subject) {
  Case c = load_case_manifest(manifest);
  ViewSamples samples = read_gbuffer_exr(c.gbuffer_path);
  classify_samples(c, samples, c.gbuffer_path);
  return find_violation(subject, c, samples, exact_truth(c, samples)).has_value();
}

[[noreturn]] void report(const std::string& target, const SampleCase& sample_case,
                         const Subject& subject, const Violation& violation) {
  std::cerr << "shadowcts fuzz " << target << ": " << subject.label() << ": " << violation.what
            << "\n";
  try {
    const SampleCase minimal = shrink(sample_case, subject, violation);
    const std::string manifest =
        write_reproducer(reproducer_folder(target, minimal), minimal.c, minimal.samples);
    std::cerr << "minimal reproducer (" << minimal.c.triangles.size() << " triangles, "
              << minimal.samples.samples.size() << " samples): " << manifest << "\n"
              << "replay: shadowcts run --case " << manifest << " --algorithm "
              << subject.algorithm->info().id << ":" << subject.variant << " --backend "
              << subject.algorithm->info().backend << "\n"
              << "the replayed reproducer "
              << (replay_reproduces(manifest, subject) ? "fails the same way"
                                                       : "does NOT fail (report this too)")
              << "\n";
  } catch (const std::exception& e) {
    std::cerr << "writing the reproducer failed: " << e.what() << "\n";
  }
  std::abort();
}

}  // namespace

void check_every_algorithm(const SampleCase& sample_case, const std::string& target,
                           const std::vector<KnownLimit>& known_limits) {
  const std::optional<HardShadowTruth> truth = exact_truth(sample_case.c, sample_case.samples);
  for (const auto& algorithm : builtin_registry().algorithms()) {
    // Approximate algorithms (shadow maps up to 8k x 8k) would take seconds per input and are
    // exempt from the comparison; the fuzzers spend their time on the exact ones.
    if (algorithm->info().capabilities.approximate) continue;
    // A known limit: run it (no crash, no throw), compare nothing on the samples it concerns.
    std::optional<HardShadowTruth> compared = truth;
    for (const KnownLimit& k : known_limits) {
      if (k.algorithm_id != algorithm->info().id || !compared) continue;
      if (k.samples.empty())
        compared.reset();
      else
        for (const std::size_t i : k.samples) compared->band.at(i) = BandClass::not_compared;
    }
    for (const std::string& variant : algorithm->info().variants) {
      const Subject subject{algorithm.get(), variant};
      if (auto violation = find_violation(subject, sample_case.c, sample_case.samples, compared))
        report(target, sample_case, subject, *violation);
    }
  }
}

}  // namespace shadowcts::fuzzing
