// The one translation unit of the reference `metric` that includes CGAL (smallest enclosing
// spheres and circles); everything else stays CGAL-free to keep compile times down.
#include "reference/metric/bounding_volumes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_2.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_3.h>
#include <CGAL/Simple_cartesian.h>
#include <glm/geometric.hpp>

namespace shadowcts::metric {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SphereTraits = CGAL::Min_sphere_of_spheres_d_traits_3<Kernel, double, CGAL::Tag_true>;
using CircleTraits = CGAL::Min_sphere_of_spheres_d_traits_2<Kernel, double, CGAL::Tag_true>;

// Relative enlargement covering the rounding of the double containment checks below: each
// computed distance or dot product is within a few units of 2^-53 of the bound R of the
// coordinates involved, far below R * 2^-40.
constexpr double rounding_margin = 0x1p-40;

struct EigenBasis {
  std::array<glm::dvec3, 3> axes;  // orthonormal, the covariance's eigenvectors
};

// Cyclic Jacobi rotations on the symmetric 3x3 covariance: converges for every symmetric matrix
// and keeps the accumulated rotation orthonormal to rounding.
EigenBasis eigenvectors(std::array<std::array<double, 3>, 3> a) {
  std::array<std::array<double, 3>, 3> v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diagonal || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
            (theta >= 0.0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double cosine = 1.0 / std::sqrt(t * t + 1.0), sine = t * cosine;
        for (int k = 0; k < 3; ++k) {  // a = J^T a J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = cosine * akp - sine * akq;
          a[k][q] = sine * akp + cosine * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = cosine * apk - sine * aqk;
          a[q][k] = sine * apk + cosine * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = cosine * vkp - sine * vkq;
          v[k][q] = sine * vkp + cosine * vkq;
        }
      }
  }
  EigenBasis basis;
  for (int j = 0; j < 3; ++j) basis.axes[j] = glm::normalize(glm::dvec3(v[0][j], v[1][j], v[2][j]));
  return basis;
}

// Mean and covariance of the triangle vertices, as in the paper (section 4).
EigenBasis covariance_axes(const std::vector<glm::dvec3>& vertices) {
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& v : vertices) mean += v;
  mean /= double(vertices.size());
  std::array<std::array<double, 3>, 3> covariance{};
  for (const glm::dvec3& v : vertices) {
    const glm::dvec3 d = v - mean;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) covariance[j][k] += d[j] * d[k];
  }
  for (auto& row : covariance)
    for (double& x : row) x /= double(vertices.size());
  return eigenvectors(covariance);
}

double distance_to_segment(const glm::dvec3& v, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length_squared = glm::dot(ab, ab);
  const double t =
      length_squared > 0.0 ? std::clamp(glm::dot(v - a, ab) / length_squared, 0.0, 1.0) : 0.0;
  // Any t in [0, 1] gives an upper bound of the distance, so the rounding of t costs nothing.
  return glm::length(v - (a + t * ab));
}

double largest_coordinate(const std::vector<glm::dvec3>& points) {
  double bound = 0.0;
  for (const glm::dvec3& p : points)
    bound = std::max({bound, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return bound;
}

}  // namespace

ClusterVolume bound_cluster(const Case& c, std::span<const std::uint32_t> triangles,
                            bool allow_capsules, const glm::dvec3& slab_axis) {
  if (triangles.empty()) throw std::invalid_argument("metric: bounding an empty cluster");
  std::vector<glm::dvec3> vertices;
  vertices.reserve(3 * triangles.size());
  for (std::uint32_t i : triangles) {
    const Triangle& t = c.triangles[i];
    vertices.insert(vertices.end(), {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)});
  }

  const EigenBasis basis = covariance_axes(vertices);
  std::array<double, 3> lo{}, hi{}, extent{};
  for (int j = 0; j < 3; ++j) {
    lo[j] = hi[j] = glm::dot(vertices[0], basis.axes[j]);
    for (const glm::dvec3& v : vertices) {
      const double s = glm::dot(v, basis.axes[j]);
      lo[j] = std::min(lo[j], s);
      hi[j] = std::max(hi[j], s);
    }
    extent[j] = hi[j] - lo[j];
  }
  const int main_axis = int(std::max_element(extent.begin(), extent.end()) - extent.begin());
  const int side_1 = (main_axis + 1) % 3, side_2 = (main_axis + 2) % 3;
  const bool elongated = extent[main_axis] > 0.0 && extent[main_axis] >= 2.0 * extent[side_1] &&
                         extent[main_axis] >= 2.0 * extent[side_2];

  ClusterVolume volume;
  double radius = 0.0;
  if (allow_capsules && elongated) {
    volume.shape = VolumeShape::capsule;
    const glm::dvec3 e0 = basis.axes[main_axis], e1 = basis.axes[side_1], e2 = basis.axes[side_2];
    std::vector<CircleTraits::Sphere> projected;
    projected.reserve(vertices.size());
    for (const glm::dvec3& v : vertices)
      projected.emplace_back(Kernel::Point_2(glm::dot(v, e1), glm::dot(v, e2)), 0.0);
    CGAL::Min_sphere_of_spheres_d<CircleTraits> circle(projected.begin(), projected.end());
    auto centre = circle.center_cartesian_begin();
    const double c1 = *centre, c2 = *++centre;
    const glm::dvec3 on_axis = c1 * e1 + c2 * e2;
    volume.axis_begin = on_axis + lo[main_axis] * e0;
    volume.axis_end = on_axis + hi[main_axis] * e0;
    radius = circle.radius();
    for (const glm::dvec3& v : vertices)
      radius = std::max(radius, distance_to_segment(v, volume.axis_begin, volume.axis_end));
  } else {
    std::vector<SphereTraits::Sphere> points;
    points.reserve(vertices.size());
    for (const glm::dvec3& v : vertices) points.emplace_back(Kernel::Point_3(v.x, v.y, v.z), 0.0);
    CGAL::Min_sphere_of_spheres_d<SphereTraits> sphere(points.begin(), points.end());
    auto centre = sphere.center_cartesian_begin();
    glm::dvec3 point;
    point.x = *centre;
    point.y = *++centre;
    point.z = *++centre;
    volume.axis_begin = volume.axis_end = point;
    radius = sphere.radius();
    for (const glm::dvec3& v : vertices) radius = std::max(radius, glm::length(v - point));
  }
  std::vector<glm::dvec3> involved = vertices;
  involved.push_back(volume.axis_begin);
  involved.push_back(volume.axis_end);
  const double bound = largest_coordinate(involved);
  volume.radius = radius * (1.0 + rounding_margin) + bound * rounding_margin;

  volume.slab_normal = slab_axis;
  volume.slab_min = volume.slab_max = glm::dot(slab_axis, vertices[0]);
  for (const glm::dvec3& v : vertices) {
    const double s = glm::dot(slab_axis, v);
    volume.slab_min = std::min(volume.slab_min, s);
    volume.slab_max = std::max(volume.slab_max, s);
  }
  volume.slab_min -= bound * rounding_margin;
  volume.slab_max += bound * rounding_margin;
  return volume;
}

}  // namespace shadowcts::metric
