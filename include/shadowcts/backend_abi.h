/* The shadowcts backend ABI: how a port the suite has never seen (a user's CUDA, ISPC, SIMD or CPU
 * code, built as a shared library) joins a run and is certified (`shadowcts certify`,
 * docs/certify.md).
 *
 * Plain C (C99), no C++: a port written in any language that can export a C function can
 * implement it. Versioned: the library exports one function,
 *
 *   int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version, ShadowctsBackend* table);
 *
 * which the suite calls once with the ABI version it speaks (SHADOWCTS_BACKEND_ABI_VERSION) and a
 * zeroed table whose struct_size the suite has set. The library fills the table: its identity,
 * every variant it implements with its capabilities declared up front (output kind, light kinds,
 * size limits, which algorithm it is), and one run function per variant. It returns
 * SHADOWCTS_STATUS_OK, or SHADOWCTS_STATUS_ABI_MISMATCH when it does not speak that version.
 *
 * Data: each run receives the case's prepared scene (include/shadowcts/prepared_scene.h) as
 * flat arrays the suite owns and keeps alive for the call (structure of arrays, float32 exactly
 * as in the case), and writes into output arrays the suite owns and has sized. Nothing crosses
 * the boundary that one side allocates and the other frees. A run returns a status and, on an
 * error, a message in the suite's buffer.
 *
 * Judging: the outputs are judged by the suite's oracles exactly like a registered algorithm's
 * (docs/specification.md): hard shadows on every robust sample, soft shadows against the
 * variant's declared error budget, light lists for completeness and soundness. A variant is
 * NotSupported on a case only where its declared capabilities exclude it (a light kind it does
 * not declare, a size above its limits); an error returned at run time is a Crash.
 */
#ifndef SHADOWCTS_BACKEND_ABI_H
#define SHADOWCTS_BACKEND_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version this header describes. A change of any struct layout or meaning is a new version. */
#define SHADOWCTS_BACKEND_ABI_VERSION 1u

/* The name of the one exported entry point (for dlsym). */
#define SHADOWCTS_BACKEND_NEGOTIATE_SYMBOL "shadowcts_backend_negotiate"

/* Status codes returned by the entry point and by the run functions. */
#define SHADOWCTS_STATUS_OK 0
#define SHADOWCTS_STATUS_ABI_MISMATCH 1 /* negotiate: the requested version is not spoken */
#define SHADOWCTS_STATUS_ERROR 2        /* run: failed; the message says why (a Crash verdict) */
/* run, light lists only: the output capacities are too small; the port has set
 * ShadowctsOutputs::list_count and ::light_count to what it needs, and is called again with
 * buffers that large. */
#define SHADOWCTS_STATUS_OUTPUT_TOO_SMALL 3

/* Which algorithm a variant implements, so that the report places it beside the suite's own
 * (DESIGN.md, "The five algorithms"). The OTHER_* values name another method by its output. */
typedef enum ShadowctsAlgorithm {
  SHADOWCTS_ALGORITHM_PTSV = 1,        /* per-triangle shadow volumes: hard */
  SHADOWCTS_ALGORITHM_PSV = 2,         /* partitioned shadow volumes: hard */
  SHADOWCTS_ALGORITHM_METRIC = 3,      /* metric-tree shadows: hard */
  SHADOWCTS_ALGORITHM_SOFTTILE = 4,    /* tiled soft shadow volumes: soft */
  SHADOWCTS_ALGORITHM_LIGHTASSIGN = 5, /* tiled/clustered light assignment: light lists */
  SHADOWCTS_ALGORITHM_OTHER_HARD = 6,  /* another hard-shadow method (e.g. brute force) */
  SHADOWCTS_ALGORITHM_OTHER_SOFT = 7,  /* another soft-shadow method */
  SHADOWCTS_ALGORITHM_OTHER_LIGHT_ASSIGNMENT = 8
} ShadowctsAlgorithm;

/* What a variant writes per view sample. Must match its algorithm (ptsv, psv, metric and
 * OTHER_HARD: HARD; softtile and OTHER_SOFT: SOFT; lightassign and OTHER_LIGHT_ASSIGNMENT:
 * LIGHT_LISTS). */
typedef enum ShadowctsOutputKind {
  SHADOWCTS_OUTPUT_HARD = 1,       /* ShadowctsOutputs::shadowed */
  SHADOWCTS_OUTPUT_SOFT = 2,       /* ShadowctsOutputs::visible_fraction */
  SHADOWCTS_OUTPUT_LIGHT_LISTS = 3 /* ShadowctsOutputs::list_* */
} ShadowctsOutputKind;

