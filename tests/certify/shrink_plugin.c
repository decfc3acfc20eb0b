/* A test-only hard-shadow port whose faults depend on one small feature of the input, so that
 * shrinking a crash or a hang (runner/certify.cpp, a worker process per candidate) has something
 * to find: a triangle with two bit-identical vertices (the degenerate fuzz generator makes them).
 * Without one, every variant gives the brute force's correct answers (examples/bruteforce_core.c).
 *   crashes  a segmentation fault, as a port that divides by an edge's length might die  -> Crash
 *   hangs    never returns, as a port whose loop over an edge never advances might        ->
 * Timeout The fault is decided from the geometry it receives, never from the case's name, so a
 * reproducer crashes or hangs exactly when it keeps such a triangle. */
#include <signal.h>
#include <unistd.h>

#include "bruteforce_core.h"

static int same_vertex(const ShadowctsScene* scene, uint64_t t, int a, int b) {
  return scene->x[a][t] == scene->x[b][t] && scene->y[a][t] == scene->y[b][t] &&
         scene->z[a][t] == scene->z[b][t];
}

static int has_repeated_vertex(const ShadowctsScene* scene) {
  for (uint64_t t = 0; t < scene->triangle_count; ++t)
    if (same_vertex(scene, t, 0, 1) || same_vertex(scene, t, 1, 2) || same_vertex(scene, t, 2, 0))
      return 1;
  return 0;
}

static int32_t run_crashes(void* context, const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                           char* message, size_t message_capacity) {
  (void)context;
  /* What a wild write does; raise() keeps the compiler from reasoning it away. */
  if (has_repeated_vertex(scene)) raise(SIGSEGV);
  return example_bruteforce_run(scene, outputs, EXAMPLE_FAULT_NONE, message, message_capacity);
}

static int32_t run_hangs(void* context, const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                         char* message, size_t message_capacity) {
  (void)context;
  if (has_repeated_vertex(scene))
    for (;;) sleep(1);
  return example_bruteforce_run(scene, outputs, EXAMPLE_FAULT_NONE, message, message_capacity);
}

#define SHRINK_PLUGIN_VARIANT(name, run)                                                \
  {                                                                                     \
    name, SHADOWCTS_ALGORITHM_OTHER_HARD, SHADOWCTS_OUTPUT_HARD,                        \
        SHADOWCTS_LIGHT_POINT | SHADOWCTS_LIGHT_DIRECTIONAL, 0, UINT64_MAX, UINT64_MAX, \
        UINT64_MAX, 0.0, 0.0, run                                                       \
  }

static const ShadowctsVariant variants[] = {SHRINK_PLUGIN_VARIANT("crashes", run_crashes),
                                            SHRINK_PLUGIN_VARIANT("hangs", run_hangs)};

SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table) {
  if (requested_abi_version != SHADOWCTS_BACKEND_ABI_VERSION ||
      table->struct_size != sizeof(ShadowctsBackend))
    return SHADOWCTS_STATUS_ABI_MISMATCH;
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "shrink_plugin";
  table->version = "0.0.1";
  table->build_id = "test";
  table->context = 0;
  table->variant_count = sizeof variants / sizeof variants[0];
  table->variants = variants;
  return SHADOWCTS_STATUS_OK;
}
