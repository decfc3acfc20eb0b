/* Deliberately bad plugin libraries for tests/certify: one library per BAD_* macro, each with one
 * defect that `shadowcts certify` must reject before writing anything (exit 2, the message
 * naming the library and the field). */
#include <signal.h>

#include "shadowcts/backend_abi.h"

static int32_t run_nothing(void* context, const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                           char* message, size_t message_capacity) {
  (void)context;
  (void)scene;
  (void)outputs;
  (void)message;
  (void)message_capacity;
  return SHADOWCTS_STATUS_OK;
}

static ShadowctsVariant variants[] = {{
    "v",
    SHADOWCTS_ALGORITHM_OTHER_HARD,
    SHADOWCTS_OUTPUT_HARD,
    SHADOWCTS_LIGHT_POINT,
    0,
    UINT64_MAX,
    UINT64_MAX,
    UINT64_MAX,
    0.0,
    0.0,
    run_nothing,
}};

#ifdef BAD_NO_ENTRY_POINT
/* Exports something, but not the entry point. */
SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate_v0(uint32_t version) {
  return (int32_t)version;
}
#else
SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table) {
  (void)requested_abi_version;
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "bad";
  table->version = "1";
  table->build_id = "test";
  table->variant_count = 1;
  table->variants = variants;
#if defined(BAD_ABI_VERSION)
  table->abi_version = 99;
#elif defined(BAD_UNKNOWN_ALGORITHM)
  variants[0].algorithm = 42;
#elif defined(BAD_ZERO_SIZE)
  variants[0].max_triangles = 0;
#elif defined(BAD_NULL_FUNCTION)
  variants[0].run = 0;
#elif defined(BAD_NO_VARIANTS)
  table->variant_count = 0;
#elif defined(BAD_EMPTY_NAME)
  table->name = "";
#elif defined(BAD_CRASH_IN_NEGOTIATE)
  raise(SIGSEGV);
#else
#error "define one BAD_* macro"
#endif
  return SHADOWCTS_STATUS_OK;
}
#endif
