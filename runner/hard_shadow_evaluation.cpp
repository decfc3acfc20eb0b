#include "hard_shadow_evaluation.h"

#include <chrono>
#include <functional>
#include <iomanip>
#include <sstream>
#include <vector>

#include <boost/math/distributions/binomial.hpp>

#include "hard_shadow_images.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

// Above this many triangles the automatic choice is the fast oracle: the exact oracle's
// candidate structure and exact predicates then cost more memory and time than a CI run should
// spend.
constexpr std::uint64_t exact_oracle_triangle_limit = 4'000'000;

// When the fast oracle judges the Embree peer, the judge and the judged share Embree: the exact
// oracle re-decides this many of the peer's robust samples (every k-th, so the same ones every
// run).
constexpr std::size_t embree_spot_check_samples = 4096;

// The lower confidence bound (Clopper-Pearson, one-sided) on the rate behind `mismatches` of
// `robust` samples: a map whose rate is at its ceiling shows a bound above it with probability at
// most statistical_verdict_failure_probability, however few samples the case has.
double mismatch_rate_lower_bound(std::uint64_t mismatches, std::uint64_t robust) {
  return boost::math::binomial_distribution<double>::find_lower_bound_on_p(
      double(robust), double(mismatches), statistical_verdict_failure_probability);
}

class HardShadowEvaluation : public CaseEvaluation {
 public:
  HardShadowEvaluation(const Case& c, const ViewSamples& samples,
                       const std::vector<std::uint8_t>& receiver_ambiguous, bool exact,
                       const ImageTarget& images, const std::string& image_folder,
                       const TruthCache* cache)
      : case_(c), samples_(samples), images_(images) {
    const auto start = std::chrono::steady_clock::now();
    const std::function<HardShadowTruth()> compute = [&] {
      return exact ? exact_hard_shadow_oracle(c, samples) : embree_hard_shadow_oracle(c, samples);
    };
    TruthCacheUse cache_use;
    truth_ = cache
                 ? cache->get(exact ? "hard.exact" : "hard.embree", c, samples, compute, cache_use)
                 : compute();
    // The exact oracle's exponents stay on demand; the fast oracle has none (hard_shadow_oracle.h).
    if (cache_use.hit && exact) truth_.lazy = exact_robust_exponents_on_demand(c, samples);
    // The answer depends on which triangle is the receiver (the half-space rule): where the
    // engine's receiver could be either of two, no level of the band can vouch for it.
    for (std::size_t i = 0; i < receiver_ambiguous.size(); ++i)
      if (receiver_ambiguous[i] && truth_.band[i] != BandClass::not_compared) {
        truth_.band[i] = BandClass::ambiguous;
        truth_.robust_exponent[i] = ambiguous_at_every_exponent;
      }
    oracle_.time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    oracle_.method = truth_.method;
    oracle_.exact = truth_.exact;
    std::uint64_t robust_lit = 0, robust_shadowed = 0, ambiguous = 0;
    for (BandClass b : truth_.band) {
      robust_lit += b == BandClass::robust_lit;
      robust_shadowed += b == BandClass::robust_shadowed;
      ambiguous += b == BandClass::ambiguous;
    }
    // The share of the compared samples that the band leaves unverified.
    const std::uint64_t classified = robust_lit + robust_shadowed + ambiguous;
    const double ambiguous_fraction = classified ? double(ambiguous) / double(classified) : 0.0;
    std::ostringstream line;
    line << truth_.method << ", eps_rel " << truth_.eps_rel << " (tau " << truth_.tau
         << "): " << robust_lit << " robust-lit, " << robust_shadowed << " robust-shadowed, "
         << ambiguous << " ambiguous (" << std::fixed << std::setprecision(2)
         << 100.0 * ambiguous_fraction << " %)";
    if (!exact)
      line << "; it shares Embree with the embree peer, so the exact oracle spot-checks up to "
           << embree_spot_check_samples << " of that peer's robust samples";
    oracle_.plan_line = line.str();
    oracle_.details = {{"eps_rel", truth_.eps_rel}, {"tau", truth_.tau},
                       {"robust_lit", robust_lit},  {"robust_shadowed", robust_shadowed},
                       {"ambiguous", ambiguous},    {"ambiguous_fraction", ambiguous_fraction}};
    if (images.enabled)
      oracle_.details["mask_image"] =
          write_oracle_images(images.out_dir, image_folder, samples, truth_);
    record_truth_cache_use({cache_use}, oracle_);
  }