/* Light kinds a variant handles (bits of ShadowctsVariant::light_kinds). A case whose light the
 * variant does not declare is NotSupported for it. Hard-shadow variants see a sun disk as a
 * directional light of its centre direction; they declare POINT and/or DIRECTIONAL. */
#define SHADOWCTS_LIGHT_POINT 1u
#define SHADOWCTS_LIGHT_DIRECTIONAL 2u
#define SHADOWCTS_LIGHT_SUN_DISK 4u /* soft shadows */
#define SHADOWCTS_LIGHT_RANGED 8u   /* light assignment: spheres and spot lights */
#define SHADOWCTS_LIGHT_ALL_KINDS 15u

/* Bits of ShadowctsVariant::flags. NEEDS_CLOSED_MESHES: NotSupported unless every caster mesh is
 * closed. APPROXIMATE: approximate by design, robust mismatches are QualityWarning, not Fail.
 * NEEDS_SAMPLES_IN_THEIR_PIXELS: NotSupported unless every sample lies in front of the camera and
 * inside the view frustum of its own pixel (samples cast from the camera, not placed by a G-buffer
 * from elsewhere or a fuzzer), as bounds built from pixel coordinates alone need (added within
 * version 1: a suite that predates it rejects the bit as unknown). */
#define SHADOWCTS_VARIANT_NEEDS_CLOSED_MESHES 1u
#define SHADOWCTS_VARIANT_APPROXIMATE 2u
#define SHADOWCTS_VARIANT_NEEDS_SAMPLES_IN_THEIR_PIXELS 4u
#define SHADOWCTS_VARIANT_ALL_FLAGS 7u

/* Longest name the suite accepts (identity strings, variant names), without the terminating 0. */
#define SHADOWCTS_MAX_NAME_LENGTH 63u

/* The case's shadow light, as the variant's output kind sees it (hard shadows: a sun disk is
 * given as DIRECTIONAL with its centre direction). */
typedef struct ShadowctsLight {
  uint32_t kind;        /* SHADOWCTS_LIGHT_POINT, _DIRECTIONAL or _SUN_DISK; 0: the case has none */
  float position[3];    /* point light */
  float direction[3];   /* directional and sun disk: unit vector from the scene to the light */
  float angular_radius; /* sun disk: radians */
} ShadowctsLight;

/* The prepared scene of one case (include/shadowcts/prepared_scene.h), caller-owned and valid
 * for the duration of one run call. */
typedef struct ShadowctsScene {
  uint32_t struct_size;  /* sizeof(ShadowctsScene) of the suite */
  const char* case_name; /* e.g. "gate_house.20k", for messages */

  /* Every triangle of the case; receivers index them. Corner k of triangle t is
   * (x[k][t], y[k][t], z[k][t]). */
  uint64_t triangle_count;
  const float* x[3];
  const float* y[3];
  const float* z[3];
  const uint32_t* mesh; /* per triangle: index into the mesh arrays */
  const uint8_t* casts; /* per triangle: 1 when it may shadow (caster mesh, non-zero area) */
  uint64_t mesh_count;
  const uint8_t* mesh_closed; /* per mesh: a closed surface */
  const uint8_t* mesh_casts;  /* per mesh: casts shadows */

  /* The regular samples (the ones that are judged), compacted, in pixel order. */
  uint64_t sample_count;
  const uint32_t* sample_pixel; /* pixel index = y * width + x */
  const float *px, *py, *pz;    /* position */
  const float *nx, *ny, *nz;    /* geometric normal, unit, facing the camera */
  const uint32_t* receiver;     /* triangle the sample lies on, or SHADOWCTS_NO_RECEIVER */

  ShadowctsLight light;
  double scale; /* S: the largest absolute coordinate of the case */
  double tau;   /* the ambiguity band's half-width, eps_rel * S */

  /* The camera (light assignment tiles and clusters are built in its view). */
  float camera_position[3], camera_target[3], camera_up[3];
  float vertical_fov_degrees, near_plane, far_plane;
  uint32_t width, height; /* pixels */

  /* Ranged lights (light assignment): kind 0 sphere, 1 spot. */
  uint64_t ranged_light_count;
  const uint32_t* ranged_kind;
  const float *ranged_cx, *ranged_cy, *ranged_cz, *ranged_range;
  const float *ranged_dx, *ranged_dy, *ranged_dz, *ranged_cone_half_angle;

  uint32_t threads; /* worker threads the port may use; 0: as many as it likes */
} ShadowctsScene;

#define SHADOWCTS_NO_RECEIVER 0xFFFFFFFFu
#define SHADOWCTS_NO_LIST 0xFFFFFFFFu

