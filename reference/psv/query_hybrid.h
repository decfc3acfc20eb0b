#pragma once
// The hybrid query of Mora 2016, section 3.5 (D-Hybrid with the context's depth test): the stack
// query with a short stack; when an intersection child does not fit, that intersection subtree is
// searched by the stackless query, which jumps back to the node it started from and hands over
// to the stack query again. It never overflows.
#include <cstdint>

#include "reference/psv/query_context.h"

namespace shadowcts::psv {

QueryAnswer query_hybrid(const QueryContext& context, const QueryPoint& p,
                         std::uint32_t stack_capacity, QueryWork& work);

}  // namespace shadowcts::psv
