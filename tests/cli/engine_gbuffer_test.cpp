// Issue 24, item 2: G-buffers as engines write them. An exported shared_edges case is re-written
// the way engines dump their frames — depth with the inverse view-projection matrix, (mesh,
// primitive) ids, or no ids at all — and everything `check` says must agree with what the world
// positions and triangle ids of `export` give. Bad input exits 2 naming file, channel and pixel,
// with nothing written.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "runner/case_gbuffer.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::read_file;
using testing::run_tool;

constexpr std::uint32_t sky_id = 0xFFFFFFFFu;

// A small frame keeps the brute-force checks below quick.
const char* const shared_edges_source =
    R"({"scene": {"generator": "shared_edges", "triangles": 20000},
  "camera": {"width": 64, "height": 64}})";

struct Exported {
  fs::path dir, manifest;
  json manifest_json;
  Case c;
  ViewSamples samples;  // world positions and triangle ids, as `export` wrote them
  HardShadowTruth truth;
  double tau = 0.0;
};

Exported export_shared_edges(const std::string& name) {
  Exported e;
  e.dir = testing::fresh_dir("engine_gbuffer_" + name);
  std::ofstream(e.dir / "source.json") << shared_edges_source;
  EXPECT_EQ(run_tool("export --case source.json --out export", e.dir), 0)
      << read_file(e.dir / "stderr.txt");
  e.manifest = e.dir / "export" / "case.json";
  e.manifest_json = json::parse(read_file(e.manifest));
  GBufferFormat format;
  e.c = load_case_manifest(e.manifest.string(), format);
  e.samples = load_case_gbuffer(e.c, format).samples;
  e.truth = exact_hard_shadow_oracle(e.c, e.samples);
  e.tau = e.c.parameters.eps_rel * e.c.scale();
  return e;
}

// One EXR channel: FLOAT values or UINT ids, one per pixel, row 0 at the top.
struct Channel {
  std::string name;
  std::vector<float> floats;
  std::vector<std::uint32_t> uints;
};

void write_exr(const fs::path& path, std::uint32_t w, std::uint32_t h,
               const std::vector<Channel>& channels) {
  auto out = OIIO::ImageOutput::create("openexr");
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(int(w), int(h), int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  for (const Channel& c : channels) {
    spec.channelnames.push_back(c.name);
    spec.channelformats.push_back(c.uints.empty() ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT);
  }
  // Both kinds are 4 bytes: pixels interleaved as raw 32-bit words in the channels' own formats.
  std::vector<std::uint32_t> words(std::size_t(w) * h * channels.size());
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
    for (std::size_t k = 0; k < channels.size(); ++k)
      words[i * channels.size() + k] = channels[k].uints.empty()
                                           ? std::bit_cast<std::uint32_t>(channels[k].floats[i])
                                           : channels[k].uints[i];
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UNKNOWN, words.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

std::vector<Channel> normal_channels(const ViewSamples& s) {
  std::vector<Channel> n = {{"N.X", {}, {}}, {"N.Y", {}, {}}, {"N.Z", {}, {}}};
  for (const ViewSample& v : s.samples)
    for (int k = 0; k < 3; ++k) n[std::size_t(k)].floats.push_back(v.normal[k]);
  return n;
}

// The engine's projection, built in double from the case camera (what an engine sets up to
// render the exported case): view space x right, y up, z forward; NDC as the convention says.
struct Projection {
  bool reversed = false, minus_one_to_one = false;
  glm::dmat4 view_projection{1.0};
};

Projection projection(const Camera& cam, bool reversed, bool minus_one_to_one) {
  const CameraFrame f = camera_frame(cam);
  glm::dmat4 view(1.0);  // glm: [column][row]
  const glm::dvec3 axes[3] = {f.right, f.up, f.forward};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) view[k][r] = axes[r][k];
    view[3][r] = -glm::dot(axes[r], f.origin);
  }
  const double n = cam.near_plane, fa = cam.far_plane;
  double a, b;  // z_ndc = a + b / z_view
  if (minus_one_to_one) {
    a = (fa + n) / (fa - n), b = -2.0 * fa * n / (fa - n);
  } else if (reversed) {
    a = -n / (fa - n), b = fa * n / (fa - n);
  } else {
    a = fa / (fa - n), b = -fa * n / (fa - n);
  }
  glm::dmat4 proj(0.0);
  proj[0][0] = 1.0 / (f.tan_half_fov * f.aspect);
  proj[1][1] = 1.0 / f.tan_half_fov;
  proj[2][2] = a;
  proj[3][2] = b;
  proj[2][3] = 1.0;  // w = z_view
  return {reversed, minus_one_to_one, proj * view};
}

