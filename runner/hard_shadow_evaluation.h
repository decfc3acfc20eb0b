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

// Computes the hard-shadow truth of `hard_case` (its light is point or directional) with the
// exact oracle, or the fast one above its size limit or on request (noted in `left_out`), and
// writes the oracle's mask image under images/<image_folder>/. With a cache, the truth comes from
// it when it holds this case's (truth_cache.h).
// Samples marked in `receiver_ambiguous` (per sample; empty: none), whose receiver the suite
// could not tell apart within the band, are counted ambiguous and never judged.
std::unique_ptr<CaseEvaluation> evaluate_hard_shadows(
    const Case& hard_case, const ViewSamples& samples,
    const std::vector<std::uint8_t>& receiver_ambiguous, OracleChoice choice,
    const ImageTarget& images, const std::string& image_folder, std::vector<std::string>& left_out,
    const TruthCache* cache);

}  // namespace shadowcts
