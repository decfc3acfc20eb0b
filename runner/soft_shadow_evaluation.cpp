#include "soft_shadow_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

#include "image_paths.h"
#include "oracles/soft_shadow/soft_shadow_comparison.h"
#include "sample_colours.h"
#include "shadowcts/image_file.h"
#include "shadowcts/soft_shadow_oracle.h"

namespace shadowcts {
namespace {

// The exact oracle's cost follows the projected casters it unites per sample, k, not the sample
// count (estimate_exact_soft_shadow_work). Its one-core seconds are estimated here as 2 µs per
// sample + 150 µs x sum(k) + 150 ns x sum(k^2), fitted on the 2-core machines (2026-12-05): a
// projection costs 60-100 µs for a closed mesh and for foliage.10k, 154 µs at foliage.100k in
// 1080p; crossing grass blades under a 60-degree sun (k about 1,300) 460 µs, which the k^2 term
// covers. Above the limit the automatic choice is the sampled oracle; the estimate visits every
// 16th regular sample (docs/soft-shadow-oracle.md).
constexpr double exact_oracle_seconds_per_sample = 2e-6;  // its cone query, with nothing to unite
constexpr double exact_oracle_seconds_per_projection = 150e-6;
constexpr double exact_oracle_seconds_per_squared_projection = 150e-9;
constexpr double exact_oracle_seconds_limit = 300.0;
constexpr std::uint32_t exact_oracle_estimate_stride = 16;
// 1024 stratified rays: error bound 0.102 per sample at failure probability 1e-9.
constexpr std::uint32_t sampled_rays_per_sample = 1024;

std::uint8_t to_byte(double v) {
  return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255));
}

// Visible fraction as grey (black: umbra, white: fully lit); sky and back-facing as in the hard
// masks.
template <class Fraction>
RgbImage visibility_image(const ViewSamples& samples, const SoftShadowTruth& truth,
                          Fraction fraction) {
  RgbImage image{samples.width, samples.height,
                 std::vector<std::uint8_t>(samples.samples.size() * 3)};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    std::uint8_t* px = &image.rgb[3 * i];
    if (samples.samples[i].sample_class == SampleClass::sky) {
      put_rgb(px, sky_colour);
    } else if (!truth.compared[i]) {
      put_rgb(px, back_facing_colour);
    } else {
      const std::uint8_t grey = to_byte(fraction(i));
      put_rgb(px, {grey, grey, grey});
    }
  }
  return image;
}

// Signed error e = f_alg - f_exact: red where too bright (light leaking into shadow), blue where
// too dark, saturated at |e| = 0.25; ambiguous samples drawn yellow-tinted.
RgbImage error_image(const ViewSamples& samples, const SoftShadowTruth& truth,
                     const std::vector<float>& fraction) {
  RgbImage image = visibility_image(samples, truth, [&](std::size_t) { return 0.8; });
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (!truth.compared[i]) continue;
    const double e = double(fraction[i]) - truth.visible_fraction[i];
    const double s = std::clamp(std::fabs(e) / 0.25, 0.0, 1.0);
    const std::uint8_t keep = to_byte(0.8 * (1.0 - s));
    std::uint8_t* px = &image.rgb[3 * i];
    px[0] = e > 0 ? 255 : keep;
    px[1] = keep;
    px[2] = e < 0 ? 255 : keep;
    if (!truth.robust[i] && s == 0.0) px[0] = 220, px[1] = 200, px[2] = 90;
  }
  return image;
}

class SoftShadowEvaluation : public CaseEvaluation {
 public:
  SoftShadowEvaluation(const Case& c, const ViewSamples& samples,
                       const std::vector<std::uint8_t>& receiver_ambiguous, bool exact,
                       const ImageTarget& images, const std::string& image_folder,
                       const TruthCache* cache)
      : samples_(samples), images_(images) {
    const auto start = std::chrono::steady_clock::now();
    const std::function<SoftShadowTruth()> compute = [&] {
      return exact ? exact_soft_shadow_oracle(c, samples)
                   : sampled_soft_shadow_oracle(c, samples, sampled_rays_per_sample);
    };
    TruthCacheUse cache_use;
    truth_ = cache ? cache->get(exact ? "soft.exact"
                                      : "soft.sampled" + std::to_string(sampled_rays_per_sample),
                                c, samples, compute, cache_use)
                   : compute();
    // The receiver never shadows its own sample: where it could be either of two triangles, the
    // fraction is not vouched for.
    for (std::size_t i = 0; i < receiver_ambiguous.size(); ++i)
      if (receiver_ambiguous[i]) truth_.robust[i] = 0;
    oracle_.time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    oracle_.method = truth_.method;
    oracle_.exact = truth_.exact;
    std::uint64_t compared = 0, robust = 0;
    double max_bound = 0;
    for (std::size_t i = 0; i < truth_.compared.size(); ++i) {
      compared += truth_.compared[i];
      robust += truth_.robust[i];
      if (truth_.compared[i]) max_bound = std::max(max_bound, truth_.error_bound[i]);
    }
    std::ostringstream line;
    line << truth_.method << ": " << robust << " robust, " << compared - robust << " ambiguous";
    if (!truth_.exact) line << ", error bound " << max_bound;
    oracle_.plan_line = line.str();
    oracle_.details = {{"eps_rel", truth_.eps_rel},      {"tau", truth_.tau},
                       {"compared", compared},           {"robust", robust},
                       {"ambiguous", compared - robust}, {"max_error_bound", max_bound}};
    if (images.enabled)
      oracle_.details["visibility_image"] = write_png_and_exr(
          images.out_dir, case_image_stem(image_folder) + "/oracle.visibility",
          visibility_image(samples, truth_,
                           [&](std::size_t i) { return truth_.visible_fraction[i]; }));
    record_truth_cache_use({cache_use}, oracle_);
  }