json rows(const glm::dmat4& m) {
  json r = json::array();
  for (int row = 0; row < 4; ++row) r.push_back({m[0][row], m[1][row], m[2][row], m[3][row]});
  return r;
}

// The depth-buffer value an engine stores for world point p (float32, as a D32 buffer holds it).
float stored_depth(const Projection& p, const glm::vec3& world) {
  const glm::dvec4 clip = p.view_projection * glm::dvec4(glm::dvec3(world), 1.0);
  const double z = clip.z / clip.w;
  return float(p.minus_one_to_one ? 0.5 * z + 0.5 : z);
}

// Case triangle index -> (mesh, index of the triangle within its mesh).
std::vector<std::pair<std::uint32_t, std::uint32_t>> mesh_primitives(const Case& c) {
  std::vector<std::uint32_t> next(c.meshes.size(), 0);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> of(c.triangles.size());
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    of[t] = {c.triangles[t].mesh, next[c.triangles[t].mesh]++};
  return of;
}

// Writes the exported frame as a depth + (mesh, primitive) G-buffer; `flip_rows` stores the
// rows bottom-up (OpenGL's glReadPixels order, row_0_ndc_y -1).
void write_depth_gbuffer(const Exported& e, const Projection& p, bool flip_rows,
                         const std::string& file, const std::string& manifest) {
  const std::uint32_t w = e.samples.width, h = e.samples.height;
  const auto ids = mesh_primitives(e.c);
  std::vector<Channel> channels = {{"Z", {}, {}}, {"mesh", {}, {}}, {"primitive", {}, {}}};
  std::vector<Channel> normals = normal_channels(e.samples);
  for (Channel& n : normals) n.floats.clear();
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const ViewSample& s = e.samples.samples[std::size_t(flip_rows ? h - 1 - y : y) * w + x];
      const bool sky = s.sample_class == SampleClass::sky;
      channels[0].floats.push_back(sky ? (p.reversed ? 0.0f : 1.0f) : stored_depth(p, s.position));
      channels[1].uints.push_back(sky ? sky_id : ids[s.receiver].first);
      channels[2].uints.push_back(sky ? 0u : ids[s.receiver].second);
      for (int k = 0; k < 3; ++k) normals[std::size_t(k)].floats.push_back(s.normal[k]);
    }
  channels.insert(channels.end(), normals.begin(), normals.end());
  write_exr(e.dir / "export" / file, w, h, channels);
  json m = e.manifest_json;
  m["gbuffer"] = {{"file", file},
                  {"positions", "depth"},
                  {"inverse_view_projection", rows(glm::inverse(p.view_projection))},
                  {"depth_range", p.minus_one_to_one ? "minus_one_to_one" : "zero_to_one"},
                  {"reversed_z", p.reversed},
                  {"row_0_ndc_y", flip_rows ? -1 : 1},
                  {"receivers", "mesh_primitive"}};
  std::ofstream(e.dir / "export" / manifest) << m.dump(2);
}

CaseGBuffer load(const fs::path& manifest, Case* loaded = nullptr) {
  GBufferFormat format;
  const Case c = load_case_manifest(manifest.string(), format);
  if (loaded) *loaded = c;
  return load_case_gbuffer(c, format);
}

void write_mask(const fs::path& path, std::uint32_t w, std::uint32_t h,
                const std::vector<float>& values) {
  write_exr(path, w, h, {{"Y", values, {}}});
}

void add_result(const fs::path& manifest, const std::string& mask) {
  json m = json::parse(read_file(manifest));
  m["result"] = {{"mask", mask}};
  std::ofstream(manifest) << m.dump(2);
}

