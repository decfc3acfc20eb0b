// The stencil shadow-volume baseline: exact, consistent crossing decisions, silhouettes from
// connectivity, and the eye-in-shadow failure of z-pass that z-fail does not have.
#include "reference/stencil/stencil_algorithm.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "oracles/exact_segment_triangle.h"
#include "reference/stencil/robust_orientation.h"
#include "reference/stencil/silhouette.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/scene_file.h"

namespace shadowcts {
namespace {

using namespace stencil;

TEST(Stencil, DescribesItself) {
  const auto algorithm = make_stencil();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "stencil");
  EXPECT_EQ(info.backend, "reference");
  EXPECT_EQ(info.variants, (std::vector<std::string>{"zfail", "zpass"}));
  EXPECT_FALSE(info.capabilities.approximate);
  EXPECT_FALSE(info.capabilities.needs_closed_meshes);
}

// How many of the fan's triangles the line crosses, with the direction of each.
int crossings(const glm::dvec3& l0, const glm::dvec3& l1, const std::vector<glm::dvec3>& fan_rim,
              const glm::dvec3& apex, int& net) {
  int crossed = 0;
  net = 0;
  for (std::size_t i = 0; i < fan_rim.size(); ++i) {
    const glm::dvec3 &a = apex, &b = fan_rim[i], &c = fan_rim[(i + 1) % fan_rim.size()];
    const int s = edge_side(l0, l1, a, b);
    if (s != 0 && edge_side(l0, l1, b, c) == s && edge_side(l0, l1, c, a) == s) {
      ++crossed;
      net += s;
    }
  }
  return crossed;
}

TEST(StencilOrientation, LinesThroughSharedVerticesAndEdgesCountConsistently) {
  // A square pyramid fan around the apex (0, 3, 0); lines through the apex and along shared edges
  // are exactly the ties simulation of simplicity has to break.
  const glm::dvec3 apex{0, 3, 0};
  const std::vector<glm::dvec3> rim = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  for (const glm::dvec3& below : {glm::dvec3(0, 0, 0), glm::dvec3(0.5, 0, 0),
                                  glm::dvec3(0, 0, -0.25), glm::dvec3(0.25, 0, 0.25)}) {
    int net = 0;
    EXPECT_EQ(crossings(below, apex, rim, apex, net), 1) << below.x << " " << below.z;
    EXPECT_EQ(std::abs(net), 1);
  }
  // A closed octahedron: an infinite line through its interior crosses it exactly twice, once
  // each way, also where it passes exactly through shared vertices and edges; a line touching it
  // from outside crosses it an even number of times, net zero.
  const std::vector<glm::dvec3> ring = {{1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}};
  const glm::dvec3 top{0, 1, 0}, bottom{0, -1, 0};
  const auto octahedron_crossings = [&](const glm::dvec3& l0, const glm::dvec3& l1, int& net) {
    int up_net = 0, down_net = 0;
    std::vector<glm::dvec3> reversed(ring.rbegin(), ring.rend());
    const int count =
        crossings(l0, l1, ring, top, up_net) + crossings(l0, l1, reversed, bottom, down_net);
    net = up_net + down_net;
    return count;
  };
  const glm::dvec3 centre{0, 0, 0};
  for (const glm::dvec3& through : {top, ring[0], glm::dvec3(0.5, 0.5, 0), glm::dvec3(0.5, 0, 0.5),
                                    glm::dvec3(0, 0.5, -0.5), glm::dvec3(0.25, 0.5, 0.25)}) {
    int net = 0;
    EXPECT_EQ(octahedron_crossings(centre, through, net), 2)
        << through.x << " " << through.y << " " << through.z;
    EXPECT_EQ(net, 0);
  }
  for (const glm::dvec3& direction : {glm::dvec3(0, 1, 1), glm::dvec3(0, 1, -1)}) {
    int net = 0;
    const int count = octahedron_crossings(ring[0], ring[0] + direction, net);  // touches a vertex
    EXPECT_EQ(count % 2, 0);
    EXPECT_EQ(net, 0);
  }
  // Antisymmetry, also in a tie.
  EXPECT_EQ(edge_side({0, 0, 0}, apex, apex, rim[1]), -edge_side({0, 0, 0}, apex, rim[1], apex));
  EXPECT_NE(edge_side({0, 0, 0}, apex, apex, rim[1]), 0);
}

Case base_case(const ShadowLight& light) {
  Case c;
  c.name = "stencil_hand_built";
  c.source = "stencil_test.cpp";
  c.light = light;
  return c;
}

void add_ground(Case& c, float half) {
  c.meshes.push_back(Mesh{"ground", false, true});  // open, and a caster
  const auto m = std::uint32_t(c.meshes.size() - 1);
  const glm::vec3 a{-half, 0, -half}, b{-half, 0, half}, d{half, 0, half}, e{half, 0, -half};
  c.triangles.push_back({a, b, d, m});
  c.triangles.push_back({a, d, e, m});
}

// A closed axis-aligned box with outward-facing triangles.
void add_box(Case& c, const glm::vec3& lo, const glm::vec3& hi) {
  c.meshes.push_back(Mesh{"box", true, true});
  const auto m = std::uint32_t(c.meshes.size() - 1);
  const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec3 u(0.0f), v(0.0f), n(0.0f);
      n[axis] = sign * half[axis];
      u[(axis + 1) % 3] = half[(axis + 1) % 3];
      v[(axis + 2) % 3] = half[(axis + 2) % 3];
      if (sign < 0) std::swap(u, v);  // keep u x v pointing out
      const glm::vec3 p00 = centre + n - u - v, p10 = centre + n + u - v, p11 = centre + n + u + v,
                      p01 = centre + n - u + v;
      c.triangles.push_back({p00, p10, p11, m});
      c.triangles.push_back({p00, p11, p01, m});
    }
}

