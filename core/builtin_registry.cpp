// The built-in algorithms of this build. An algorithm folder is registered once its factory
// header exists, so each reference algorithm lands with its own folder.
#include "reference/bruteforce/hard_shadow_bruteforce.h"
#include "reference/embree/hard_shadow_embree.h"
#include "shadowcts/registry.h"
#if __has_include("reference/ptsv/ptsv_algorithm.h")
#include "reference/ptsv/ptsv_algorithm.h"
#define SHADOWCTS_HAVE_PTSV 1
#endif
#if __has_include("reference/psv/psv_algorithm.h")
#include "reference/psv/psv_algorithm.h"
#define SHADOWCTS_HAVE_PSV 1
#endif
#if __has_include("reference/metric/metric_algorithm.h")
#include "reference/metric/metric_algorithm.h"
#define SHADOWCTS_HAVE_METRIC 1
#endif
#if __has_include("reference/softtile/softtile_algorithm.h")
#include "reference/softtile/softtile_algorithm.h"
#define SHADOWCTS_HAVE_SOFTTILE 1
#endif
#if __has_include("reference/lightassign/lightassign_algorithm.h")
#include "reference/lightassign/lightassign_algorithm.h"
#define SHADOWCTS_HAVE_LIGHTASSIGN 1
#endif
#if SHADOWCTS_HAVE_CUDA
#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"
#endif

namespace shadowcts {

const Registry& builtin_registry() {
  static const Registry registry = [] {
    Registry r;
    r.add(make_bruteforce_hard_shadow());
    r.add(make_embree_hard_shadow());
#if SHADOWCTS_HAVE_PTSV
    r.add(make_ptsv());
#endif
#if SHADOWCTS_HAVE_PSV
    r.add(make_psv());
#endif
#if SHADOWCTS_HAVE_METRIC
    r.add(make_metric());
#endif
#if SHADOWCTS_HAVE_SOFTTILE
    r.add(make_softtile());
#endif
#if SHADOWCTS_HAVE_LIGHTASSIGN
    r.add(make_lightassign());
#endif
#if SHADOWCTS_HAVE_CUDA
    r.add(make_bruteforce_hard_shadow_cuda());
#endif
    return r;
  }();
  return registry;
}

}  // namespace shadowcts