json results(const fs::path& out) {
  return json::parse(read_file(out / "results.json"));
}

// A perfect engine's answers (the oracle's at the exported positions), with planted leaks: every
// shadowed sample of the rows 20 to 29 answered lit.
std::vector<float> planted_mask(const Exported& e) {
  std::vector<float> mask(e.truth.shadowed.begin(), e.truth.shadowed.end());
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (i / e.samples.width >= 20 && i / e.samples.width < 30) mask[i] = 0.0f;
  return mask;
}

// Robust leaks of `mask` against `truth` (lit where a robust sample is shadowed).
std::uint64_t robust_leaks(const std::vector<float>& mask, const HardShadowTruth& truth) {
  std::uint64_t leaks = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    leaks += truth.band[i] == BandClass::robust_shadowed && !(mask[i] > 0.5f);
  return leaks;
}

TEST(EngineGBuffer, DepthAndMeshPrimitiveIdsGiveTheWorldPositionsAnswers) {
  const Exported e = export_shared_edges("depth");
  const std::uint32_t w = e.samples.width, h = e.samples.height;
  struct Convention {
    const char* name;
    bool reversed, minus_one_to_one, flip_rows;
  };
  // D3D/Vulkan/Metal with reversed Z; OpenGL's default depth range, rows as glReadPixels gives.
  for (const Convention& k :
       {Convention{"reversed_z", true, false, false}, Convention{"opengl", false, true, true}}) {
    SCOPED_TRACE(k.name);
    const std::string file = std::string("depth_") + k.name + ".exr";
    const std::string manifest = std::string("case_") + k.name + ".json";
    write_depth_gbuffer(e, projection(e.c.camera, k.reversed, k.minus_one_to_one), k.flip_rows,
                        file, manifest);
    const CaseGBuffer depth = load(e.dir / "export" / manifest);
    ASSERT_EQ(depth.samples.samples.size(), e.samples.samples.size());
    EXPECT_TRUE(depth.receiver_ambiguous.empty());
    // Same pixel, same class and receiver; the position within the band of the exported one.
    double largest_error = 0.0;
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const ViewSample& d = depth.samples.samples[std::size_t(y) * w + x];
        const ViewSample& s = e.samples.samples[std::size_t(k.flip_rows ? h - 1 - y : y) * w + x];
        ASSERT_EQ(d.sample_class, s.sample_class) << "pixel " << x << "," << y;
        if (s.sample_class == SampleClass::sky) continue;
        ASSERT_EQ(d.receiver, s.receiver) << "pixel " << x << "," << y;
        for (int a = 0; a < 3; ++a)
          largest_error =
              std::max(largest_error, std::fabs(double(d.position[a]) - double(s.position[a])));
      }
    RecordProperty(std::string("largest_position_error_") + k.name, std::to_string(largest_error));
    EXPECT_LE(largest_error, e.tau) << "tau " << e.tau;

    // Every sample robust at the reconstructed position has the exported position inside its
    // band cube (error <= tau), so its exact answer is the exported sample's.
    const HardShadowTruth truth = exact_hard_shadow_oracle(e.c, depth.samples);
    std::uint64_t robust = 0;
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const std::size_t i = std::size_t(y) * w + x;
        const std::size_t j = std::size_t(k.flip_rows ? h - 1 - y : y) * w + x;
        if (truth.band[i] != BandClass::robust_lit && truth.band[i] != BandClass::robust_shadowed)
          continue;
        ++robust;
        EXPECT_EQ(truth.shadowed[i], e.truth.shadowed[j]) << "pixel " << x << "," << y;
      }
    EXPECT_GT(robust, w * h / 2);

    // `check` on both G-buffers: a perfect engine passes on both; planted leaks fail on both,
    // with the leaks the oracle finds at each G-buffer's own positions.
    std::vector<float> perfect(e.truth.shadowed.begin(), e.truth.shadowed.end());
    std::vector<float> planted = planted_mask(e);
    for (const bool leaking : {false, true}) {
      SCOPED_TRACE(leaking ? "planted leaks" : "perfect");
      const std::vector<float>& mask = leaking ? planted : perfect;
      std::vector<float> file_order(mask.size());
      for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
          file_order[std::size_t(y) * w + x] =
              mask[std::size_t(k.flip_rows ? h - 1 - y : y) * w + x];
      write_mask(e.dir / "export" / "mask_world.exr", w, h, mask);
      write_mask(e.dir / "export" / "mask_depth.exr", w, h, file_order);
      fs::copy_file(e.dir / "export" / "case.json", e.dir / "export" / "check_world.json",
                    fs::copy_options::overwrite_existing);
      fs::copy_file(e.dir / "export" / manifest, e.dir / "export" / "check_depth.json",
                    fs::copy_options::overwrite_existing);
      add_result(e.dir / "export" / "check_world.json", "mask_world.exr");
      add_result(e.dir / "export" / "check_depth.json", "mask_depth.exr");
      const int world_rc = run_tool("check --case export/check_world.json --out out_world", e.dir);
      const int depth_rc = run_tool("check --case export/check_depth.json --out out_depth", e.dir);
      EXPECT_EQ(world_rc, leaking ? 1 : 0) << read_file(e.dir / "stderr.txt");
      EXPECT_EQ(depth_rc, world_rc) << read_file(e.dir / "stderr.txt");
      const json world = results(e.dir / "out_world"), depth_json = results(e.dir / "out_depth");
      const json& a = world["results"][0];
      const json& b = depth_json["results"][0];
      EXPECT_EQ(a["verdict"], b["verdict"]);
      EXPECT_EQ(a["verdict"], leaking ? "Fail" : "Pass");
      for (const char* count : {"regular", "sky", "back_facing"})
        EXPECT_EQ(world["cases"][0]["samples"][count], depth_json["cases"][0]["samples"][count])
            << count;
      EXPECT_EQ(a["error"]["leaks"], robust_leaks(mask, e.truth));
      EXPECT_EQ(b["error"]["leaks"], robust_leaks(file_order, truth));
      EXPECT_EQ(b["error"]["false_shadows"], 0);
      if (leaking) {
        EXPECT_GT(b["error"]["leaks"].get<std::uint64_t>(), 0u);
      }
    }
  }
}

