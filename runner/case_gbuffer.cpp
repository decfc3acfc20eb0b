#include "case_gbuffer.h"

#include <sstream>

#include "oracles/receiver_search.h"
#include "shadowcts/gbuffer_exr.h"

namespace shadowcts {

CaseGBuffer load_case_gbuffer(const Case& c, const GBufferFormat& format) {
  CaseGBuffer g;
  g.samples = read_gbuffer_exr(c.gbuffer_path, format, c);
  if (format.receivers == GBufferReceivers::search) {
    const ReceiverSearch found = find_receivers(
        c, g.samples, c.gbuffer_path,
        format.positions == GBufferPositions::depth ? "channel Z" : "channels P.X P.Y P.Z");
    g.receiver_ambiguous = found.receiver_ambiguous;
    g.receivers_searched = true;
    g.unique_receivers = found.unique;
    g.ambiguous_receivers = found.ambiguous;
    g.tau = found.tau;
  }
  classify_samples(c, g.samples, c.gbuffer_path);
  return g;
}

std::string receiver_plan_line(const CaseGBuffer& g) {
  std::ostringstream line;
  line << "found by the suite (the G-buffer has no ids): " << g.unique_receivers
       << " samples on one triangle, " << g.ambiguous_receivers
       << " ambiguous (within tau = " << g.tau
       << " of two or more triangles: counted as ambiguous, never judged)";
  return line.str();
}

}  // namespace shadowcts
