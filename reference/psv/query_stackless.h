#pragma once
// The stackless query: Algorithm 3 of Mora 2016 (D-Stackless with the context's depth test).
// Intersection subtrees are searched first; a lit leaf jumps along the volume's ancestor link to
// the parent of its intersection subtree, which is then visited a second time for its positive or
// negative child.
#include "reference/psv/query_context.h"

namespace shadowcts::psv {

QueryAnswer query_stackless(const QueryContext& context, QueryPoint& p, QueryWork& work);

}  // namespace shadowcts::psv