// Distance from p to the closed triangle (a, b, c), in double (Ericson, Real-Time Collision
// Detection, 5.1.5): the test's own measure, independent of the suite's exact search.
double point_triangle_distance(const glm::dvec3& p, const Triangle& t) {
  const glm::dvec3 a(t.v0), b(t.v1), c(t.v2);
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + d1 / (d1 - d3) * ab));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + d2 / (d2 - d6) * ac));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return glm::length(p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)));
  const double denom = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

double area2(const Triangle& t) {
  return glm::length(
      glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0)));
}

// World positions without ids: every 4th sample is moved onto the midpoint of an edge its
// receiver shares with another triangle. Moved samples must come out ambiguous; a sample within
// tau (Euclidean, so inside the band cube) of two triangles too; a sample with only its own
// receiver within sqrt(3) tau (the cube's corner) must find exactly that receiver.
TEST(EngineGBuffer, WithoutIdsTheReceiverIsFoundAndSharedEdgesAreAmbiguous) {
  const Exported e = export_shared_edges("search");
  const std::uint32_t w = e.samples.width, h = e.samples.height;
  using Key = std::array<std::uint32_t, 3>;
  auto key = [](const glm::vec3& v) { return std::bit_cast<Key>(v); };
  std::map<std::pair<Key, Key>, std::vector<std::uint32_t>> edges;
  for (std::uint32_t t = 0; t < e.c.triangles.size(); ++t) {
    const Triangle& tri = e.c.triangles[t];
    if (area2(tri) == 0.0) continue;
    const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
    for (int k = 0; k < 3; ++k) edges[std::minmax(key(v[k]), key(v[(k + 1) % 3]))].push_back(t);
  }
  ViewSamples moved = e.samples;
  std::vector<std::uint8_t> on_edge(moved.samples.size(), 0);
  std::size_t regular = 0, moved_count = 0;
  for (std::size_t i = 0; i < moved.samples.size(); ++i) {
    ViewSample& s = moved.samples[i];
    if (s.sample_class == SampleClass::sky || regular++ % 4) continue;
    const Triangle& r = e.c.triangles[s.receiver];
    const glm::vec3 v[3] = {r.v0, r.v1, r.v2};
    for (int k = 0; k < 3; ++k) {
      if (edges[std::minmax(key(v[k]), key(v[(k + 1) % 3]))].size() < 2) continue;
      s.position = glm::vec3(0.5 * (glm::dvec3(v[k]) + glm::dvec3(v[(k + 1) % 3])));
      on_edge[i] = 1;
      ++moved_count;
      break;
    }
  }
  ASSERT_GT(moved_count, 100u);

  for (const bool move : {false, true}) {
    SCOPED_TRACE(move ? "moved onto shared edges" : "as exported");
    const ViewSamples& source = move ? moved : e.samples;
    std::vector<Channel> channels = {{"P.X", {}, {}}, {"P.Y", {}, {}}, {"P.Z", {}, {}}};
    for (const ViewSample& s : source.samples)
      for (int k = 0; k < 3; ++k)
        channels[std::size_t(k)].floats.push_back(s.sample_class == SampleClass::sky
                                                      ? std::numeric_limits<float>::infinity()
                                                      : s.position[k]);
    const std::vector<Channel> normals = normal_channels(source);
    channels.insert(channels.end(), normals.begin(), normals.end());
    const std::string file = move ? "no_ids_moved.exr" : "no_ids.exr";
    write_exr(e.dir / "export" / file, w, h, channels);
    json m = e.manifest_json;
    m["gbuffer"] = {{"file", file}, {"receivers", "search"}};
    const fs::path manifest = e.dir / "export" / (move ? "search_moved.json" : "search.json");
    std::ofstream(manifest) << m.dump(2);

    const CaseGBuffer found = load(manifest);
    ASSERT_TRUE(found.receivers_searched);
    EXPECT_EQ(found.tau, e.tau);
    std::uint64_t ambiguous = 0;
    for (std::size_t i = 0; i < source.samples.size(); ++i) {
      const ViewSample& s = source.samples[i];
      const ViewSample& f = found.samples.samples[i];
      ASSERT_EQ(f.sample_class == SampleClass::sky, s.sample_class == SampleClass::sky);
      if (s.sample_class == SampleClass::sky) continue;
      EXPECT_EQ(f.position, s.position);
      ambiguous += found.receiver_ambiguous[i];
      std::size_t surely_within = 0, maybe_within = 0;
      std::uint32_t nearest = 0;
      for (std::uint32_t t = 0; t < e.c.triangles.size(); ++t) {
        const Triangle& tri = e.c.triangles[t];
        bool far = false;  // a cheap reject: the triangle's box is farther than 2 tau
        for (int k = 0; k < 3; ++k)
          far = far || std::min({tri.v0[k], tri.v1[k], tri.v2[k]}) - s.position[k] > 2 * e.tau ||
                s.position[k] - std::max({tri.v0[k], tri.v1[k], tri.v2[k]}) > 2 * e.tau;
        if (far || area2(tri) == 0.0) continue;
        const double d = point_triangle_distance(glm::dvec3(s.position), e.c.triangles[t]);
        if (d <= 0.999 * e.tau) ++surely_within;
        if (d <= 1.001 * std::sqrt(3.0) * e.tau) {
          ++maybe_within;
          nearest = t;
        }
      }
      const std::string where =
          "pixel " + std::to_string(s.pixel_x) + "," + std::to_string(s.pixel_y);
      if (on_edge[i] && move) {
        EXPECT_TRUE(found.receiver_ambiguous[i]) << where;
      }
      if (surely_within >= 2) {
        EXPECT_TRUE(found.receiver_ambiguous[i]) << where;
      }
      if (maybe_within == 1) {
        EXPECT_FALSE(found.receiver_ambiguous[i]) << where;
        EXPECT_EQ(f.receiver, nearest) << where;
        EXPECT_EQ(f.receiver, s.receiver) << where;  // the triangle the exported ray hit
      }
      EXPECT_GE(maybe_within, 1u) << where;
    }
    EXPECT_EQ(ambiguous, found.ambiguous_receivers);
    if (move) {
      EXPECT_GE(found.ambiguous_receivers, moved_count);
    }

    // `check` with the oracle's own answers at these positions: Pass; the plan and results.json
    // give the receiver counts, and the oracle's ambiguous samples include every receiver-
    // ambiguous one it compares.
    const HardShadowTruth truth = exact_hard_shadow_oracle(e.c, found.samples);
    std::uint64_t expected_ambiguous = 0;
    for (std::size_t i = 0; i < truth.band.size(); ++i)
      expected_ambiguous +=
          truth.band[i] == BandClass::ambiguous ||
          (truth.band[i] != BandClass::not_compared && found.receiver_ambiguous[i]);
    write_mask(e.dir / "export" / "mask.exr", w, h,
               std::vector<float>(truth.shadowed.begin(), truth.shadowed.end()));
    add_result(manifest, "mask.exr");
    const std::string out = move ? "out_moved" : "out";
    const std::string command =
        "check --case export/" + manifest.filename().string() + " --out " + out;
    EXPECT_EQ(run_tool(command, e.dir), 0) << read_file(e.dir / "stderr.txt");
    const std::string plan = read_file(e.dir / "stdout.txt");
    EXPECT_NE(plan.find("receivers: found by the suite (the G-buffer has no ids): " +
                        std::to_string(found.unique_receivers) + " samples on one triangle, " +
                        std::to_string(found.ambiguous_receivers) + " ambiguous"),
              std::string::npos)
        << plan;
    const json r = results(e.dir / out);
    EXPECT_EQ(r["results"][0]["verdict"], "Pass");
    EXPECT_EQ(r["cases"][0]["samples"]["receivers"]["ambiguous"], found.ambiguous_receivers);
    EXPECT_EQ(r["cases"][0]["oracles"]["hard"]["ambiguous"], expected_ambiguous);
    if (!move) {
      // The same samples with the exported ids: the search's judgement is the ids' with exactly
      // the receiver-ambiguous samples moved to ambiguous (at 64x64 a few exported samples do
      // lie within tau of a shared edge).
      add_result(e.manifest, "mask.exr");
      EXPECT_EQ(run_tool("check --case export/case.json --out out_ids", e.dir), 0);
      const json ids = results(e.dir / "out_ids");
      std::map<BandClass, std::uint64_t> with_ids, searched;
      for (std::size_t i = 0; i < e.truth.band.size(); ++i) {
        ++with_ids[e.truth.band[i]];
        ++searched[found.receiver_ambiguous[i] && e.truth.band[i] != BandClass::not_compared
                       ? BandClass::ambiguous
                       : e.truth.band[i]];
      }
      for (const auto& [name, band] : {std::pair{"robust_lit", BandClass::robust_lit},
                                       std::pair{"robust_shadowed", BandClass::robust_shadowed},
                                       std::pair{"ambiguous", BandClass::ambiguous}}) {
        EXPECT_EQ(ids["cases"][0]["oracles"]["hard"][name], with_ids[band]) << name;
        EXPECT_EQ(r["cases"][0]["oracles"]["hard"][name], searched[band]) << name;
      }
      EXPECT_EQ(ids["cases"][0]["samples"]["regular"], r["cases"][0]["samples"]["regular"]);
    }
  }
}

