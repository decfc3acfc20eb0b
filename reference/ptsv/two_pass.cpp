#include "reference/ptsv/two_pass.h"

#include <algorithm>

#include "shadowcts/phase_progress.h"

namespace shadowcts::ptsv {

int default_job_level(int leaf_level) {
  return std::clamp((leaf_level + 1) / 2, 1, leaf_level);
}

void traverse_two_pass(ClusterTraversal& traversal, const std::vector<ShadowVolume>& volumes,
                       int job_level, TraversalCounters& counters) {
  std::vector<TraversalJob> jobs;
  phase_progress::begin(volumes.size(), "shadow volumes", "the first pass");
  {
    phase_progress::Batch done;
    for (std::size_t v = 0; v < volumes.size(); ++v) {
      traversal.emit_jobs_at(job_level, std::uint32_t(v), &jobs);
      traversal.traverse_from_root(volumes[v]);
      done.add();
    }
  }
  traversal.emit_jobs_at(-1, 0, nullptr);
  if (!jobs.empty()) phase_progress::begin(jobs.size(), "jobs", "the second pass");
  phase_progress::Batch done;
  for (const TraversalJob& job : jobs) {
    ++counters.second_pass_jobs;
    traversal.traverse_from(volumes[job.volume], job_level, job.node);
    done.add();
  }
}

}  // namespace shadowcts::ptsv
