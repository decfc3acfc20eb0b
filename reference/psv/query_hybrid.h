#pragma once
// The hybrid query of Mora 2016, section 3.5 (D-Hybrid with the context's depth test): the stack
// query with a short stack; when an intersection child does not fit, that intersection subtree is
// searched by the stackless query, which jumps back to the node it started from and hands over
// to the stack query again. It never overflows.
#include <cstdint>
#include <span>

#include "reference/psv/query_context.h"

namespace shadowcts::psv {

// The short stack is stack_storage (the caller's buffer, reused from sample to sample).
QueryAnswer query_hybrid(const QueryContext& context, QueryPoint& p,
                         std::span<std::uint32_t> stack_storage, QueryWork& work);

}  // namespace shadowcts::psv