// The stencil's front-face rule and the loaders' Mesh::closed use one definition of closedness
// (shadowcts/closed_surface.h): on open, closed, non-manifold and duplicated-face meshes, the mesh
// a file loads as is closed exactly when the stencil treats it as closed.
TEST(StencilSilhouette, ClosednessAgreesWithTheLoaders) {
  struct Shape {
    std::string name, faces;
    int face_count;
    bool closed;
  };
  // Vertices 0-3: a tetrahedron; 4: a point below it (for a fin on the edge 0-1).
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n";
  const std::string tetrahedron = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::vector<Shape> shapes = {
      {"closed", tetrahedron, 4, true},
      {"open", "3 0 2 1\n3 0 1 3\n3 0 3 2\n", 3, false},
      {"non_manifold", tetrahedron + "3 1 0 4\n3 0 1 4\n", 6, false},  // a two-sided fin on 0-1
      {"duplicated_face", tetrahedron + "3 0 2 1\n", 5, false},
      {"duplicated_reversed_face", tetrahedron + "3 0 1 2\n", 5, false},
  };
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "shadowcts_stencil_closedness";
  std::filesystem::create_directories(dir);
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {0.3f, 1.0f, 0.2f};
  for (const Shape& shape : shapes) {
    const std::filesystem::path file = dir / (shape.name + ".off");
    std::ofstream(file) << "OFF\n5 " << shape.face_count << " 0\n" << vertices << shape.faces;
    const LoadedScene loaded = load_scene_file(file.string());
    ASSERT_EQ(loaded.meshes.size(), 1u) << shape.name;
    EXPECT_EQ(loaded.meshes[0].closed, shape.closed) << shape.name;
    Case c = base_case(light);
    c.meshes = loaded.meshes;
    c.triangles = loaded.triangles;
    const Occluders occluders = find_occluders(c, hard_shadow_light(c));
    EXPECT_EQ(occluders.closed_meshes, shape.closed ? 1u : 0u) << shape.name;
  }
  std::filesystem::remove_all(dir);
}

TEST(StencilSilhouette, ClosedBoxUnderAnOverheadLightHasTheTopRimAsSilhouette) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {0, 1, 0};
  Case c = base_case(light);
  add_box(c, {-1, 3, -1}, {1, 4, 1});
  const Occluders box = find_occluders(c, hard_shadow_light(c));
  EXPECT_EQ(box.closed_meshes, 1u);
  EXPECT_EQ(box.caps.size(), 2u);        // the top; the sides are edge-on, the bottom faces away
  EXPECT_EQ(box.silhouette.size(), 4u);  // its rim; the diagonal is shared and cancels
  // An open ground: both triangles are caps, only its 4 boundary edges are silhouettes.
  add_ground(c, 8);
  const Occluders both = find_occluders(c, hard_shadow_light(c));
  EXPECT_EQ(both.closed_meshes, 1u);
  EXPECT_EQ(both.caps.size(), 4u);
  EXPECT_EQ(both.silhouette.size(), 8u);
}

