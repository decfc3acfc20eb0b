#include "shadowcts/prepared_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shadowcts/geometry/triangle_area.h"

namespace shadowcts {

PreparedScene prepare_scene(const Case& c, const ViewSamples& view_samples) {
  PreparedScene scene{c, view_samples, {}, {}, c.light, c.scale(), 0.0};
  scene.tau = c.parameters.eps_rel * scene.scale;

  CasterArrays& casters = scene.casters;
  const std::size_t n = c.triangles.size();
  for (int k = 0; k < 3; ++k) {
    casters.x[k].resize(n);
    casters.y[k].resize(n);
    casters.z[k].resize(n);
  }
  casters.mesh.resize(n);
  casters.casts.resize(n);
  for (const Mesh& m : c.meshes) {
    casters.mesh_closed.push_back(m.closed ? 1 : 0);
    casters.mesh_casts.push_back(m.caster ? 1 : 0);
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      const Triangle& tri = c.triangles[t];
      const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
      for (int k = 0; k < 3; ++k) {
        casters.x[k][t] = v[k].x;
        casters.y[k][t] = v[k].y;
        casters.z[k][t] = v[k].z;
      }
      casters.mesh[t] = tri.mesh;
      casters.casts[t] =
          casters.mesh_casts[tri.mesh] != 0 && !triangle_has_zero_area(v[0], v[1], v[2]) ? 1 : 0;
    }
  });

  RegularSamples& regular = scene.samples;
  const std::vector<ViewSample>& all = view_samples.samples;
  for (std::uint32_t i = 0; i < all.size(); ++i)
    if (all[i].sample_class == SampleClass::regular) regular.index.push_back(i);
  const std::size_t m = regular.index.size();
  for (std::vector<float>* a :
       {&regular.px, &regular.py, &regular.pz, &regular.nx, &regular.ny, &regular.nz})
    a->resize(m);
  regular.receiver.resize(m);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const ViewSample& s = all[regular.index[i]];
      regular.px[i] = s.position.x;
      regular.py[i] = s.position.y;
      regular.pz[i] = s.position.z;
      regular.nx[i] = s.normal.x;
      regular.ny[i] = s.normal.y;
      regular.nz[i] = s.normal.z;
      regular.receiver[i] = s.receiver;
    }
  });
  return scene;
}

}  // namespace shadowcts
