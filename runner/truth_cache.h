#pragma once
// Oracle truths kept between runs (`shadowcts run --truth-cache DIR`). The exact oracles cost
// seconds to minutes per case (the soft one about 17 s on foliage.10k, the hard one about 40 s on
// gate_house.1M at 1080p), and the same case is judged again for every port, shard and CI run.
//
// An entry is used only when this very build (the program's GNU build id) computed it from
// byte-identical inputs: the entry holds those inputs (every Case field an oracle may read, and
// every view sample) and they are compared in full, so neither a hash collision nor an edited
// case can return a wrong truth. A damaged entry (checksum, truncation) is recomputed and
// replaced. One file per case and oracle; entries are written atomically (complete or absent),
// so concurrent runs (CTest -j) can share a folder.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "case_evaluation.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_truth.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// What the cache did for one truth: the record says so (results.json, the plan line).
struct TruthCacheUse {
  bool used = false;       // a cache was asked at all
  bool hit = false;        // the truth came from `entry`
  std::string entry;       // file name in the cache folder
  double computed_ms = 0;  // the oracle's time when it computed the entry (this run's on a miss)
  std::string note;        // why an entry was not used or not stored; empty when all went well
};

class TruthCache {
 public:
  // Creates `dir` if needed; throws UsageError naming it when that fails.
  explicit TruthCache(std::filesystem::path dir);

  // The truth of `oracle` (an id naming the oracle and its settings, e.g. "soft.exact") for the
  // case and samples: from the cache, or computed by `compute` and stored. A hard-shadow truth
  // from the cache has no lazy exponents: the caller attaches them.
  HardShadowTruth get(std::string_view oracle, const Case& c, const ViewSamples& samples,
                      const std::function<HardShadowTruth()>& compute, TruthCacheUse& use) const;
  SoftShadowTruth get(std::string_view oracle, const Case& c, const ViewSamples& samples,
                      const std::function<SoftShadowTruth()>& compute, TruthCacheUse& use) const;
  LightAssignmentTruth get(std::string_view oracle, const Case& c, const ViewSamples& samples,
                           const std::function<LightAssignmentTruth()>& compute,
                           TruthCacheUse& use) const;

 private:
  std::filesystem::path dir_;
};

// Says what the cache did in the oracle's summary: results.json's "truth_cache" (one object per
// entry) and the plan line. Nothing when no cache was asked.
void record_truth_cache_use(const std::vector<TruthCacheUse>& uses, OracleSummary& oracle);

// The program's GNU build id in hex, empty when it was linked without one (the cache is then
// off and says so).
std::string program_build_id();

}  // namespace shadowcts
