#include "known_limits.h"

#include <fnmatch.h>

#include <algorithm>

namespace shadowcts {

const std::vector<RecordLimit>& stiff_record_limits() {
  // The stiff cases that show a method's known limit. The stiff-suite test checks that every
  // entry still fails, so whoever fixes one must delete it here.
  static const std::vector<RecordLimit> table = {
      {"hard.stencil.zpass.reference.stiff.camera_in_shadow_volume",
       "z-pass counts shadow-volume faces between the eye and the sample: with the eye inside a "
       "volume every count is off by one (the eye-in-shadow failure z-fail exists to fix)"},
      {"hard.stencil.zpass.reference.stiff.light_inside_closed_mesh",
       "z-pass with the light inside a closed mesh: the volumes of its inner faces contain the "
       "eye, "
       "the same eye-in-shadow failure"},
      {"hard.embree.*.stiff.light_at_caster_vertex",
       "Embree's float ray along the rounded L - p ends at t = 1 next to the caster's corner at L "
       "and "
       "misses it for a few samples; the band moves p, not L, so these samples count as robust"},
      {"hard.embree.*.stiff.light_1e-6_from_caster",
       "segments cross the quad's plane within ~3e-8 of its edge near L; any float evaluation errs "
       "by "
       "~ulp * |L - p| there, rounding at the light end that the band (moves of p) does not cover"},
      // Every backend of softtile:post: they answer alike.
      {"soft.softtile.post.*.stiff.sun_radius_45_degrees",
       "the post's sin(a) normalization rasterizes a disk of tangent radius sin(a) instead of "
       "tan(a); "
       "its budget covers a <= ~5.7 degrees (docs/soft-shadow-budgets.md), and at 45 degrees the "
       "missing annulus is half the disk"},
      // Shadow maps beyond their declared ceiling on the robust mismatch rate (measured
      // 2026-12-02; the ceilings are in reference/shadowmap/shadowmap_algorithm.cpp). The biased
      // maps only: the unbiased map's ceiling (0.6) covers these.
      {"hard.shadowmap.[1248]k.reference.stiff.light_at_caster_vertex",
       "a shadow map's blind spot: the light touches a caster, and the cube map's near plane (1e-4 "
       "of the scene scale) clips the part of it around the light away, so the map misses the "
       "caster that shadows most of the scene (robust mismatch rate 0.94)"},
      {"hard.shadowmap.[1248]k.reference.stiff.light_on_caster_edge",
       "the same near-plane blind spot: the light inside a caster's edge (rate 0.94)"},
      {"hard.shadowmap.[1248]k.reference.stiff.light_1ulp_off_caster_edge",
       "the same near-plane blind spot: the light a float step off a caster's edge (rate "
       "0.92-0.94)"},
      {"hard.shadowmap.[1248]k.reference.stiff.light_in_caster_face",
       "the same near-plane blind spot: the light inside a caster's face (rate 0.94)"},
      {"hard.shadowmap.[1248]k.reference.stiff.light_1ulp_off_caster_face",
       "the same near-plane blind spot: the light a float step off a caster's face (rate "
       "0.92-0.95)"},
      {"hard.shadowmap.[1248]k.reference.stiff.light_1e-6_from_caster",
       "the same near-plane blind spot: the light 1e-6 beside a caster's edge (rate 0.49-0.52)"},
      {"hard.shadowmap.*.reference.stiff.grazing_receivers",
       "the sun 2^-10 rad above the ground: a texel of the fitted orthographic map covers about a "
       "thousand times its width of ground, so the depth test decides most lit ground wrongly "
       "(rate 0.33-0.86); no resolution or bias covers a grazing light"},
  };
  return table;
}

const RecordLimit* stiff_record_limit(const std::string& record_name) {
  for (const RecordLimit& e : stiff_record_limits())
    if (fnmatch(e.records, record_name.c_str(), 0) == 0) return &e;
  return nullptr;
}

std::string known_limit(const std::string& record_name, const std::string& algorithm_id,
                        const std::string& variant,
                        const std::vector<fuzzing::KnownLimit>& case_limits,
                        const std::vector<std::size_t>& wrong_samples) {
  if (const RecordLimit* entry = stiff_record_limit(record_name)) return entry->why;
  if (wrong_samples.empty()) return "";  // failed otherwise (a budget, a rerun): no limit says why
  for (const fuzzing::KnownLimit& limit : case_limits) {
    if (limit.algorithm_id != algorithm_id) continue;
    if (!limit.variant.empty() && limit.variant != variant) continue;
    const bool covers_all =
        limit.samples.empty() ||
        std::all_of(wrong_samples.begin(), wrong_samples.end(), [&](std::size_t i) {
          return std::find(limit.samples.begin(), limit.samples.end(), i) != limit.samples.end();
        });
    if (covers_all) return limit.why;
  }
  return "";
}

}  // namespace shadowcts
