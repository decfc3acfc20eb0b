/* A test plugin for the adapter's other output kinds and its checks (tests/certify/
 * plugin_backend_test.cpp): light lists through the OUTPUT_TOO_SMALL protocol, a soft shadow that
 * claims exactness but sees no shadow, and a hard shadow that writes a value other than 0/1. */
#include <math.h>

#include "shadowcts/backend_abi.h"

/* One list for every sample: the lights whose sphere meets the box of all sample positions. Asks
 * for one list more than it is given first, so the suite calls it again with more room. */
static int32_t one_list(void* context, const ShadowctsScene* s, ShadowctsOutputs* o, char* message,
                        size_t capacity) {
  (void)context;
  (void)message;
  (void)capacity;
  if (o->list_capacity <= s->sample_count) {
    o->list_count = s->sample_count + 1;
    o->light_count = 0;
    return SHADOWCTS_STATUS_OUTPUT_TOO_SMALL;
  }
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint64_t i = 0; i < s->sample_count; ++i) {
    const float p[3] = {s->px[i], s->py[i], s->pz[i]};
    for (int k = 0; k < 3; ++k) {
      lo[k] = fminf(lo[k], p[k]);
      hi[k] = fmaxf(hi[k], p[k]);
    }
    o->list_of_sample[i] = 0;
  }
  uint64_t count = 0;
  for (uint64_t l = 0; l < s->ranged_light_count && count < o->light_capacity; ++l) {
    const double c[3] = {s->ranged_cx[l], s->ranged_cy[l], s->ranged_cz[l]};
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = c[k] < lo[k] ? lo[k] - c[k] : c[k] > hi[k] ? c[k] - hi[k] : 0.0;
      d2 += d * d;
    }
    if (d2 <= (double)s->ranged_range[l] * s->ranged_range[l])
      o->list_lights[count++] = (uint32_t)l;
  }
  o->list_offsets[0] = 0;
  o->list_offsets[1] = (uint32_t)count;
  for (int k = 0; k < 3; ++k) {
    o->list_bounds[k] = lo[k];
    o->list_bounds[3 + k] = hi[k];
  }
  o->list_count = 1;
  o->light_count = count;
  return SHADOWCTS_STATUS_OK;
}

static int32_t fully_lit(void* context, const ShadowctsScene* s, ShadowctsOutputs* o, char* message,
                         size_t capacity) {
  (void)context;
  (void)message;
  (void)capacity;
  for (uint64_t i = 0; i < s->sample_count; ++i) o->visible_fraction[i] = 1.0f;
  return SHADOWCTS_STATUS_OK;
}

static int32_t bad_bit(void* context, const ShadowctsScene* s, ShadowctsOutputs* o, char* message,
                       size_t capacity) {
  (void)context;
  (void)message;
  (void)capacity;
  if (s->sample_count > 0) o->shadowed[0] = 2;
  return SHADOWCTS_STATUS_OK;
}

static const ShadowctsVariant variants[] = {
    {"one_list", SHADOWCTS_ALGORITHM_OTHER_LIGHT_ASSIGNMENT, SHADOWCTS_OUTPUT_LIGHT_LISTS,
     SHADOWCTS_LIGHT_RANGED, 0, UINT64_MAX, UINT64_MAX, UINT64_MAX, 0.0, 0.0, one_list},
    {"fully_lit", SHADOWCTS_ALGORITHM_OTHER_SOFT, SHADOWCTS_OUTPUT_SOFT, SHADOWCTS_LIGHT_SUN_DISK,
     0, UINT64_MAX, UINT64_MAX, UINT64_MAX, 0.0, 0.0, fully_lit},
    {"bad_bit", SHADOWCTS_ALGORITHM_OTHER_HARD, SHADOWCTS_OUTPUT_HARD,
     SHADOWCTS_LIGHT_POINT | SHADOWCTS_LIGHT_DIRECTIONAL, 0, UINT64_MAX, UINT64_MAX, UINT64_MAX,
     0.0, 0.0, bad_bit},
};

SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table) {
  if (requested_abi_version != SHADOWCTS_BACKEND_ABI_VERSION) return SHADOWCTS_STATUS_ABI_MISMATCH;
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "other_outputs";
  table->version = "1";
  table->build_id = "test";
  table->variant_count = 3;
  table->variants = variants;
  return SHADOWCTS_STATUS_OK;
}
