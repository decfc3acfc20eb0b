#pragma once
// The stack-based query: Algorithm 1 of Mora 2016 (PSV, Gerhards et al. 2015, with the wedge
// optimization), and D-PSV when the context does the depth test.
#include <cstdint>
#include <span>

#include "reference/psv/query_context.h"

namespace shadowcts::psv {

// Locates p with a stack of stack_storage.size() intersection children (the caller's buffer,
// reused from sample to sample). When a push would not fit, the query stops and answers
// stack_overflow (it never writes past the stack): the answer is then unknown, and the caller
// decides what to do with that sample.
QueryAnswer query_stack(const QueryContext& context, QueryPoint& p,
                        std::span<std::uint32_t> stack_storage, QueryWork& work);

}  // namespace shadowcts::psv
