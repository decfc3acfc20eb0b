#include "light_assignment_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>

#include "heat_map.h"
#include "image_paths.h"
#include "oracles/light_assignment/light_assignment_comparison.h"
#include "shadowcts/image_file.h"
#include "shadowcts/light_assignment_oracle.h"

namespace shadowcts {
namespace {

class LightAssignmentEvaluation : public CaseEvaluation {
 public:
  LightAssignmentEvaluation(const Case& c, const ViewSamples& samples, const ImageTarget& images,
                            const std::string& image_folder, const TruthCache* cache)
      : case_(c), samples_(samples), images_(images) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<TruthCacheUse> cache_uses(2);
    auto truth = [&](bool normal_rule, TruthCacheUse& use) {
      const std::function<LightAssignmentTruth()> compute = [&] {
        return exact_light_assignment_oracle(c, samples, normal_rule);
      };
      return cache ? cache->get(normal_rule ? "lights.normal_rule" : "lights.plain", c, samples,
                                compute, use)
                   : compute();
    };
    plain_ = truth(false, cache_uses[0]);
    with_normals_ = truth(true, cache_uses[1]);
    oracle_.time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    oracle_.method = plain_.method;
    oracle_.exact = plain_.exact;
    std::ostringstream line;
    line << plain_.method << ": exact minimum " << plain_.exact_minimum()
         << " lighting computations (" << with_normals_.exact_minimum()
         << " with the normal rule), " << plain_.ambiguous_lights.size()
         << " ambiguous sample-light pairs";
    oracle_.plan_line = line.str();
    // The exact set size per sample, on the same scale as the algorithms' list lengths.
    std::vector<std::uint32_t> exact_count(samples.samples.size());
    for (std::size_t s = 0; s < samples.samples.size(); ++s)
      exact_count[s] = std::uint32_t(plain_.set_size(s));
    scale_ =
        std::max<std::uint32_t>(1, 4 * *std::max_element(exact_count.begin(), exact_count.end()));
    oracle_.details = {{"eps_rel", plain_.eps_rel},
                       {"tau", plain_.tau},
                       {"exact_minimum", plain_.exact_minimum()},
                       {"exact_minimum_normal_rule", with_normals_.exact_minimum()},
                       {"ambiguous_pairs", plain_.ambiguous_lights.size()},
                       {"heat_map_full_scale", scale_}};
    if (images.enabled)
      oracle_.details["lights_image"] =
          write_png_and_exr(images.out_dir, case_image_stem(image_folder) + "/oracle.lights",
                            count_heat_map(samples, exact_count, scale_));
    record_truth_cache_use(cache_uses, oracle_);
  }

  void judge(const AlgorithmOutput& output, RunRecord& record) const override {
    const bool normals = light_lists_use_normal_rule(record.variant);
    const LightAssignmentComparison cmp =
        compare_light_lists(output.light_lists, case_, samples_, normals ? with_normals_ : plain_);
    if (record.verdict != Verdict::fail) {
      record.verdict = cmp.verdict;
      record.reason = cmp.reason;
      // Without a regular sample there is no list to check against a truth (malformed lists
      // still fail).
      if (cmp.compared == 0 && cmp.verdict == Verdict::pass) {
        record.verdict = Verdict::not_supported;
        record.reason = nothing_to_judge(samples_, cmp.ambiguous_members);
      }
    }
    nlohmann::ordered_json misses = nlohmann::ordered_json::array();
    for (const LightListMiss& m : cmp.first_misses)
      misses.push_back({{"sample", m.sample}, {"light", m.light}, {"list", m.list}});
    record.error = {{"compared", cmp.compared},
                    {"normal_rule", normals},
                    {"lists", cmp.lists},
                    {"completeness_misses", cmp.completeness_misses},
                    {"first_misses", misses},
                    {"unsound_listings", cmp.unsound_listings},
                    {"samples_outside_bounds", cmp.samples_outside_bounds},
                    {"ambiguous_unlisted", cmp.ambiguous_unlisted},
                    {"listed_lights", cmp.listed_lights},
                    {"lighting_computations", cmp.lighting_computations},
                    {"exact_minimum", cmp.exact_minimum},
                    {"lighting_ratio", cmp.lighting_ratio}};
    std::ostringstream headline;
    headline << "misses " << cmp.completeness_misses << ", unsound "
             << cmp.unsound_listings + cmp.samples_outside_bounds << ", lighting x"
             << cmp.lighting_ratio;
    record.headline = headline.str();
    // Without a structure, no per-sample list lengths to draw.
    if (!cmp.structure_error.empty() || !images_.enabled) return;
    const LightLists& lists = output.light_lists;
    std::vector<std::uint32_t> length(samples_.samples.size(), 0);
    for (std::size_t s = 0; s < length.size(); ++s) {
      const std::uint32_t list = lists.list_of_sample[s];
      if (list != LightLists::no_list) length[s] = lists.offsets[list + 1] - lists.offsets[list];
    }
    record.images = {write_png_and_exr(images_.out_dir, algorithm_image_stem(record) + ".lights",
                                       count_heat_map(samples_, length, scale_))};
  }

 private:
  const Case& case_;
  const ViewSamples& samples_;
  ImageTarget images_;
  LightAssignmentTruth plain_, with_normals_;
  std::uint32_t scale_ = 1;
};

}  // namespace

std::unique_ptr<CaseEvaluation> evaluate_light_assignment(const Case& c, const ViewSamples& samples,
                                                          const ImageTarget& images,
                                                          const std::string& image_folder,
                                                          const TruthCache* cache) {
  return std::make_unique<LightAssignmentEvaluation>(c, samples, images, image_folder, cache);
}

}  // namespace shadowcts
