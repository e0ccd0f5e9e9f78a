#pragma once
/// A value that follows piecewise-linear keyframes in load time, held constant before the first and after the
/// last keyframe.

#include <algorithm>
#include <cassert>
#include <utility>
#include <vector>

namespace nodus::loading {

template <class Value>
class Path {
 public:
  explicit Path(Value initial) : times_{0.0}, values_{initial} {}
  /// A path with these keyframes (as times() and values() return them; a saved state): at least one, times
  /// not decreasing.
  Path(std::vector<double> times, std::vector<Value> values)
      : times_(std::move(times)), values_(std::move(values)) {
    assert(!times_.empty() && times_.size() == values_.size());
  }

  /// Appends a keyframe; times must not decrease.
  void add(double time, const Value& value) {
    assert(time >= times_.back());
    times_.push_back(time);
    values_.push_back(value);
  }
  /// Restarts the path at `time` with `value`.
  void reset(double time, const Value& value) {
    times_.assign(1, time);
    values_.assign(1, value);
  }
  Value at(double time) const {
    if (time <= times_.front()) return values_.front();
    if (time >= times_.back()) return values_.back();
    const auto it = std::upper_bound(times_.begin(), times_.end(), time);
    const std::size_t i = static_cast<std::size_t>(it - times_.begin());
    const double s = (time - times_[i - 1]) / (times_[i] - times_[i - 1]);
    return values_[i - 1] + s * (values_[i] - values_[i - 1]);
  }
  double last_time() const { return times_.back(); }
  /// The keyframes, in order.
  const std::vector<double>& times() const { return times_; }
  const std::vector<Value>& values() const { return values_; }

 private:
  std::vector<double> times_;
  std::vector<Value> values_;
};

}  // namespace nodus::loading
