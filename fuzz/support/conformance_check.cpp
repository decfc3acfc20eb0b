#include "conformance_check.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>

#include "runner/case_reproducer.h"
#include "runner/case_shrinking.h"
#include "runner/conformance_violation.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/registry.h"

namespace shadowcts::fuzzing {
namespace {

struct Subject {
  const Algorithm* algorithm;
  std::string variant;
  std::string label() const {
    return algorithm->info().id + ":" + variant + " [" + algorithm->info().backend + "]";
  }
};

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
  return find_violation(*subject.algorithm, subject.variant, c, samples,
                        exact_hard_shadow_truth(c, samples))
      .has_value();
}

[[noreturn]] void report(const std::string& target, const SampleCase& sample_case,
                         const Subject& subject, const Violation& violation) {
  std::cerr << "shadowcts fuzz " << target << ": " << subject.label() << ": " << violation.what
            << "\n";
  try {
    const SampleCase minimal =
        shrink_case(sample_case, violation.sample, [&](const SampleCase& candidate) {
          return violation_on(*subject.algorithm, subject.variant, candidate).has_value();
        });
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
  const std::optional<HardShadowTruth> truth =
      exact_hard_shadow_truth(sample_case.c, sample_case.samples);
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
      if (auto violation =
              find_violation(*algorithm, variant, sample_case.c, sample_case.samples, compared))
        report(target, sample_case, subject, *violation);
    }
  }
}

}  // namespace shadowcts::fuzzing
