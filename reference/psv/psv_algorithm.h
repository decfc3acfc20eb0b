#pragma once
// Reference `psv`: partitioned shadow volumes over a TOP tree (Gerhards et al. 2015; Mora et al.
// 2016), with the four queries of the 2016 paper as variants:
//   stack      PSV (Algorithm 1 with the wedge optimization), stack of 12
//   stack32    PSV with the stack of 32 both papers use
//   depth      D-PSV: PSV with the depth test, stack of 12
//   stackless  D-Stackless (Algorithm 3)
//   hybrid     D-Hybrid: short stack of 12, stackless where it is full
// A stack query whose stack would overflow is counted (stack_overflows) and that sample is
// answered by the stackless query instead: the mask is always the tree's answer.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "psv", backend "reference".
std::unique_ptr<Algorithm> make_psv();

}  // namespace shadowcts
