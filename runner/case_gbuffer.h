#pragma once
// A case's own G-buffer as the runner uses it: read as the manifest's "gbuffer" says
// (gbuffer_format.h), receivers found by the suite where the G-buffer names none, samples
// classified against the case's light. Read before anything is written: bad input fails the run
// up front.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/gbuffer_format.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct CaseGBuffer {
  ViewSamples samples;
  // Per sample, 1 where the suite found two or more triangles within tau of it (receivers
  // "search"); the evaluations count such samples ambiguous and never judge them. Empty when
  // the G-buffer names the receivers.
  std::vector<std::uint8_t> receiver_ambiguous;
  bool receivers_searched = false;
  std::uint64_t unique_receivers = 0, ambiguous_receivers = 0;
  double tau = 0.0;  // the search's cube half-width
};

// Throws InputError naming the file, the channel and the pixel.
CaseGBuffer load_case_gbuffer(const Case& c, const GBufferFormat& format);

// The plan's line about the receivers of a searched G-buffer ("receivers: ...").
std::string receiver_plan_line(const CaseGBuffer& gbuffer);

}  // namespace shadowcts