// The stiff case for stencil shadows: the camera sits under a closed box, inside its shadow
// volume, and looks at a ground plane that is partly in the box's shadow.
Case eye_in_shadow_case(const ShadowLight& light) {
  Case c = base_case(light);
  c.name = "stencil_eye_in_shadow";
  add_ground(c, 40);
  add_box(c, {-1, 3, -1}, {1, 4, 1});
  c.camera.position = {0.0625f, 1.5f, 0.03125f};
  c.camera.target = {3.0f, 0.0f, 0.5f};
  c.camera.vertical_fov_degrees = 70.0f;
  c.camera.width = 96;
  c.camera.height = 96;
  validate(c);
  return c;
}

void expect_eye_in_shadow_results(const Case& c) {
  const ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  std::size_t robust_shadowed = 0, robust_lit = 0;
  for (BandClass b : truth.band) {
    robust_shadowed += b == BandClass::robust_shadowed;
    robust_lit += b == BandClass::robust_lit;
  }
  ASSERT_GT(robust_shadowed, 100u);  // the view sees both sides of the shadow boundary
  ASSERT_GT(robust_lit, 100u);
  const auto algorithm = make_stencil();
  ASSERT_FALSE(algorithm->unsupported_reason(c, samples, "zpass"));
  const HardShadowComparison zpass =
      compare_hard_shadows(algorithm->run(c, samples, "zpass").shadowed, truth);
  const HardShadowComparison zfail =
      compare_hard_shadows(algorithm->run(c, samples, "zfail").shadowed, truth);
  // z-pass starts counting at 0 in the eye, which is really inside one volume: every robust
  // answer flips.
  EXPECT_EQ(zpass.verdict, Verdict::fail);
  EXPECT_EQ(zpass.leaks, robust_shadowed);
  EXPECT_EQ(zpass.false_shadows, robust_lit);
  EXPECT_EQ(zfail.verdict, Verdict::pass) << zfail.reason;
  EXPECT_EQ(zfail.leaks + zfail.false_shadows, 0u);
}

TEST(StencilEyeInShadow, ZPassFailsAndZFailPassesUnderAPointLight) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {0.25f, 10.0f, 0.125f};
  expect_eye_in_shadow_results(eye_in_shadow_case(light));
}

TEST(StencilEyeInShadow, ZPassFailsAndZFailPassesUnderADirectionalLight) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {-0.25f, 1.0f, 0.0625f};  // the shadow falls towards +x, into the view
  expect_eye_in_shadow_results(eye_in_shadow_case(light));
}

Case hard_view(Case c) {
  if (c.light && c.light->kind == ShadowLightKind::sun_disk) {
    c.light->kind = ShadowLightKind::directional;
    c.light->angular_radius = 0.0f;
  }
  return c;
}

TEST(StencilAgainstExactOracle, ZFailIsRightOnEveryRobustSampleOfTheDefaultFixtures) {
  const auto algorithm = make_stencil();
  int fixtures = 0;
  for (const std::string& name : default_fixtures()) {
    const Case c = hard_view(make_fixture(name));
    if (!c.light) continue;
    const ViewSamples samples = generate_view_samples(c);
    ASSERT_FALSE(algorithm->unsupported_reason(c, samples, "zfail")) << name;
    const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
    const AlgorithmOutput output = algorithm->run(c, samples, "zfail");
    const HardShadowComparison h = compare_hard_shadows(output.shadowed, truth);
    EXPECT_EQ(h.leaks, 0u) << name;
    EXPECT_EQ(h.false_shadows, 0u) << name;
    EXPECT_GT(h.robust, 0u) << name;
    ASSERT_EQ(output.counters.size(), 7u);
    EXPECT_EQ(output.counters[0].first, "silhouette_edges");
    EXPECT_GT(output.counters[0].second, 0u) << name;
    EXPECT_EQ(output.counters[2].first, "quads_tested");
    ASSERT_EQ(output.per_sample_counters.size(), 1u);
    EXPECT_EQ(output.per_sample_counters[0].second.size(), samples.samples.size());
    ++fixtures;
  }
  EXPECT_GE(fixtures, 5);
}

