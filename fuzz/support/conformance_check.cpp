#include "conformance_check.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <map>
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

constexpr const char* differs_prefix = "differs from ";

// Whether a subject keeps the fuzz property on a case, as check_every_algorithm judges it.
using Check = std::function<std::optional<Violation>(const SampleCase&)>;

// The reference backend of the subject's algorithm, or nullptr (the subject is one, or has none).
const Algorithm* reference_of(const Subject& subject) {
  const AlgorithmInfo& info = subject.algorithm->info();
  return info.backend == "reference" ? nullptr : builtin_registry().find(info.id, "reference");
}

// The property of one subject on a case whose truths are known.
std::optional<Violation> subject_violation(const Subject& subject, const SampleCase& sample_case,
                                           const ExactTruths& truths,
                                           std::map<std::string, AlgorithmOutput>& references) {
  const Algorithm& algorithm = *subject.algorithm;
  const OutputKind kind = algorithm.info().capabilities.output;
  const Case& c = sample_case.c;
  const ViewSamples& samples = sample_case.samples;
  std::optional<AlgorithmOutput> output;
  if (auto violation = find_violation(algorithm, subject.variant, c, samples, truths, &output))
    return violation;
  if (!output) return std::nullopt;  // NotSupported
  const Algorithm* reference = kind == OutputKind::hard_shadow ? nullptr : reference_of(subject);
  if (!reference || reference->unsupported_reason(c, samples, subject.variant)) return std::nullopt;
  const std::string key = reference->info().id + ":" + subject.variant;
  auto it = references.find(key);
  if (it == references.end())
    it = references.emplace(key, reference->run(c, samples, subject.variant)).first;
  if (auto difference = difference_from_reference(kind, samples, *output, it->second)) {
    difference->what = differs_prefix + key + " [reference]: " + difference->what;
    return difference;
  }
  return std::nullopt;
}

// The truths check_every_algorithm judges by: soft fractions for gross errors only (see
// conformance_check.h).
ExactTruths fuzz_truths(const SampleCase& sample_case) {
  ExactTruths truths = exact_truths(sample_case.c, sample_case.samples);
  truths.soft_gross_errors_only = true;
  return truths;
}

Check check_of(const Subject& subject) {
  return [subject](const SampleCase& candidate) {
    std::map<std::string, AlgorithmOutput> references;
    return subject_violation(subject, candidate, fuzz_truths(candidate), references);
  };
}

// Loads the written reproducer the way `shadowcts run --case` does and checks it again.
bool replay_reproduces(const std::string& manifest, const Check& check) {
  SampleCase replayed;
  replayed.c = load_case_manifest(manifest);
  replayed.samples = read_gbuffer_exr(replayed.c.gbuffer_path);
  classify_samples(replayed.c, replayed.samples, replayed.c.gbuffer_path);
  return check(replayed).has_value();
}

[[noreturn]] void report(const std::string& target, const SampleCase& sample_case,
                         const Subject& subject, const Violation& violation) {
  std::cerr << "shadowcts fuzz " << target << ": " << subject.label() << ": " << violation.what
            << "\n";
  try {
    const Check check = check_of(subject);
    const SampleCase minimal =
        shrink_case(sample_case, violation.sample,
                    [&](const SampleCase& candidate) { return check(candidate).has_value(); });
    const std::string manifest =
        write_reproducer(reproducer_folder(target, minimal), minimal.c, minimal.samples);
    std::cerr << "minimal reproducer (" << minimal.c.triangles.size() << " triangles, "
              << minimal.samples.samples.size() << " samples): " << manifest << "\n"
              << "replay: shadowcts run --case " << manifest << " --algorithm "
              << subject.algorithm->info().id << ":" << subject.variant << " --backend "
              << subject.algorithm->info().backend
              << (violation.what.rfind(differs_prefix, 0) == 0
                      ? " --backend reference (they differ)"
                      : "")
              << "\n"
              << "the replayed reproducer "
              << (replay_reproduces(manifest, check) ? "fails the same way"
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
  const ExactTruths truths = fuzz_truths(sample_case);
  // The reference outputs the ports are diffed against, by "id:variant", run once per case.
  std::map<std::string, AlgorithmOutput> references;
  for (const auto& algorithm : builtin_registry().algorithms()) {
    // Approximate algorithms (shadow maps up to 8k x 8k) would take seconds per input and are
    // exempt from the comparison; the fuzzers spend their time on the exact ones.
    if (algorithm->info().capabilities.approximate) continue;
    for (const std::string& variant : algorithm->info().variants) {
      // A known limit: run it (no crash, no throw), compare nothing on the samples it concerns.
      ExactTruths compared = truths;
      for (const KnownLimit& k : known_limits) {
        if (k.algorithm_id != algorithm->info().id || !compared.hard) continue;
        if (!k.variant.empty() && k.variant != variant) continue;
        if (k.samples.empty())
          compared.hard.reset();
        else
          for (const std::size_t i : k.samples) compared.hard->band.at(i) = BandClass::not_compared;
      }
      const Subject subject{algorithm.get(), variant};
      if (auto violation = subject_violation(subject, sample_case, compared, references))
        report(target, sample_case, subject, *violation);
    }
  }
}

}  // namespace shadowcts::fuzzing
