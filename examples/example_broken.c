/* libexample_broken.so: a deliberately broken hard-shadow port, to show what certification
 * reports (tests/certify). It is the brute force of bruteforce_core.c with one fault per
 * fixture family, chosen by the case's name,
 *   ground_blockers.*  a crack along every triangle edge: light leaks through the shared
 *                      edges of the closed boxes                                    -> Fail
 *   gate_house.*       a segmentation fault                                         -> Crash
 *   closed_shapes.*    never returns                                                -> Timeout
 *   shared_edges.*     a fatal-error path that ends the host process: exit(3)       -> Crash
 *   foliage.*          state kept across processes: every second process (a marker file in
 *                      $TMPDIR or /tmp alternates) answers one sample differently,
 *                      so certify's rerun in a fresh process differs               -> Fail
 * and one chosen by the geometry it receives, as a real port's fast path would be:
 *   scenes whose casters' vertices all lie on the grid of 1/4096 (CAD exports; the surfaces
 *   of the fuzz profile's watertight generator) take a "fast path" with the same crack along
 *   every triangle edge: light leaks through their shared edges                     -> Fail
 * Every other case gets the correct answers. */
#include <fcntl.h>
#include <math.h>
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

/* 1 when the scene has a caster and every vertex of every caster is a multiple of 1/4096 in
 * every coordinate (scaling a float by a power of two is exact). */
static int grid_aligned_casters(const ShadowctsScene* scene) {
  int any_caster = 0;
  for (uint64_t t = 0; t < scene->triangle_count; ++t) {
    if (!scene->casts[t]) continue;
    any_caster = 1;
    for (int k = 0; k < 3; ++k) {
      const double coordinates[3] = {scene->x[k][t], scene->y[k][t], scene->z[k][t]};
      for (int a = 0; a < 3; ++a) {
        const double on_grid = coordinates[a] * 4096.0;
        if (on_grid != floor(on_grid)) return 0;
      }
    }
  }
  return any_caster;
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
  if (starts_with(name, "shared_edges.")) {
    fprintf(stderr, "example_broken: fatal: cannot continue\n");
    exit(3);
  }
  const ExampleFault fault = starts_with(name, "ground_blockers.") || grid_aligned_casters(scene)
                                 ? EXAMPLE_FAULT_EDGE_CRACK
                                 : EXAMPLE_FAULT_NONE;
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
