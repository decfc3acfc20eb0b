#include "oracles/receiver_search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/exact_segment_triangle.h"
#include "oracles/exact_triangle_cube.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

struct Box {
  std::array<double, 3> lo, hi;
};

// Every double comparison below is conservative without a margin: the exact difference of two
// floats is at most tau only if its rounding to double is (rounding is monotone, tau a double).
bool box_within(const Box& b, const glm::dvec3& p, double h) {
  for (int k = 0; k < 3; ++k)
    if (b.lo[std::size_t(k)] - p[k] > h || p[k] - b.hi[std::size_t(k)] > h) return false;
  return true;
}

// Median-split hierarchy of the float boxes of the non-zero-area triangles, for point queries.
class TriangleBoxTree {
 public:
  explicit TriangleBoxTree(const Case& c) {
    for (std::size_t t = 0; t < c.triangles.size(); ++t) {
      if (is_zero_area(c.triangles[t])) continue;
      const Triangle& tri = c.triangles[t];
      Box b;
      for (int k = 0; k < 3; ++k) {
        b.lo[std::size_t(k)] = std::min({tri.v0[k], tri.v1[k], tri.v2[k]});
        b.hi[std::size_t(k)] = std::max({tri.v0[k], tri.v1[k], tri.v2[k]});
      }
      items_.push_back({b, std::uint32_t(t)});
    }
    if (!items_.empty()) build(0, items_.size());
  }

  // Calls visit(triangle) for every triangle whose box lies within h of p (L-infinity).
  template <class Visitor>
  void visit(const glm::dvec3& p, double h, Visitor&& visit) const {
    if (nodes_.empty()) return;
    // Median splits keep the depth near log2(n): 128 entries hold any case validate() accepts.
    std::array<std::uint32_t, 128> stack;
    std::size_t depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
      const Node& node = nodes_[stack[--depth]];
      if (!box_within(node.box, p, h)) continue;
      if (node.count) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
          if (box_within(items_[i].box, p, h)) visit(items_[i].triangle);
      } else {
        stack[depth++] = node.right;
        stack[depth++] = node.left;
      }
    }
  }

 private:
  struct Item {
    Box box;
    std::uint32_t triangle;
  };
  struct Node {
    Box box;
    std::uint32_t left = 0, right = 0;   // inner node
    std::uint32_t first = 0, count = 0;  // leaf: items [first, first + count)
  };

  std::uint32_t build(std::size_t begin, std::size_t end) {
    const auto index = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    Box box = items_[begin].box;
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        box.lo[k] = std::min(box.lo[k], items_[i].box.lo[k]);
        box.hi[k] = std::max(box.hi[k], items_[i].box.hi[k]);
      }
    nodes_[index].box = box;
    if (end - begin <= 4) {
      nodes_[index].first = std::uint32_t(begin);
      nodes_[index].count = std::uint32_t(end - begin);
      return index;
    }
    std::size_t axis = 0;
    for (std::size_t k = 1; k < 3; ++k)
      if (box.hi[k] - box.lo[k] > box.hi[axis] - box.lo[axis]) axis = k;
    const std::size_t middle = begin + (end - begin) / 2;
    // Ties broken by triangle index: the tree depends on the case only.
    std::nth_element(items_.begin() + std::ptrdiff_t(begin),
                     items_.begin() + std::ptrdiff_t(middle), items_.begin() + std::ptrdiff_t(end),
                     [axis](const Item& a, const Item& b) {
                       const double ca = a.box.lo[axis] + a.box.hi[axis];
                       const double cb = b.box.lo[axis] + b.box.hi[axis];
                       return ca != cb ? ca < cb : a.triangle < b.triangle;
                     });
    const std::uint32_t left = build(begin, middle);
    const std::uint32_t right = build(middle, end);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
  }

  std::vector<Item> items_;
  std::vector<Node> nodes_;
};

enum class Found : std::uint8_t { not_searched, none, unique, ambiguous };

}  // namespace

ReceiverSearch find_receivers(const Case& c, ViewSamples& samples, const std::string& source,
                              const std::string& position_channels) {
  ReceiverSearch result;
  result.tau = c.parameters.eps_rel * c.scale();
  result.receiver_ambiguous.assign(samples.samples.size(), 0);
  const TriangleBoxTree tree(c);
  std::vector<Found> found(samples.samples.size(), Found::not_searched);
  const double tau = result.tau;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size()), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      ViewSample& s = samples.samples[i];
      if (s.sample_class == SampleClass::sky || s.receiver != no_receiver) continue;
      const glm::dvec3 p(s.position);
      std::uint32_t lowest = no_receiver, count = 0;
      tree.visit(p, tau, [&](std::uint32_t t) {
        if (!triangle_meets_cube(c.triangles[t], p, tau)) return;
        ++count;
        lowest = std::min(lowest, t);
      });
      found[i] = count == 0 ? Found::none : count == 1 ? Found::unique : Found::ambiguous;
      s.receiver = lowest;
    }
  });
  for (std::size_t i = 0; i < found.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (found[i] == Found::none) {
      std::ostringstream problem;
      problem.precision(9);
      problem << "no triangle of the case lies within tau = " << tau << " of the position ("
              << s.position.x << ", " << s.position.y << ", " << s.position.z
              << "): the G-buffer does not show this case's scene there (check the camera, the "
                 "inverse view-projection and the depth convention), or its depth is too coarse "
                 "(float32 depth, ideally reversed-Z, or world positions)";
      throw InputError(source,
                       position_channels + ", pixel (" + std::to_string(s.pixel_x) + ", " +
                           std::to_string(s.pixel_y) + ")",
                       problem.str());
    }
    result.unique += found[i] == Found::unique;
    result.ambiguous += found[i] == Found::ambiguous;
    result.receiver_ambiguous[i] = found[i] == Found::ambiguous;
  }
  return result;
}

}  // namespace shadowcts