TEST(Stencil, SameResultForAnyThreadCount) {
  Case c = make_fixture("ground_blockers.10k");
  const ViewSamples samples = generate_view_samples(c);
  const auto algorithm = make_stencil();
  for (const char* variant : {"zfail", "zpass"}) {
    c.parameters.threads = 2;
    const AlgorithmOutput many = algorithm->run(c, samples, variant);
    c.parameters.threads = 1;
    const AlgorithmOutput one = algorithm->run(c, samples, variant);
    EXPECT_EQ(one.shadowed, many.shadowed) << variant;
    EXPECT_EQ(one.counters, many.counters) << variant;
  }
}

// A point light on a caster: that triangle (exactly decided) is no cap, and it shadows every
// sample it does not receive (the definition's closed segment), as in ptsv and psv.
TEST(Stencil, APointLightOnACasterShadowsEverySampleItDoesNotReceive) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {0.0f, 4.0f, 0.0f};  // on the box's top face
  const Case c = eye_in_shadow_case(light);
  const ViewSamples samples = generate_view_samples(c);
  const auto stencil = make_stencil();
  ASSERT_FALSE(stencil->unsupported_reason(c, samples, "zfail"));
  const AlgorithmOutput output = stencil->run(c, samples, "zfail");
  const HardShadowComparison h =
      compare_hard_shadows(output.shadowed, exact_hard_shadow_oracle(c, samples));
  EXPECT_GT(h.robust, 0u);
  EXPECT_EQ(h.leaks, 0u);
  EXPECT_EQ(h.false_shadows, 0u);
  // Every ground sample's segment already crosses the box's walls below the light: the rule
  // changes no sample here (the stiff cases light_on_caster_edge and light_in_caster_face, where
  // the caster is open, depend on it).
  EXPECT_EQ(output.counters.back().first, "light_on_caster_samples");
}

// Minimal fuzz reproducers (one sample each), rebuilt in code. Each checks first that the eye
// is lit (no caster meets its segment to the point light or its ray towards the directional
// light), where z-pass must be exact too, and that the exact oracle calls the sample robust.
struct Reproducer {
  Case c;
  ViewSample sample;
};

Case reproducer_case(const ShadowLight& light, const glm::vec3& eye, const glm::vec3& target,
                     float near_plane, float far_plane) {
  Case c = base_case(light);
  c.name = "stencil_fuzz_reproducer";
  c.meshes = {Mesh{"part0", false, false}, Mesh{"part1", false, true}};
  c.camera.position = eye;
  c.camera.target = target;
  c.camera.near_plane = near_plane;
  c.camera.far_plane = far_plane;
  c.camera.width = 1;
  c.camera.height = 1;
  return c;
}

void expect_both_variants_exact(const Reproducer& r, bool shadowed) {
  validate(r.c);
  ViewSamples samples;
  samples.width = samples.height = 1;
  samples.samples = {r.sample};
  samples.samples[0].sample_class = SampleClass::regular;  // re-derived just below
  classify_samples(r.c, samples, r.c.name);
  ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular);

  const HardShadowLight light = hard_shadow_light(r.c);
  const ExactShadowPredicate predicate(light, 2.0 * r.c.scale());
  MovedPoint eye;
  eye.base = glm::dvec3(r.c.camera.position);
  for (std::size_t i = 0; i < r.c.triangles.size(); ++i)
    ASSERT_FALSE(casts_shadow(r.c, i) && predicate.blocks(r.c.triangles[i], eye))
        << "the eye is in the shadow of triangle " << i;

  const HardShadowTruth truth = exact_hard_shadow_oracle(r.c, samples);
  ASSERT_TRUE(truth.band[0] == BandClass::robust_lit ||
              truth.band[0] == BandClass::robust_shadowed);
  ASSERT_EQ(truth.shadowed[0] != 0, shadowed);
  const auto algorithm = make_stencil();
  for (const char* variant : {"zfail", "zpass"}) {
    ASSERT_FALSE(algorithm->unsupported_reason(r.c, samples, variant));
    EXPECT_EQ(algorithm->run(r.c, samples, variant).shadowed[0], truth.shadowed[0]) << variant;
  }
}

