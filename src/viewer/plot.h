// SPDX-License-Identifier: Apache-2.0
// The scrolling force/torque plot: a fixed ring of recent ticks drawn with ImGui's draw list.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "viewer/live_feed.h"

namespace mrh::viewer::internal {

/// The plotted part of one tick: displayed force (N) and torque (N·m), world frame.
struct PlotPoint {
  double t = 0.0;  ///< s, viewer clock
  std::array<float, 3> f{};
  std::array<float, 3> tau{};
};

/// The last `capacity` ticks, oldest first. UI thread only.
class PlotHistory {
 public:
  explicit PlotHistory(std::size_t capacity) : points_(capacity) {}

  void Push(const TickSample& sample);

  void Clear() { size_ = head_ = 0; }

  std::size_t size() const { return size_; }

  /// i = 0 is the oldest point kept. @pre i < size().
  const PlotPoint& operator[](std::size_t i) const {
    return points_[(head_ + points_.size() - size_ + i) % points_.size()];
  }

 private:
  std::vector<PlotPoint> points_;
  std::size_t size_ = 0;
  std::size_t head_ = 0;  ///< where the next point goes
};

/// Which quantity a plot shows.
enum class PlotQuantity { kForce, kTorque };

/// Draws magnitude and x, y, z of the quantity over the last `seconds` as an ImGui widget of
/// `size` pixels. Call inside an ImGui window.
void DrawPlot(const char* id, const PlotHistory& history, PlotQuantity quantity, float seconds,
              float width, float height);

}  // namespace mrh::viewer::internal