// Each class of bad input: exit 2, the message names the file, the channel and the pixel, and
// no output folder (not even a partial one) is left.
TEST(EngineGBuffer, BadInputExitsTwoNamingFileChannelAndPixel) {
  const Exported e = export_shared_edges("bad");
  const std::uint32_t w = e.samples.width, h = e.samples.height;
  const Projection reversed_z = projection(e.c.camera, true, false);
  write_depth_gbuffer(e, reversed_z, false, "good.exr", "good.json");
  write_mask(e.dir / "export" / "mask.exr", w, h, std::vector<float>(std::size_t(w) * h, 0.0f));
  // The first pixel that is not sky, and the good file's channels to corrupt.
  std::size_t first = 0;
  while (e.samples.samples[first].sample_class == SampleClass::sky) ++first;
  const std::string pixel =
      "pixel (" + std::to_string(first % w) + ", " + std::to_string(first / w) + ")";
  auto channels_of_good = [&] {
    auto in = OIIO::ImageInput::open((e.dir / "export" / "good.exr").string());
    std::vector<Channel> channels;
    for (int c = 0; c < in->spec().nchannels; ++c) {
      Channel ch{in->spec().channelnames[std::size_t(c)], {}, {}};
      if (in->spec().channelformat(c) == OIIO::TypeDesc::UINT) {
        ch.uints.resize(std::size_t(w) * h);
        EXPECT_TRUE(in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::UINT, ch.uints.data()));
      } else {
        ch.floats.resize(std::size_t(w) * h);
        EXPECT_TRUE(in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, ch.floats.data()));
      }
      channels.push_back(std::move(ch));
    }
    return channels;
  };
  auto find = [](std::vector<Channel>& channels, const std::string& name) -> Channel& {
    for (Channel& c : channels)
      if (c.name == name) return c;
    throw std::logic_error("no channel " + name);
  };
  const json good = json::parse(read_file(e.dir / "export" / "good.json"));

  struct Bad {
    std::string name;
    std::vector<std::string> expected;  // substrings of the message
  };
  auto expect_refused = [&](const Bad& bad, const json& manifest) {
    SCOPED_TRACE(bad.name);
    json m = manifest;
    m["result"] = {{"mask", "mask.exr"}};
    std::ofstream(e.dir / "export" / "bad.json") << m.dump(2);
    fs::remove_all(e.dir / "out");
    EXPECT_EQ(run_tool("check --case export/bad.json --out out", e.dir), 2)
        << read_file(e.dir / "stdout.txt");
    const std::string message = read_file(e.dir / "stderr.txt");
    for (const std::string& part : bad.expected)
      EXPECT_NE(message.find(part), std::string::npos)
          << "expected '" << part << "' in " << message;
    EXPECT_FALSE(fs::exists(e.dir / "out"));
    for (const auto& entry : fs::directory_iterator(e.dir))
      EXPECT_EQ(entry.path().filename().string().find("out.partial"), std::string::npos);
  };
  auto with_file = [&](const std::vector<Channel>& channels, std::uint32_t width,
                       std::uint32_t height) {
    write_exr(e.dir / "export" / "bad.exr", width, height, channels);
    json m = good;
    m["gbuffer"]["file"] = "bad.exr";
    return m;
  };

  {  // the good file passes: the failures below are the corruptions'
    json m = good;
    m["result"] = {{"mask", "mask.exr"}};
    std::ofstream(e.dir / "export" / "bad.json") << m.dump(2);
    EXPECT_NE(run_tool("check --case export/bad.json --out out_good", e.dir), 2)
        << read_file(e.dir / "stderr.txt");
  }
  {
    std::vector<Channel> c = channels_of_good();
    c.erase(c.begin());  // Z
    expect_refused({"missing channel", {"bad.exr", "channel Z", "is missing"}}, with_file(c, w, h));
  }
  {
    std::vector<Channel> c = channels_of_good();
    for (Channel& ch : c) {
      ch.floats.resize(ch.floats.empty() ? 0 : std::size_t(w) * (h / 2));
      ch.uints.resize(ch.uints.empty() ? 0 : std::size_t(w) * (h / 2));
    }
    expect_refused({"size", {"bad.exr", "dataWindow", "differs from the case camera's"}},
                   with_file(c, w, h / 2));
  }
  {
    std::vector<Channel> c = channels_of_good();
    find(c, "Z").floats[first] = std::numeric_limits<float>::quiet_NaN();
    expect_refused({"NaN depth", {"bad.exr", "channel Z, " + pixel, "is NaN"}}, with_file(c, w, h));
  }
  {
    std::vector<Channel> c = channels_of_good();
    find(c, "Z").floats[first] = 1.5f;
    expect_refused({"depth out of range", {"bad.exr", "channel Z, " + pixel, "outside [0, 1]"}},
                   with_file(c, w, h));
  }
  {
    std::vector<Channel> c = channels_of_good();
    find(c, "mesh").uints[first] = 99;
    expect_refused({"mesh out of range", {"bad.exr", "channel mesh, " + pixel, "mesh 99"}},
                   with_file(c, w, h));
  }
  {
    std::vector<Channel> c = channels_of_good();
    find(c, "primitive").uints[first] = 1000000;
    expect_refused(
        {"primitive out of range", {"bad.exr", "channel primitive, " + pixel, "primitive 1000000"}},
        with_file(c, w, h));
  }
  {
    std::vector<Channel> c = channels_of_good();
    find(c, "N.Y").floats[first] = std::numeric_limits<float>::quiet_NaN();
    expect_refused({"NaN normal", {"bad.exr", "channels N.X N.Y N.Z, " + pixel, "is not finite"}},
                   with_file(c, w, h));
  }
  {  // triangle ids: the exported world G-buffer with an id beyond the case's triangles
    std::vector<Channel> c = {{"P.X", {}, {}}, {"P.Y", {}, {}}, {"P.Z", {}, {}}};
    std::vector<Channel> rest = normal_channels(e.samples);
    Channel id{"id", {}, {}};
    for (const ViewSample& s : e.samples.samples) {
      // Sky as an engine without ids marks it (the ids mark it too).
      for (int k = 0; k < 3; ++k)
        c[std::size_t(k)].floats.push_back(s.sample_class == SampleClass::sky
                                               ? std::numeric_limits<float>::infinity()
                                               : s.position[k]);
      id.uints.push_back(s.sample_class == SampleClass::sky ? sky_id : s.receiver);
    }
    id.uints[first] = std::uint32_t(e.c.triangles.size());
    c.insert(c.end(), rest.begin(), rest.end());
    c.push_back(id);
    write_exr(e.dir / "export" / "bad.exr", w, h, c);
    json m = e.manifest_json;
    m["gbuffer"] = "bad.exr";
    expect_refused(
        {"triangle id out of range", {"bad.exr", "channel id, " + pixel, "out of range"}}, m);
    // No ids, and a sample far from every triangle: nothing to be its receiver.
    // Moved 5 % of the way back towards the eye: the camera ray there meets no triangle.
    c.pop_back();
    const glm::dvec3 p(e.samples.samples[first].position), eye(e.c.camera.position);
    const glm::vec3 off(p + 0.05 * (eye - p));
    for (int k = 0; k < 3; ++k) c[std::size_t(k)].floats[first] = off[k];
    write_exr(e.dir / "export" / "bad.exr", w, h, c);
    m["gbuffer"] = {{"file", "bad.exr"}, {"receivers", "search"}};
    expect_refused({"no receiver", {"bad.exr", "channels P.X P.Y P.Z, " + pixel, "no triangle"}},
                   m);
  }
  {
    json m = good;
    m["gbuffer"].erase("inverse_view_projection");
    expect_refused({"no matrix", {"bad.json", "gbuffer.inverse_view_projection", "is required"}},
                   m);
    m = good;
    m["gbuffer"]["inverse_view_projection"][3] = {0, 0, 0};
    expect_refused({"matrix row", {"bad.json", "gbuffer.inverse_view_projection[3]"}}, m);
    m = good;
    m["gbuffer"]["row_0_ndc_y"] = 0;
    expect_refused({"row direction", {"bad.json", "gbuffer.row_0_ndc_y", "must be 1 or -1"}}, m);
    m = good;
    m["gbuffer"]["positions"] = "world";
    expect_refused({"depth keys with world positions",
                    {"bad.json", "gbuffer.inverse_view_projection", "belongs to"}},
                   m);
  }
  {  // the mask: values out of range
    std::vector<float> mask(std::size_t(w) * h, 0.0f);
    mask[first] = 2.0f;
    write_mask(e.dir / "export" / "mask_bad.exr", w, h, mask);
    json m = good;
    m["result"] = {{"mask", "mask_bad.exr"}};
    std::ofstream(e.dir / "export" / "bad2.json") << m.dump(2);
    fs::remove_all(e.dir / "out");
    EXPECT_EQ(run_tool("check --case export/bad2.json --out out", e.dir), 2);
    const std::string message = read_file(e.dir / "stderr.txt");
    EXPECT_NE(message.find("mask_bad.exr: channel Y, " + pixel), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(e.dir / "out"));
  }
}

}  // namespace
}  // namespace shadowcts