  void judge(const AlgorithmOutput& output, RunRecord& record) const override {
    const bool approximate = record.approximate;
    const HardShadowComparison h = compare_hard_shadows(output.shadowed, truth_);
    const bool judged_by_itself = !truth_.exact && record.algorithm == "embree";
    const std::uint64_t mismatches = h.leaks + h.false_shadows;
    const double rate = h.robust ? double(mismatches) / double(h.robust) : 0.0;
    const double lowest =
        approximate && h.robust ? mismatch_rate_lower_bound(mismatches, h.robust) : 0.0;
    if (record.verdict != Verdict::fail) {
      record.verdict = h.verdict;
      record.reason = h.reason;
      // Approximate baselines (shadow maps): their mismatches are the figures, not a failure,
      // up to the rate the variant declares; above it the answer is wrong, not approximate. On
      // few samples the rate is a noisy estimate: the map is broken only where even the rate's
      // lower confidence bound lies above the ceiling.
      if (approximate && h.verdict == Verdict::fail) {
        const bool above = lowest > record.mismatch_ceiling;
        std::ostringstream figures;
        figures << "robust mismatch rate " << std::setprecision(4) << rate << " (" << mismatches
                << " of " << h.robust << ", at least " << lowest << " at confidence 1 - "
                << statistical_verdict_failure_probability << ")" << (above ? " above" : " within")
                << " the declared ceiling " << record.mismatch_ceiling;
        if (above) {
          record.reason = figures.str() + ": " + h.reason;
        } else {
          record.verdict = Verdict::quality_warning;
          record.reason = "approximate by design (" + figures.str() + "): " + h.reason;
        }
      }
      if (h.robust == 0) {
        record.verdict = Verdict::not_supported;
        record.reason = nothing_to_judge(samples_, h.ambiguous) + " (" +
                        std::to_string(h.ambiguous_disagreements) + " of the ambiguous differ)";
      }
    }
    nlohmann::ordered_json curve = nlohmann::ordered_json::array();
    for (const auto& [exponent, at_exponent] : h.mismatch_curve)
      curve.push_back({{"eps_rel_log2", exponent}, {"robust_mismatches", at_exponent}});
    record.error = {
        {"compared", h.compared},           {"robust", h.robust},
        {"ambiguous", h.ambiguous},         {"leaks", h.leaks},
        {"false_shadows", h.false_shadows}, {"ambiguous_disagreements", h.ambiguous_disagreements},
        {"robust_mismatch_rate", rate},     {"mismatch_curve", curve}};
    if (approximate) {
      record.error["robust_mismatch_rate_lower_bound"] = lowest;
      record.error["mismatch_ceiling"] = record.mismatch_ceiling;
    }
    if (judged_by_itself) spot_check_with_exact_oracle(output, record);
    record.headline = "leaks " + std::to_string(h.leaks) + ", false shadows " +
                      std::to_string(h.false_shadows) + ", ambiguous " +
                      std::to_string(h.ambiguous_disagreements) + "/" +
                      std::to_string(h.ambiguous) + " differ";
    if (images_.enabled)
      record.images =
          write_algorithm_images(images_.out_dir, record, samples_, output.shadowed, truth_);
  }

 private:
  // The exact oracle on a deterministic subset of the samples the fast oracle calls robust; a
  // robust mismatch there fails the record like any other.
  void spot_check_with_exact_oracle(const AlgorithmOutput& output, RunRecord& record) const {
    std::vector<std::size_t> robust;
    for (std::size_t i = 0; i < truth_.band.size(); ++i)
      if (truth_.band[i] == BandClass::robust_lit || truth_.band[i] == BandClass::robust_shadowed)
        robust.push_back(i);
    const std::size_t step = robust.size() / embree_spot_check_samples + 1;
    // Only the checked samples, compacted: the exact oracle classifies each sample on its own, so
    // this is its answer on the full set, without a second copy of every view sample.
    std::vector<std::size_t> picked;
    for (std::size_t k = 0; k < robust.size(); k += step) picked.push_back(robust[k]);
    ViewSamples subset;
    subset.width = std::uint32_t(picked.size());
    subset.height = 1;
    subset.samples.reserve(picked.size());
    for (std::size_t i : picked) subset.samples.push_back(samples_.samples[i]);
    HardShadowTruth exact = exact_hard_shadow_oracle(case_, subset);
    exact.lazy.reset();  // refers to `subset`, which ends here
    std::uint64_t checked = 0, mismatches = 0;
    for (std::size_t k = 0; k < picked.size(); ++k) {
      if (exact.band[k] != BandClass::robust_lit && exact.band[k] != BandClass::robust_shadowed)
        continue;
      ++checked;
      mismatches += output.shadowed[picked[k]] != exact.shadowed[k];
    }
    record.error["exact_spot_check"] = {{"checked", checked}, {"robust_mismatches", mismatches}};
    if (mismatches != 0 && record.verdict != Verdict::fail && !did_not_finish(record.verdict)) {
      record.verdict = Verdict::fail;
      record.reason = "the exact oracle's spot check of " + std::to_string(checked) +
                      " robust samples (the fast oracle shares Embree with this algorithm): " +
                      std::to_string(mismatches) + " differ";
    }
  }

  std::vector<std::size_t> robust_mismatches(const AlgorithmOutput& output) const override {
    std::vector<std::size_t> wrong;
    for (std::size_t i = 0; i < truth_.band.size(); ++i)
      if ((truth_.band[i] == BandClass::robust_lit ||
           truth_.band[i] == BandClass::robust_shadowed) &&
          (output.shadowed[i] != 0) != (truth_.shadowed[i] != 0))
        wrong.push_back(i);
    return wrong;
  }

  const Case& case_;
  const ViewSamples& samples_;
  ImageTarget images_;
  HardShadowTruth truth_;
};

}  // namespace

std::unique_ptr<CaseEvaluation> evaluate_hard_shadows(
    const Case& hard_case, const ViewSamples& samples,
    const std::vector<std::uint8_t>& receiver_ambiguous, OracleChoice choice,
    const ImageTarget& images, const std::string& image_folder, std::vector<std::string>& left_out,
    const TruthCache* cache) {
  const bool exact =
      choice == OracleChoice::exact || (choice == OracleChoice::automatic &&
                                        hard_case.triangles.size() <= exact_oracle_triangle_limit);
  if (!exact)
    left_out.push_back(
        choice == OracleChoice::embree
            ? "exact hard-shadow oracle: --oracle embree asked for the fast one (band estimated)"
            : "exact hard-shadow oracle: " + std::to_string(hard_case.triangles.size()) +
                  " triangles exceed its limit of " + std::to_string(exact_oracle_triangle_limit) +
                  "; the fast oracle's band is estimated");

  return std::make_unique<HardShadowEvaluation>(hard_case, samples, receiver_ambiguous, exact,
                                                images, image_folder, cache);
}

}  // namespace shadowcts
