/* The hard-shadow brute force of the example plugins, in plain C: every regular sample against
 * every caster, with a watertight segment/ray-triangle test (Woop, Benthin and Wald 2013, in
 * double) and the receiver half-space rule of docs/specification.md. */
#ifndef SHADOWCTS_EXAMPLE_BRUTEFORCE_CORE_H
#define SHADOWCTS_EXAMPLE_BRUTEFORCE_CORE_H

#include "shadowcts/backend_abi.h"

/* Faults the broken example plants (example_broken.c); the correct example passes NONE. */
typedef enum ExampleFault {
  EXAMPLE_FAULT_NONE = 0,
  /* A crack along every triangle edge: hits within a small fraction of the triangle from an edge
   * are dropped, so light leaks between triangles that share an edge. */
  EXAMPLE_FAULT_EDGE_CRACK = 1
} ExampleFault;

/* Fills outputs->shadowed for every regular sample and two counters (pair_tests,
 * predicate_calls). Runs on up to scene->threads POSIX threads (0: the online CPUs). Returns a
 * SHADOWCTS_STATUS_* code with a message on an error. */
int32_t example_bruteforce_run(const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                               ExampleFault fault, char* message, size_t message_capacity);

#endif
