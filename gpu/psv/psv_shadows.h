#pragma once
// Hard shadows with partitioned shadow volumes on a CUDA device (or the emulator): the host side
// both builds of the kernels share. The TOP tree is built in batches
// (reference/psv/top_tree_batches.h): the device descends each batch's triangles, one thread per
// triangle, and the host commits them in insertion order, so it is the reference's tree node for
// node; then one device thread per regular sample queries it.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/psv/psv_kernels.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::gpu_psv {

using QueryKernel = PsvQueryResult (*)(PsvQueryInput);
using DescentSessionMaker = std::unique_ptr<PsvDescentSession> (*)(const PsvDescentSetup&);

// build_psv with the descents on the device (`make_session`'s): the same tree, statistics and
// plane tests; `device_exact_tests` receives the exact plane tests of the device's descents (the
// host's, in the commit's resumed descents, are counted by build.planes).
psv::PsvBuild build_psv_on_device(const Case& c, const ViewSamples& samples, std::uint64_t seed,
                                  DescentSessionMaker make_session, psv::BatchWork& work,
                                  std::uint64_t& device_exact_tests);

// The kernel's input for a built tree: its nodes and volume sources byte for byte, the case's
// triangles, the regular samples the build says need a query (PsvBuild::reached; their
// view-sample indices appended to regular_samples).
PsvQueryInput psv_query_input(const Case& c, const ViewSamples& samples, const psv::PsvBuild& build,
                              const psv::PsvOptions& options,
                              std::vector<std::size_t>& regular_samples);

// psv::psv_hard_shadows with the queries run by `kernel`: the same mask, per-sample node visits
// and counters (the build's and the queries' exact plane tests summed, as the reference counts
// them). Runs on c.parameters.threads threads where the emulator spreads blocks.
psv::PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples,
                                const psv::PsvOptions& options, QueryKernel kernel,
                                DescentSessionMaker make_session);

}  // namespace shadowcts::gpu_psv