// fuzz_differential-a39721c4cf38ab7a: the sample (on a small caster) is hidden from the eye
// behind the ground triangle, itself a caster: z-pass has to count the light cap that its eye
// segment enters.
TEST(StencilFuzzReproducer, ZPassCountsALightCapInFrontOfTheSample) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {-0.6360863447189331f, 0.1380854845046997f, -0.7591617703437805f};
  Reproducer r{reproducer_case(light, {-12.70687198638916f, 4.215230464935303f, -22.7977352142334f},
                               {4.0f, 0.5884010791778564f, -2.8582754135131836f},
                               1.3132550520822406e-05f, 13132.55078125f),
               {}};
  r.c.meshes[0].caster = true;
  r.c.triangles = {{{0, 0, -8}, {0, 0, 0}, {8, 0, 0}, 0},
                   {{1.0624275207519531f, -0.23539441823959351f, 0.87627381086349487f},
                    {1.4709442853927612f, 1.4121966361999512f, 0.65556478500366211f},
                    {1.8331978321075439f, -0.22112375497817993f, 2.2834491729736328f},
                    1}};
  r.sample.position = {1.0719585418701172f, -0.19698430597782135f, 0.87114191055297852f};
  r.sample.normal = {0, 0, -1};
  r.sample.receiver = 1;
  expect_both_variants_exact(r, true);
}

// fuzz_differential (e1603e48c96c4ef8): the eye at the point light, the sample exactly on the
// diagonal shared by two coplanar ground triangles, under a caster near the light. The eye line
// lies in the plane through the light and the diagonal, so it meets the diagonal, and the dark
// caps' copy of it, exactly: the tie that sent it past the receiver's light cap must send it past
// the receiver's dark cap too. Their rounded extruded vertices had decided that edge instead, so
// the receiver's own volume counted an exit without an entry and z-fail left the sample lit.
TEST(StencilFuzzReproducer, TheEyeAtThePointLightSeesTheDarkCapsEdgesAsTheirLightCapsEdges) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {3.229381561279297f, 5.300436019897461f, -4.149859428405762f};
  Reproducer r{
      reproducer_case(light, light.position, {-1.4753661155700684f, 2.917203426361084f, -4.0f},
                      1.6380588931497186e-05f, 16380.5888671875f),
      {}};
  r.c.meshes[0].caster = true;
  r.c.triangles = {{{-8, 0, -8}, {0, 0, 0}, {0, 0, -8}, 0},
                   {{-8, 0, -8}, {-8, 0, 0}, {0, 0, 0}, 0},
                   {{5.049267768859863f, 3.2916676998138428f, -7.19283390045166f},
                    {3.344972610473633f, 5.834406852722168f, -4.394125461578369f},
                    {2.418731212615967f, 2.7034213542938232f, -2.601506471633911f},
                    1}};
  r.sample.position = {-7.5f, 0, -7.5f};
  r.sample.normal = {0, 1, 0};
  r.sample.receiver = 0;
  expect_both_variants_exact(r, true);
  // The other receiver of the diagonal.
  r.sample.receiver = 1;
  expect_both_variants_exact(r, true);
}

// The directional counterpart: eyes up the light's direction from samples on the shared
// diagonal (the eye is the sample plus a multiple of the direction, exactly), a caster between.
TEST(StencilFuzzReproducer, AnEyeLineAlongTheDirectionalLightThroughASharedEdgeCountsOnce) {
  // Directions normalized in double are rounded, and so are the extruded vertices.
  const std::pair<glm::vec3, float> directions[] = {
      {{1, 2, 2}, 4.0f}, {{2, 3, 6}, 2.0f}, {{1, 4, 8}, 1.0f}, {{4, 4, 7}, 1.0f}};
  for (const auto& [direction, multiple] : directions)
    for (float k = 0.25f; k < 8.0f; k += 0.25f) {
      ShadowLight light;
      light.kind = ShadowLightKind::directional;
      light.direction = direction;
      const glm::vec3 sample{-k, 0, -k};
      Reproducer r{reproducer_case(light, sample + multiple * direction, sample, 0.01f, 1000), {}};
      r.c.meshes[0].caster = true;
      r.c.triangles = {{{-8, 0, -8}, {0, 0, 0}, {0, 0, -8}, 0},
                       {{-8, 0, -8}, {-8, 0, 0}, {0, 0, 0}, 0},
                       {{-64, 1, -64}, {0, 1, 64}, {64, 1, -64}, 1}};
      r.sample.position = sample;
      r.sample.normal = {0, 1, 0};
      for (std::uint32_t receiver : {0u, 1u}) {
        SCOPED_TRACE(testing::Message()
                     << "direction (" << direction.x << ", " << direction.y << ", " << direction.z
                     << "), sample at -" << k << ", receiver " << receiver);
        r.sample.receiver = receiver;
        expect_both_variants_exact(r, true);
      }
    }
}