  void judge(const AlgorithmOutput& output, RunRecord& record) const override {
    const SoftShadowComparison s =
        compare_soft_shadows(output.visible_fraction, truth_, record.soft_budget);
    if (record.verdict != Verdict::fail) {
      record.verdict = s.verdict;
      record.reason = s.reason;
      // Invalid outputs and a mean over budget stay failures even without robust samples.
      if (s.robust == 0 && s.verdict == Verdict::pass) {
        record.verdict = Verdict::not_supported;
        record.reason = nothing_to_judge(samples_, s.ambiguous);
      }
    }
    record.error = {
        {"compared", s.compared},
        {"robust", s.robust},
        {"ambiguous", s.ambiguous},
        {"mean_abs_error", s.mean_abs_error},
        {"unexplained_mean_error", s.unexplained_mean_error},
        {"mean_allowance", s.mean_allowance},
        {"rms_error", s.rms_error},
        {"p99_abs_error", s.p99_abs_error},
        {"max_abs_error", s.max_abs_error},
        {"mean_signed_error", s.mean_signed_error},
        {"umbra_leaks", s.umbra_leaks},
        {"lit_occlusions", s.lit_occlusions},
        {"over_budget", s.over_budget},
        {"invalid_outputs", s.invalid_outputs},
        {"budget",
         {{"per_sample", record.soft_budget.per_sample}, {"mean", record.soft_budget.mean}}}};
    std::ostringstream headline;
    headline << "mean |e| " << s.mean_abs_error << ", max " << s.max_abs_error << ", leaks "
             << s.umbra_leaks;
    record.headline = headline.str();
    if (!images_.enabled) return;
    const std::string stem = algorithm_image_stem(record);
    record.images = {write_png_and_exr(images_.out_dir, stem + ".visibility",
                                       visibility_image(samples_, truth_,
                                                        [&](std::size_t i) {
                                                          return double(output.visible_fraction[i]);
                                                        })),
                     write_png_and_exr(images_.out_dir, stem + ".error",
                                       error_image(samples_, truth_, output.visible_fraction))};
  }

 private:
  const ViewSamples& samples_;
  ImageTarget images_;
  SoftShadowTruth truth_;
};

}  // namespace

std::unique_ptr<CaseEvaluation> evaluate_soft_shadows(
    const Case& c, const ViewSamples& samples, const std::vector<std::uint8_t>& receiver_ambiguous,
    OracleChoice choice, const ImageTarget& images, const std::string& image_folder,
    std::vector<std::string>& left_out, const TruthCache* cache) {
  bool exact = choice == OracleChoice::exact;
  if (choice == OracleChoice::embree)
    left_out.push_back(
        "exact soft-shadow oracle: --oracle embree asked for the sampled one; figures carry the "
        "sampled oracle's error bound");
  if (choice == OracleChoice::automatic) {
    const ExactSoftShadowWork work =
        estimate_exact_soft_shadow_work(c, samples, exact_oracle_estimate_stride);
    const double seconds =
        exact_oracle_seconds_per_sample * double(samples.count(SampleClass::regular)) +
        exact_oracle_seconds_per_projection * double(work.projections) +
        exact_oracle_seconds_per_squared_projection * work.squared_projections;
    exact = seconds <= exact_oracle_seconds_limit;
    if (!exact) {
      std::ostringstream why;
      why << "exact soft-shadow oracle: about " << work.projections
          << " projected casters to unite (estimated at every " << exact_oracle_estimate_stride
          << "th regular sample), an estimated " << std::fixed << std::setprecision(0) << seconds
          << " s on one core, above its limit of " << exact_oracle_seconds_limit
          << " s; figures carry the sampled oracle's error bound (--oracle exact insists)";
      left_out.push_back(why.str());
    }
  }
  return std::make_unique<SoftShadowEvaluation>(c, samples, receiver_ambiguous, exact, images,
                                                image_folder, cache);
}

}  // namespace shadowcts
