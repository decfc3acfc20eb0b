#include "reference/bruteforce/hard_shadow_bruteforce.h"
#include "reference/embree/hard_shadow_embree.h"
#include "shadowcts/registry.h"
#if SHADOWCTS_HAVE_CUDA
#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"
#endif

namespace shadowcts {

const Registry& builtin_registry() {
  static const Registry registry = [] {
    Registry r;
    r.add(make_bruteforce_hard_shadow());
    r.add(make_embree_hard_shadow());
#if SHADOWCTS_HAVE_CUDA
    r.add(make_bruteforce_hard_shadow_cuda());
#endif
    return r;
  }();
  return registry;
}

}  // namespace shadowcts