// fuzz_watertight-f86d8fd9b34c69eb: a point light; the eye segment of a far sample passes
// through a caster of an open three-triangle fan. The fuzzer's receiver (triangle 0, no caster)
// has the sample far on its side away from the light, the fan too: under the receiver half-space
// rule the fan shadows nothing there, and the part of the segment the rule judges is long (the cap
// tree is asked for a large box). With a receiver plane that has the whole segment on the light's
// side (triangle 0 moved up, still no caster, so no volume changes) every caster counts: the
// original reproducer.
Reproducer open_fan_reproducer() {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {24, -24, 15};
  Reproducer r{
      reproducer_case(light, {15.653000831604004f, -11.27051830291748f, 7.933642864227295f},
                      {-5.702150344848633f, 21.296873092651367f, -10.145084381103516f},
                      6.947140354895964e-05f, 69471.3984375f),
      {}};
  r.c.triangles = {
      {{-1, -8, -1}, {1, -8, -1}, {0, -8, 1}, 0},
      {{7.5f, 3.125f, 0.5f}, {7.5f, 2.5625f, 2}, {7.21875f, 2.875f, 0.9833984375f}, 1},
      {{7.5f, 3.125f, 0.5f}, {8.466796875f, 2.5625f, 1.0625f}, {8.125f, 3.125f, 1.57421875f}, 1},
      {{7.5f, 3.125f, 0.5f}, {8.125f, 3.125f, 1.57421875f}, {7.5f, 2.5625f, 2}, 1}};
  r.sample.position = {-19.871097564697266f, 50.593746185302734f, -22.290168762207031f};
  r.sample.normal = {0, -1, 0};
  r.sample.receiver = 0;
  return r;
}

TEST(StencilFuzzReproducer, ZPassCountsALightCapOfAnOpenFan) {
  Reproducer r = open_fan_reproducer();
  expect_both_variants_exact(r, false);
  r.c.triangles[0] = {{-1, 64, -1}, {1, 64, -1}, {0, 64, 1}, 0};
  expect_both_variants_exact(r, true);
}

// fuzz_degenerate-66673e5b68a0975e: the same at a 2^40 scale.
TEST(StencilFuzzReproducer, ZPassCountsALightCapAtAHugeScale) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {-2147483648000.0f, 2869038153728.0f, 1297080123392.0f};
  Reproducer r{reproducer_case(light, {-1495385767936.0f, 1892195500032.0f, 903212957696.0f},
                               {0.0f, -347892350976.0f, 0.0f}, 3989957.5f, 3989957509120000.0f),
               {}};
  const float s = 1099511627776.0f;  // 2^40
  r.c.triangles = {{{-s, -s, -s}, {s, -s, -s}, {0, -s, s}, 0},
                   {{506806140928.0f, -893353197568.0f, 592705486848.0f},
                    {68719476736.0f, 901943132160.0f, -377957122048.0f},
                    {-816043786240.0f, 154618822656.0f, 42949672960.0f},
                    1}};
  r.sample.position = {481036337152.0f, -1597727834112.0f, -755914244096.0f};
  r.sample.normal = {0, 1, 0};
  r.sample.receiver = 0;
  expect_both_variants_exact(r, true);
}

