#include "oracles/soft_shadow/exact_disk_union.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <list>
#include <numbers>

#include <CGAL/Cartesian.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/General_polygon_set_2.h>
#include <CGAL/Gps_circle_segment_traits_2.h>
#include <CGAL/convex_hull_2.h>

namespace shadowcts {
namespace {

using Kernel = CGAL::Cartesian<CGAL::Exact_rational>;
using Point = Kernel::Point_2;
using Traits = CGAL::Gps_circle_segment_traits_2<Kernel>;
using PolygonSet = CGAL::General_polygon_set_2<Traits>;
using Polygon = Traits::General_polygon_2;
using PolygonWithHoles = Traits::General_polygon_with_holes_2;
using Curve = Traits::Curve_2;
using XCurve = Traits::X_monotone_curve_2;

// The unit disk as a general polygon: the circle split into its two x-monotone arcs.
Polygon unit_disk() {
  const Traits traits;
  std::list<boost::variant<Traits::Point_2, XCurve>> pieces;
  traits.make_x_monotone_2_object()(Curve(Kernel::Circle_2(Point(0, 0), 1)),
                                    std::back_inserter(pieces));
  Polygon disk;
  for (const auto& piece : pieces) disk.push_back(boost::get<XCurve>(piece));
  return disk;
}

// Whether the convex counter-clockwise polygon contains the closed unit disk: every edge line at
// distance >= 1 with the origin on its inner side. Exact.
bool contains_unit_disk(const std::vector<Point>& hull) {
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Point& a = hull[i];
    const Point& b = hull[(i + 1) % hull.size()];
    const CGAL::Exact_rational ex = b.x() - a.x(), ey = b.y() - a.y();
    const CGAL::Exact_rational side = ex * (-a.y()) - ey * (-a.x());  // (b - a) x (o - a)
    if (side < 0 || side * side < ex * ex + ey * ey) return false;
  }
  return true;
}

// Green's theorem: the signed area enclosed by a closed chain of curves, each traversed from its
// source to its target.
double signed_area(const Polygon& boundary) {
  double sum = 0.0;
  for (auto it = boundary.curves_begin(); it != boundary.curves_end(); ++it) {
    const XCurve& cv = *it;
    const double x0 = CGAL::to_double(cv.source().x()), y0 = CGAL::to_double(cv.source().y());
    const double x1 = CGAL::to_double(cv.target().x()), y1 = CGAL::to_double(cv.target().y());
    if (cv.is_linear()) {
      sum += 0.5 * (x0 * y1 - x1 * y0);
      continue;
    }
    const Kernel::Circle_2& circle = cv.supporting_circle();
    const double cx = CGAL::to_double(circle.center().x());
    const double cy = CGAL::to_double(circle.center().y());
    const double r2 = CGAL::to_double(circle.squared_radius());
    // An x-monotone arc sweeps at most half the circle, |sweep| <= pi, in the direction of its
    // orientation. The difference of the endpoints' angles is that sweep, or it minus 2 pi where
    // the arc crosses atan2's cut at angle pi; or, for an arc shorter than the rounding of its
    // endpoints to double (a sliver leaving the disk), a tiny value of either sign, which is no
    // wrap: taking it for one added a whole disk (pi) to the area.
    double sweep = std::atan2(y1 - cy, x1 - cx) - std::atan2(y0 - cy, x0 - cx);
    if (cv.orientation() == CGAL::COUNTERCLOCKWISE) {
      if (sweep < -0.5 * std::numbers::pi) sweep += 2.0 * std::numbers::pi;
      sweep = std::max(sweep, 0.0);
    } else {
      if (sweep > 0.5 * std::numbers::pi) sweep -= 2.0 * std::numbers::pi;
      sweep = std::min(sweep, 0.0);
    }
    // x dy - y dx around a circle centred at c: the centre's shoelace term plus r^2 dtheta.
    sum += 0.5 * (cx * (y1 - y0) - cy * (x1 - x0) + r2 * sweep);
  }
  return sum;
}

}  // namespace

CoveredDiskArea covered_disk_area(const std::vector<DiskPolygon>& polygons) {
  CoveredDiskArea result;
  std::vector<Polygon> pieces;
  for (const DiskPolygon& polygon : polygons) {
    std::vector<Point> corners, hull;
    for (int i = 0; i < polygon.count; ++i)
      corners.emplace_back(polygon.corners[i].x, polygon.corners[i].y);
    CGAL::convex_hull_2(corners.begin(), corners.end(), std::back_inserter(hull));
    if (hull.size() < 3) continue;  // no area
    if (contains_unit_disk(hull)) {
      result.area = std::numbers::pi;
      result.fast_path = true;
      return result;
    }
    Polygon piece;
    for (std::size_t i = 0; i < hull.size(); ++i)
      piece.push_back(XCurve(hull[i], hull[(i + 1) % hull.size()]));
    pieces.push_back(std::move(piece));
  }
  if (pieces.empty()) {
    result.fast_path = true;
    return result;
  }
  PolygonSet set;
  set.join(pieces.begin(), pieces.end());
  set.intersection(unit_disk());
  std::list<PolygonWithHoles> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  double area = 0.0;
  for (const PolygonWithHoles& part : parts) {
    area += std::fabs(signed_area(part.outer_boundary()));
    for (auto hole = part.holes_begin(); hole != part.holes_end(); ++hole)
      area -= std::fabs(signed_area(*hole));
  }
  result.area = std::clamp(area, 0.0, std::numbers::pi);
  return result;
}

}  // namespace shadowcts
