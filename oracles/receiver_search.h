#pragma once
// The receiver of a view sample whose G-buffer names none (an engine without triangle ids): the
// triangle the sample lies on, decided exactly.
//
// "Lies on": a float sample is off its triangle's plane by rounding (its own, and the depth
// reconstruction's), so the search asks which triangles meet the closed cube |q - p|inf <= tau
// around the sample, with tau = eps_rel S the ambiguity band of the case (DESIGN.md): the cube
// of every move the band allows. Zero-area triangles are never receivers. Exactly one such
// triangle is the receiver. Two or more (a sample on or near a shared edge or vertex, or on a
// crease within tau) make the sample ambiguous: its receiver is then the lowest candidate index,
// and the oracles count it ambiguous and never judge it. None is bad input: the G-buffer does not
// show this case's scene where that sample is.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct ReceiverSearch {
  double tau = 0.0;
  std::uint64_t unique = 0;                      // samples that lie on exactly one triangle
  std::uint64_t ambiguous = 0;                   // samples within tau of two or more triangles
  std::vector<std::uint8_t> receiver_ambiguous;  // per sample: 1 where ambiguous
};

// Sets the receiver of every non-sky sample of `samples` whose receiver is no_receiver. Throws
// InputError naming `source`, `position_channels` and the first such pixel (row-major) that lies
// on no triangle. Parallel and deterministic.
ReceiverSearch find_receivers(const Case& c, ViewSamples& samples, const std::string& source,
                              const std::string& position_channels);

}  // namespace shadowcts