// fuzz_degenerate-eb863e8a83fbe68d: the sample lies exactly in the plane of its receiver (a
// caster), which the eye sees from the side facing away from the light while the sample's normal
// faces the light. A receiver never shadows itself: both variants must leave the sample on the lit
// side of its own cap, not on the eye's side of it (which is inside the receiver's own volume).
TEST(StencilFuzzReproducer, TheReceiversOwnCapLeavesTheSampleLitWhenSeenFromBehind) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {-2147483648000.0f, 2869038153728.0f, 1297080123392.0f};
  const float s = 1099511627776.0f;  // 2^40
  Reproducer r{reproducer_case(light, {-s, -s, -s}, {-s, -s, -3558094405632.0f}, 0.001f, 1000.0f),
               {}};
  r.c.triangles = {{{-s, -s, -s}, {s, -s, -s}, {0, -s, s}, 0},
                   {{377957122048.0f, -644245094400.0f, -111669149696.0f},
                    {506806140928.0f, 111669149696.0f, -773094113280.0f},
                    {-618475290624.0f, -386547056640.0f, -335007449088.0f},
                    1}};
  r.sample.position = {122943438848.0f, -233001975808.0f, -470835789824.0f};
  r.sample.normal = {0, 1, 0};
  r.sample.receiver = 1;
  expect_both_variants_exact(r, false);
}

// fuzz_degenerate-26d850dcbe5b8485: the sample lies on a needle caster one ulp wide, its
// receiver, but its float position is a rounding below the needle's plane: inside the needle's
// own volume, beside a side quad. Forcing the sample onto the lit side of the receiver's cap alone
// counted the entry through the cap but not the exit through the side quad (a false shadow); the
// receiver's whole own volume is subtracted now.
TEST(StencilFuzzReproducer, TheReceiversOwnVolumeNeverShadowsASampleBesideItsSideQuad) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {-96256.0f, 821248.0f, -425984.0f};
  Reproducer r{reproducer_case(light, {-61843.47265625f, 505311.71875f, -273690.25f},
                               {0.0f, -62464.015625f, 0.0f}, 0.8421664237976074f, 842166400.0f),
               {}};
  const float s = 262144.0f;  // 2^18
  r.c.triangles = {{{-s, -s, -s}, {s, -s, -s}, {0, -s, s}, 0},
                   {{-0x1.14p+17f, 0x1.0cp+17f, -0x1p+18f},
                    {-0x1p+18f, -0x1p+18f, -0x1.34p+17f},
                    {-0x1.fffffep+17f, -0x1.000002p+18f, -0x1.33fffep+17f},
                    1}};
  r.sample.position = {-0x1.c5p+17f, -0x1.3d0002p+17f, -0x1.67p+17f};
  r.sample.normal = {0, 1, 0};
  r.sample.receiver = 1;
  expect_both_variants_exact(r, false);
}

// fuzz_watertight-bf947eecba672556: a T-junction (a vertex of one caster in the middle of
// another's edge) and a sample exactly on the shadow plane of the edge piece both triangles cover
// (from both sides: robust-shadowed). The two side quads through that plane are extruded through
// rounded vertices, and with a far sample stretching the extrusion their rounded triangles put the
// sample on different sides: both variants leaked. Side quads take sides of their exact plane.
// The receiver (no caster) lies above both samples, as the light does not: the fuzzer's receiver
// at y = -8 had the casters beyond its plane, where the receiver half-space rule ignores them.
TEST(StencilFuzzReproducer, SidesOfSideQuadsAreTakenOfTheirExactPlane) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {24.0f, -24.0f, -15.0f};
  Case c = reproducer_case(light, {10.23654556274414f, -10.883883476257324f, -5.7293500900268555f},
                           {-62.20115661621094f, 58.1468505859375f, 43.0625114440918f},
                           0.00020308911916799843f, 203089.109375f);
  c.camera.width = 2;
  c.triangles = {{{-1, 128, -1}, {1, 128, -1}, {0, 128, 1}, 0},
                 {{-0x1.3p-1f, 0x1.cp+2f, 0x1.c8p+1f},
                  {0x1p-1f, 0x1.fp+2f, 0x1.5p+1f},
                  {-0x1.4p-1f, 0x1.c4p+2f, 0x1.ap+0f},
                  1},
                 {{-0x1.32p-1f, 0x1.c08p+2f, 0x1.a9p+1f},  // on the edge above
                  {-0x1.4p-1f, 0x1.c4p+2f, 0x1.ap+0f},
                  {-0x1.8p+0f, 0x1.dp+2f, 0x1.5p+1f},
                  1}};
  ViewSamples samples;
  samples.width = 2;
  samples.height = 1;
  for (const auto& [position, normal] :
       {std::pair{glm::vec3(-0x1.9dap+3f, 0x1.692p+4f, 0x1.554p+3f), glm::vec3(0, -1, 0)},
        // Far away: it sets how far the volumes are extruded.
        std::pair{glm::vec3(-0x1.f1cp+6f, 0x1.57f8p+6f, 0x1.5398p+6f), glm::vec3(1, 0, 0)}}) {
    ViewSample sample;
    sample.position = position;
    sample.normal = normal;
    sample.receiver = 0;
    sample.pixel_x = std::uint32_t(samples.samples.size());
    sample.sample_class = SampleClass::regular;  // re-derived below
    samples.samples.push_back(sample);
  }
  validate(c);
  classify_samples(c, samples, c.name);
  ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  ASSERT_EQ(truth.band[0], BandClass::robust_shadowed);
  for (const char* variant : {"zfail", "zpass"})
    EXPECT_EQ(make_stencil()->run(c, samples, variant).shadowed[0], 1) << variant;
}

