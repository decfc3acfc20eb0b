/* libexample_broken.so: a deliberately broken hard-shadow port, to show what certification
 * reports (tests/certify). It is the brute force of bruteforce_core.c with one fault per
 * fixture family, chosen by the case's name:
 *   ground_blockers.*  a crack along every triangle edge: light leaks through the shared
 *                      edges of the closed boxes                                    -> Fail
 *   gate_house.*       a segmentation fault                                         -> Crash
 *   closed_shapes.*    never returns                                                -> Timeout
 *   foliage.*          state kept across processes: every second process (a marker file in
 *                      $TMPDIR or /tmp alternates) answers one sample differently,
 *                      so certify's rerun in a fresh process differs               -> Fail
 * Every other case gets the correct answers. */
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bruteforce_core.h"

static int starts_with(const char* text, const char* prefix) {
  return strncmp(text, prefix, strlen(prefix)) == 0;
}

/* The "state kept across processes" fault: 1 on every second call of this function in any
 * process, alternating through a marker file (created when absent, removed when present). */
static int second_run(const char* case_name) {
  const char* dir = getenv("TMPDIR");
  char path[512];
  snprintf(path, sizeof path, "%s/shadowcts_example_broken_%ld_%s", dir && *dir ? dir : "/tmp",
           (long)getuid(), case_name);
  const int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd >= 0) {
    close(fd);
    return 0;
  }
  unlink(path);
  return 1;
}

/* Decided once per process: both calls within one worker answer alike. */
static int flipped_process(const char* case_name) {
  static int decided = -1;
  if (decided < 0) decided = second_run(case_name);
  return decided;
}

static int32_t run_broken(void* context, const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                          char* message, size_t message_capacity) {
  (void)context;
  const char* name = scene->case_name;
  if (starts_with(name, "gate_house.")) {
    /* What a wild write does; raise() keeps the compiler from reasoning it away. */
    raise(SIGSEGV);
  }
  if (starts_with(name, "closed_shapes.")) {
    for (;;) sleep(1);
  }
  const ExampleFault fault =
      starts_with(name, "ground_blockers.") ? EXAMPLE_FAULT_EDGE_CRACK : EXAMPLE_FAULT_NONE;
  const int32_t status = example_bruteforce_run(scene, outputs, fault, message, message_capacity);
  if (status == SHADOWCTS_STATUS_OK && starts_with(name, "foliage.") && scene->sample_count > 0 &&
      flipped_process(name))
    outputs->shadowed[scene->sample_count / 2] ^= 1;
  return status;
}

static const ShadowctsVariant variants[] = {{
    "faulty",
    SHADOWCTS_ALGORITHM_OTHER_HARD,
    SHADOWCTS_OUTPUT_HARD,
    SHADOWCTS_LIGHT_POINT | SHADOWCTS_LIGHT_DIRECTIONAL,
    0,
    UINT64_MAX,
    UINT64_MAX,
    UINT64_MAX,
    0.0,
    0.0,
    run_broken,
}};

SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table) {
  if (requested_abi_version != SHADOWCTS_BACKEND_ABI_VERSION) return SHADOWCTS_STATUS_ABI_MISMATCH;
  table->abi_version = SHADOWCTS_BACKEND_ABI_VERSION;
  table->name = "example_broken";
  table->version = "0.0.1";
  table->build_id = "broken on purpose";
  table->variant_count = 1;
  table->variants = variants;
  return SHADOWCTS_STATUS_OK;
}
