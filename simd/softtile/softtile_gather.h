#pragma once
// The simd port of the gather pass (reference/softtile/softtile_gather.h): the reference's frame,
// then its clusters gathered in parallel (blocks of clusters over oneTBB, each with the
// reference's gather_cluster) and joined in triangle order, so the Gathered is the reference's,
// triangle for triangle and counter for counter, for any thread count.
#include "reference/softtile/softtile_gather.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::simd::softtile {

shadowcts::softtile::Gathered gather(const Case& c, const ViewSamples& samples);

}  // namespace shadowcts::simd::softtile
