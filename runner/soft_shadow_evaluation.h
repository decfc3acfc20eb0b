#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "case_evaluation.h"
#include "image_paths.h"
#include "shadowcts/case.h"
#include "shadowcts/runner.h"
#include "shadowcts/view_samples.h"
#include "truth_cache.h"

namespace shadowcts {

// Computes the sun-disk visibility truth of `c` with the exact oracle, or the sampled one above
// its size limit or on request (noted in `left_out`), and writes the oracle's visibility image
// under images/<image_folder>/. With a cache, the truth comes from it when it holds this case's.
// Runs are judged against the error budget their algorithm declares for the variant.
// Samples marked in `receiver_ambiguous` (per sample; empty: none), whose receiver the suite
// could not tell apart within the band, are counted ambiguous and never judged.
std::unique_ptr<CaseEvaluation> evaluate_soft_shadows(
    const Case& c, const ViewSamples& samples, const std::vector<std::uint8_t>& receiver_ambiguous,
    OracleChoice choice, const ImageTarget& images, const std::string& image_folder,
    std::vector<std::string>& left_out, const TruthCache* cache);

}  // namespace shadowcts