/* One named work counter (nodes visited, pair tests, ...), reported in results.json. */
typedef struct ShadowctsCounter {
  char name[SHADOWCTS_MAX_NAME_LENGTH + 1];
  uint64_t value;
} ShadowctsCounter;

/* Caller-owned outputs of one run, sized by the suite; the port writes only those of its
 * variant's output kind (the others are null). */
typedef struct ShadowctsOutputs {
  uint32_t struct_size; /* sizeof(ShadowctsOutputs) of the suite */

  /* HARD: per regular sample, 1 shadowed, 0 lit (sample_count entries, zeroed). */
  uint8_t* shadowed;
  /* SOFT: per regular sample, the visible fraction of the sun disk in [0, 1]. */
  float* visible_fraction;

  /* LIGHT_LISTS: list k holds list_lights[list_offsets[k] .. list_offsets[k + 1]) (indices of
   * ranged lights); list_bounds[6k .. 6k + 6) is the box (min xyz, max xyz) its lights were culled
   * against; list_of_sample[i] is the list regular sample i uses (or SHADOWCTS_NO_LIST). The port
   * sets list_count and light_count; when they exceed the capacities it returns
   * SHADOWCTS_STATUS_OUTPUT_TOO_SMALL and is called again with larger buffers. */
  uint64_t list_capacity;  /* list_offsets holds list_capacity + 1 entries, list_bounds 6x */
  uint64_t light_capacity; /* list_lights entries */
  uint64_t list_count;
  uint64_t light_count;
  uint32_t* list_offsets;
  uint32_t* list_lights;
  float* list_bounds;
  uint32_t* list_of_sample; /* sample_count entries */

  /* Optional work counters: the port writes up to counter_capacity and sets counter_count. */
  uint32_t counter_capacity;
  uint32_t counter_count;
  ShadowctsCounter* counters;
} ShadowctsOutputs;

/* Runs one variant on one case. `context` is ShadowctsBackend::context. Writes at most
 * message_capacity bytes (0-terminated) into `message` on an error. Must be deterministic: the
 * suite runs every case more than once, in separate processes, and different outputs are a Fail. */
typedef int32_t (*ShadowctsRunFunction)(void* context, const ShadowctsScene* scene,
                                        ShadowctsOutputs* outputs, char* message,
                                        size_t message_capacity);

/* One variant the port implements, with its capabilities declared up front. */
typedef struct ShadowctsVariant {
  const char* name;     /* non-empty, [a-z0-9_+-], at most SHADOWCTS_MAX_NAME_LENGTH */
  uint32_t algorithm;   /* ShadowctsAlgorithm */
  uint32_t output_kind; /* ShadowctsOutputKind; must match the algorithm */
  uint32_t light_kinds; /* SHADOWCTS_LIGHT_* bits; non-zero, fitting the output kind */
  uint32_t flags;       /* SHADOWCTS_VARIANT_* bits */
  /* Size limits: the variant is NotSupported above them. Non-zero; UINT64_MAX for none. */
  uint64_t max_triangles;
  uint64_t max_regular_samples;
  uint64_t max_sample_triangle_pairs;
  /* SOFT only: the error the variant declares it may make (visible fraction, in [0, 1]): per
   * robust sample and mean; 0 claims exactness. */
  double soft_error_per_sample;
  double soft_error_mean;
  ShadowctsRunFunction run; /* never null */
} ShadowctsVariant;

/* The table shadowcts_backend_negotiate fills. */
typedef struct ShadowctsBackend {
  uint32_t struct_size; /* set by the suite: sizeof(ShadowctsBackend) */
  uint32_t abi_version; /* set by the port: the version it speaks (== the requested one) */
  /* Identity: non-empty, printable ASCII, at most SHADOWCTS_MAX_NAME_LENGTH. `name` becomes the
   * backend's id in results ([a-z0-9_-]). Static strings the library keeps while loaded. */
  const char* name;
  const char* version;
  const char* build_id;
  void* context;                    /* passed to every run; may be null */
  uint32_t variant_count;           /* at least 1 */
  const ShadowctsVariant* variants; /* variant_count entries, static */
} ShadowctsBackend;

typedef int32_t (*ShadowctsNegotiateFunction)(uint32_t requested_abi_version,
                                              ShadowctsBackend* table);

/* What the library exports (define it with this prototype). */
#if defined(__GNUC__)
#define SHADOWCTS_BACKEND_EXPORT __attribute__((visibility("default")))
#else
#define SHADOWCTS_BACKEND_EXPORT
#endif
SHADOWCTS_BACKEND_EXPORT int32_t shadowcts_backend_negotiate(uint32_t requested_abi_version,
                                                             ShadowctsBackend* table);

#ifdef __cplusplus
}
#endif

#endif /* SHADOWCTS_BACKEND_ABI_H */
