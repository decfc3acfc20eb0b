/* libexample_bruteforce_c.so: a small hard-shadow port in plain C, loaded by `shadowcts certify`
 * through the C ABI (include/shadowcts/backend_abi.h). Brute force with a watertight
 * segment/ray-triangle test and the receiver half-space rule (bruteforce_core.c); it passes
 * certification on the conformance profile. */
#include "bruteforce_core.h"

static int32_t run_exact(void* context, const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                         char* message, size_t message_capacity) {
  (void)context;
  return example_bruteforce_run(scene, outputs, EXAMPLE_FAULT_NONE, message, message_capacity);
}

static const ShadowctsVariant variants[] = {{
    "watertight",                                        /* name */
    SHADOWCTS_ALGORITHM_OTHER_HARD,                      /* a brute force: another hard method */
    SHADOWCTS_OUTPUT_HARD,                               /* output_kind */
    SHADOWCTS_LIGHT_POINT | SHADOWCTS_LIGHT_DIRECTIONAL, /* light_kinds */
    0,                                                   /* flags */
    UINT64_MAX,                                          /* max_triangles */
    UINT64_MAX,                                          /* max_regular_samples */
    UINT64_MAX,                                          /* max_sample_triangle_pairs */
    0.0,                                                 /* soft_error_per_sample */
    0.0,                                                 /* soft_error_mean */
    run_exact,                                           /* run */
}};

SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table) {
  if (requested_abi_version != SHADOWCTS_BACKEND_ABI_VERSION ||
      table->struct_size != sizeof(ShadowctsBackend))
    return SHADOWCTS_STATUS_ABI_MISMATCH;
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "example_bruteforce_c";
  table->version = "1.0.0";
  table->build_id = "example";
  table->context = 0;
  table->variant_count = sizeof variants / sizeof variants[0];
  table->variants = variants;
  return SHADOWCTS_STATUS_OK;
}
