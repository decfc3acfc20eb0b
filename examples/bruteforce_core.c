/* See bruteforce_core.h. Plain C99 plus POSIX threads. */
#include "bruteforce_core.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct Job {
  const ShadowctsScene* scene;
  ShadowctsOutputs* outputs;
  ExampleFault fault;
  int point_light;     /* else directional */
  double light[3];     /* L, or the direction d towards the light */
  uint64_t begin, end; /* regular samples [begin, end) */
  const float* boxes;  /* per triangle: its box, min xyz then max xyz */
  uint64_t pair_tests, predicate_calls;
} Job;

static void corner(const ShadowctsScene* s, uint64_t t, int k, double v[3]) {
  v[0] = s->x[k][t];
  v[1] = s->y[k][t];
  v[2] = s->z[k][t];
}

static void sub(const double a[3], const double b[3], double out[3]) {
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Watertight ray-triangle test (Woop, Benthin, Wald 2013) from origin o along dir, for the
 * parameter range [0, t_max] (t_max < 0: unbounded). The shear is the same for every triangle,
 * and each edge function is computed from the same two sheared vertices in both triangles that
 * share the edge, so its value is exactly negated there: a ray through a shared edge meets at
 * least one of the two. On a hit, *t is the parameter of the hit. */
static int watertight_hit(const double o[3], const double dir[3], double t_max, const double v0[3],
                          const double v1[3], const double v2[3], ExampleFault fault, double* t) {
  int kz = 0;
  if (fabs(dir[1]) > fabs(dir[kz])) kz = 1;
  if (fabs(dir[2]) > fabs(dir[kz])) kz = 2;
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (dir[kz] < 0.0) {
    const int swap = kx;
    kx = ky;
    ky = swap;
  }
  const double sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz], sz = 1.0 / dir[kz];
  double a[3], b[3], c[3];
  sub(v0, o, a);
  sub(v1, o, b);
  sub(v2, o, c);
  const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  const double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return 0;
  const double det = u + v + w;
  if (det == 0.0) return 0; /* the ray lies in the triangle's plane */
  if (fault == EXAMPLE_FAULT_EDGE_CRACK) {
    const double crack = 1e-2 * fabs(det);
    if (fabs(u) < crack || fabs(v) < crack || fabs(w) < crack) return 0;
  }
  const double az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
  const double tt = u * az + v * bz + w * cz;
  if (det > 0.0 ? tt < 0.0 : tt > 0.0) return 0;
  if (t_max >= 0.0 && (det > 0.0 ? tt > t_max * det : tt < t_max * det)) return 0;
  *t = tt / det;
  return 1;
}

static int sign_of(double x) {
  return (x > 0.0) - (x < 0.0);
}

static int sample_shadowed(Job* job, uint64_t i) {
  const ShadowctsScene* s = job->scene;
  const double p[3] = {s->px[i], s->py[i], s->pz[i]};
  double dir[3];
  if (job->point_light)
    sub(job->light, p, dir);
  else
    memcpy(dir, job->light, sizeof dir);
  const double t_max = job->point_light ? 1.0 : -1.0;
  /* The box of the segment (unbounded along the ray for a directional light). */
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    const double end = job->point_light ? job->light[k] : (dir[k] > 0.0 ? INFINITY : -INFINITY);
    lo[k] = fmin(p[k], end);
    hi[k] = fmax(p[k], end);
    if (!job->point_light && dir[k] == 0.0) lo[k] = hi[k] = p[k];
  }
  /* The receiver's plane: f(x) = n . (x - a), with `side` the sign of the light's side. */
  const uint32_t r = s->receiver[i];
  int rule = 0, side = 0;
  double ra[3] = {0.0, 0.0, 0.0}, n[3] = {0.0, 0.0, 0.0};
  if (r != SHADOWCTS_NO_RECEIVER && r < s->triangle_count) {
    double rb[3], rc[3], e1[3], e2[3];
    corner(s, r, 0, ra);
    corner(s, r, 1, rb);
    corner(s, r, 2, rc);
    sub(rb, ra, e1);
    sub(rc, ra, e2);
    cross(e1, e2, n);
    if (n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0) {
      rule = 1;
      if (job->point_light) {
        double la[3];
        sub(job->light, ra, la);
        side = sign_of(dot(n, la));
      } else {
        side = sign_of(dot(n, dir));
      }
      if (side == 0) return 0; /* grazing: no point is strictly on the light's side */
    }
  }
  double pa[3];
  if (rule) sub(p, ra, pa);
  const double fp = rule ? side * dot(n, pa) : 0.0;
  const double fdir = rule ? side * dot(n, dir) : 0.0; /* f along the segment: fp + t * fdir */
  for (uint64_t t = 0; t < s->triangle_count; ++t) {
    ++job->pair_tests;
    if (t == r || !s->casts[t]) continue;
    const float* box = job->boxes + 6 * t; /* min xyz, max xyz */
    if (box[3] < lo[0] || box[0] > hi[0] || box[4] < lo[1] || box[1] > hi[1] || box[5] < lo[2] ||
        box[2] > hi[2])
      continue;
    double v[3][3];
    int above = 0;
    for (int k = 0; k < 3; ++k) {
      corner(s, t, k, v[k]);
      if (rule) {
        double va[3];
        sub(v[k], ra, va);
        above += side * dot(n, va) > 0.0;
      } else {
        ++above;
      }
    }
    if (above == 0) continue; /* no vertex strictly on the light's side: never shadows here */
    ++job->predicate_calls;
    double hit_t = 0.0;
    if (!watertight_hit(p, dir, t_max, v[0], v[1], v[2], job->fault, &hit_t)) continue;
    if (above == 3 || fp + hit_t * fdir > 0.0) return 1;
  }
  return 0;
}

