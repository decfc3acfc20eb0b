#pragma once
// Hard shadows with partitioned shadow volumes on a CUDA device (or the emulator): the host side
// both builds of the query kernel share. First step of the port: the TOP tree is the reference's,
// built on the host (reference/psv/psv_shadows.h, build_psv) and uploaded as a flat node array;
// one device thread per regular sample queries it.
#include <cstddef>
#include <vector>

#include "gpu/psv/psv_kernels.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::gpu_psv {

using QueryKernel = PsvQueryResult (*)(const PsvQueryInput&);

// The kernel's input for a built tree: its nodes and volume sources byte for byte, the case's
// triangles, the regular samples (their view-sample indices appended to regular_samples).
PsvQueryInput psv_query_input(const Case& c, const ViewSamples& samples, const psv::PsvBuild& build,
                              const psv::PsvOptions& options,
                              std::vector<std::size_t>& regular_samples);

// psv::psv_hard_shadows with the queries run by `kernel`: the same mask, per-sample node visits
// and counters (the build's and the queries' exact plane tests summed, as the reference counts
// them). Runs on c.parameters.threads threads where the emulator spreads blocks.
psv::PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples,
                                const psv::PsvOptions& options, QueryKernel kernel);

}  // namespace shadowcts::gpu_psv