// stiff.shared_edges_narrow_view shrunk to one sample and a few casters (open meshes). The eye
// (0, 16, 0) and the point light (0, 16, -8) differ only in z, and the sample lies at x = 2 x_e
// under the slab's bottom edge along z at x = x_e, y = 8: the eye line lies exactly in the plane
// through that edge and the light, the plane of the edge's side quad. The sample is far from any
// shadow (the exact oracle: robust-lit), and both variants counted it inside a volume.
Reproducer narrow_view_reproducer(const glm::vec3& sample, const Triangle& other_caster) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {0, 16, -8};
  Reproducer r{reproducer_case(light, {0, 16, 0}, {0, 0, 0}, 0.5f, 64.0f), {}};
  r.c.camera.up = {0, 0, -1};
  r.c.camera.vertical_fov_degrees = 0x1.ca5b5ep-1f;  // the stiff case's 0.9 degrees
  r.c.triangles = {
      {{0x1p-6f, 0, -4}, {0x1p-6f, 0, 0}, {0x1.01p+2f, 0, 0}, 0},
      // A cell of the slab's bottom (facing down); its edge at x = 0x1.08p-5.
      {{0x1.08p-5f, 8, -0x1.78p-5f}, {0x1.18p-5f, 8, -0x1.68p-5f}, {0x1.08p-5f, 8, -0x1.68p-5f}, 1},
      other_caster};
  r.sample.position = sample;
  r.sample.normal = {0, 1, 0};
  r.sample.receiver = 0;
  return r;
}

// The eye and the sample both on the quad's plane: the tie rules put the eye past it and the
// sample before it, so z-fail counted the quad wherever the rounded extruded vertices let the
// line meet its triangles. The line, perturbed, runs parallel to the plane: no crossing. (The other
// caster is a fan triangle nearer to the light: it sets the extrusion, and so the rounding.)
TEST(StencilExactPlanes, AnEyeLineInASideQuadsPlaneDoesNotCrossIt) {
  expect_both_variants_exact(narrow_view_reproducer({0x1.08p-4f, 0, -0x1.57ffcp-4f},
                                                    {{-0x1.4p-8f, 0x1.000666p+3f, -0x1.019p+2f},
                                                     {-0x1.42b128p-8f, 8, -0x1.019cc8p+2f},
                                                     {-0x1.660eacp-8f, 8, -0x1.01989p+2f},
                                                     1}),
                             false);
}

// The eye line also meets, inside that plane, the exact line from the light through the slab's
// corner (the edge's end): the lateral edge of the side quads there, of the bottom's and of the
// south wall's edges. Their rounded extruded vertex lies on the other side of the eye line than
// the exact line does, and judged by it the line entered volumes it never left (z-pass) and
// crossed the quad in the plane (z-fail). Lateral edges are taken of their exact line.
TEST(StencilExactPlanes, LateralEdgesOfSideQuadsAreTheirExactLines) {
  expect_both_variants_exact(narrow_view_reproducer({0x1.08p-4f, 0, -0x1.77ffcp-4f},
                                                    {{0x1.08p-5f, 8, -0x1.78p-5f},
                                                     {0x1.08p-5f, 0x1.001p+3f, -0x1.78p-5f},
                                                     {0x1.c8p-5f, 0x1.001p+3f, -0x1.78p-5f},
                                                     1}),
                             false);
}

}  // namespace
}  // namespace shadowcts