static void* run_job(void* argument) {
  Job* job = (Job*)argument;
  for (uint64_t i = job->begin; i < job->end; ++i)
    job->outputs->shadowed[i] = (uint8_t)sample_shadowed(job, i);
  return NULL;
}

static void add_counter(ShadowctsOutputs* o, const char* name, uint64_t value) {
  if (o->counter_count >= o->counter_capacity) return;
  ShadowctsCounter* c = &o->counters[o->counter_count++];
  snprintf(c->name, sizeof c->name, "%s", name);
  c->value = value;
}

int32_t example_bruteforce_run(const ShadowctsScene* scene, ShadowctsOutputs* outputs,
                               ExampleFault fault, char* message, size_t message_capacity) {
  if (scene->struct_size != sizeof(ShadowctsScene) ||
      outputs->struct_size != sizeof(ShadowctsOutputs) || !outputs->shadowed) {
    snprintf(message, message_capacity, "ABI structs of another size or no shadow output");
    return SHADOWCTS_STATUS_ERROR;
  }
  const uint32_t kind = scene->light.kind;
  if (kind != SHADOWCTS_LIGHT_POINT && kind != SHADOWCTS_LIGHT_DIRECTIONAL) {
    snprintf(message, message_capacity, "case %s: light kind %u is not declared", scene->case_name,
             (unsigned)kind);
    return SHADOWCTS_STATUS_ERROR;
  }
  long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  uint64_t threads = scene->threads ? scene->threads : (uint64_t)(cpus > 0 ? cpus : 1);
  if (threads > 64) threads = 64;
  if (threads > scene->sample_count) threads = scene->sample_count ? scene->sample_count : 1;
  float* boxes =
      (float*)malloc(6 * sizeof(float) * (scene->triangle_count ? scene->triangle_count : 1));
  if (!boxes) {
    snprintf(message, message_capacity, "out of memory for %llu triangle boxes",
             (unsigned long long)scene->triangle_count);
    return SHADOWCTS_STATUS_ERROR;
  }
  for (uint64_t t = 0; t < scene->triangle_count; ++t) {
    const float* axes[3][3] = {{scene->x[0], scene->x[1], scene->x[2]},
                               {scene->y[0], scene->y[1], scene->y[2]},
                               {scene->z[0], scene->z[1], scene->z[2]}};
    for (int k = 0; k < 3; ++k) {
      boxes[6 * t + k] = fminf(fminf(axes[k][0][t], axes[k][1][t]), axes[k][2][t]);
      boxes[6 * t + 3 + k] = fmaxf(fmaxf(axes[k][0][t], axes[k][1][t]), axes[k][2][t]);
    }
  }
  Job jobs[64];
  pthread_t ids[64];
  for (uint64_t j = 0; j < threads; ++j) {
    Job* job = &jobs[j];
    memset(job, 0, sizeof *job);
    job->scene = scene;
    job->outputs = outputs;
    job->fault = fault;
    job->boxes = boxes;
    job->point_light = kind == SHADOWCTS_LIGHT_POINT;
    for (int k = 0; k < 3; ++k)
      job->light[k] = job->point_light ? scene->light.position[k] : scene->light.direction[k];
    job->begin = scene->sample_count * j / threads;
    job->end = scene->sample_count * (j + 1) / threads;
  }
  uint64_t started = 0;
  for (uint64_t j = 1; j < threads; ++j, ++started)
    if (pthread_create(&ids[j], NULL, run_job, &jobs[j]) != 0) break;
  run_job(&jobs[0]);
  for (uint64_t j = started + 1; j < threads; ++j)
    run_job(&jobs[j]); /* threads that failed to start */
  for (uint64_t j = 1; j <= started; ++j) pthread_join(ids[j], NULL);
  free(boxes);
  uint64_t pairs = 0, calls = 0;
  for (uint64_t j = 0; j < threads; ++j) {
    pairs += jobs[j].pair_tests;
    calls += jobs[j].predicate_calls;
  }
  add_counter(outputs, "pair_tests", pairs);
  add_counter(outputs, "predicate_calls", calls);
  return SHADOWCTS_STATUS_OK;
}
