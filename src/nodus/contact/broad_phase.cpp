#include "nodus/contact/broad_phase.hpp"

#include <utility>

namespace nodus::contact {

Box3 element_box(const BeamCurves& curves, int element) {
  const Eigen::Matrix3d nodes = curves.element_axis(element);
  // Bezier control point of the middle: the curve passes through nodes.col(1) at t = 0.
  const Eigen::Vector3d control = 2.0 * nodes.col(1) - 0.5 * (nodes.col(0) + nodes.col(2));
  Box3 box(nodes.col(0));
  box.extend(nodes.col(2));
  box.extend(control);
  return box;
}

namespace {

std::vector<Box3> element_boxes(const BeamCurves& curves, const std::vector<int>& elements) {
  std::vector<Box3> boxes;
  boxes.reserve(elements.size());
  for (int e : elements) boxes.push_back(element_box(curves, e));
  return boxes;
}

}  // namespace

ElementTree::ElementTree(const BeamCurves& curves, const std::vector<int>& elements)
    : ElementTree(elements, element_boxes(curves, elements)) {}

ElementTree::ElementTree(std::vector<int> ids, std::vector<Box3> boxes)
    : elements_(std::move(ids)), boxes_(std::move(boxes)) {
  std::vector<int> entries(elements_.size());
  for (std::size_t i = 0; i < entries.size(); ++i) entries[i] = static_cast<int>(i);
  tree_.init(entries.begin(), entries.end(), boxes_.begin(), boxes_.end());
}

namespace {

struct BoxQuery {
  const Box3& box;
  const std::vector<int>& elements;
  const std::vector<Box3>& boxes;
  std::vector<int>& out;
  bool intersectVolume(const Box3& volume) const { return volume.intersects(box); }
  bool intersectObject(const int& entry) {
    // KdBVH hands over both objects of a leaf pair without testing their own boxes.
    const auto i = static_cast<std::size_t>(entry);
    if (boxes[i].intersects(box)) out.push_back(elements[i]);
    return false;  // keep going
  }
};

}  // namespace

void ElementTree::query(const Box3& box, std::vector<int>& out) const {
  if (elements_.empty()) return;
  BoxQuery q{box, elements_, boxes_, out};
  Eigen::BVIntersect(tree_, q);
}

}  // namespace nodus::contact
