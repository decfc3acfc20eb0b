// The built-in algorithms of this build, in the order `shadowcts list` shows them.
#include "gpu/bruteforce/hard_shadow_bruteforce_emu.h"
#include "gpu/lightassign/lightassign_algorithm.h"
#include "gpu/metric/metric_algorithm.h"
#include "gpu/psv/psv_algorithm.h"
#include "gpu/ptsv/ptsv_algorithm.h"
#include "gpu/softtile/softtile_algorithm.h"
#include "reference/bruteforce/hard_shadow_bruteforce.h"
#include "reference/embree/hard_shadow_embree.h"
#include "reference/embree/soft_shadow_embree.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "reference/metric/metric_algorithm.h"
#include "reference/psv/psv_algorithm.h"
#include "reference/ptsv/ptsv_algorithm.h"
#include "reference/shadowmap/shadowmap_algorithm.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/stencil/stencil_algorithm.h"
#include "shadowcts/registry.h"
#include "simd/lightassign/lightassign_algorithm.h"
#include "simd/metric/metric_algorithm.h"
#include "simd/psv/psv_algorithm.h"
#include "simd/ptsv/ptsv_algorithm.h"
#include "simd/softtile/softtile_algorithm.h"
#if SHADOWCTS_HAVE_CUDA
#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"
#include "gpu/lightassign/lightassign_cuda.h"
#include "gpu/ptsv/ptsv_cuda.h"
#include "gpu/softtile/softtile_cuda.h"
#endif

namespace shadowcts {

const Registry& builtin_registry() {
  static const Registry registry = [] {
    Registry r;
    r.add(make_bruteforce_hard_shadow());
    r.add(make_embree_hard_shadow());
    r.add(make_embree_soft_shadow());
    r.add(make_ptsv());
    r.add(make_psv());
    r.add(make_metric());
    r.add(make_shadowmap());
    r.add(make_stencil());
    r.add(make_softtile());
    r.add(make_lightassign());
    // The device kernels run by the emulator: on every machine, in their own records.
    r.add(make_bruteforce_hard_shadow_cuda_emu());
    r.add(make_lightassign_cuda_emu());
    r.add(make_metric_cuda_emu());
    r.add(make_cuda_emu_ptsv());
    r.add(make_softtile_cuda_emu());
    r.add(make_psv_cuda_emu());
    r.add(make_simd_ptsv());
    r.add(make_simd_psv());
    r.add(make_simd_softtile());
    r.add(make_simd_metric());
    r.add(make_simd_lightassign());
#if SHADOWCTS_HAVE_CUDA
    r.add(make_bruteforce_hard_shadow_cuda());
    r.add(make_lightassign_cuda());
    r.add(make_metric_cuda());
    r.add(make_cuda_ptsv());
    r.add(make_softtile_cuda());
    r.add(make_psv_cuda());
#endif
    return r;
  }();
  return registry;
}

}  // namespace shadowcts
