#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "case_evaluation.h"
#include "image_paths.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"
#include "truth_cache.h"

namespace shadowcts {

// Computes the exact light sets of every regular sample (with and without the normal rule) and
// judges light lists for completeness, soundness and efficiency; writes per-sample list-length
// images under images/<image_folder>/. With a cache, the truths come from it when it holds this
// case's.
std::unique_ptr<CaseEvaluation> evaluate_light_assignment(const Case& c, const ViewSamples& samples,
                                                          const ImageTarget& images,
                                                          const std::string& image_folder,
                                                          const TruthCache* cache);

}  // namespace shadowcts
