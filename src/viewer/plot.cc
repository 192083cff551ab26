// SPDX-License-Identifier: Apache-2.0
// PlotHistory and DrawPlot: four polylines (|v|, x, y, z) with an auto-scaled symmetric range.
#include "viewer/plot.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mrh::viewer::internal {
namespace {

// The y range never shrinks below this, so that noise around zero is not blown up to full scale.
constexpr float kMinForceRange = 0.5f;    // N
constexpr float kMinTorqueRange = 0.01f;  // N·m
// Points per horizontal pixel at most; more would only overdraw.
constexpr float kPointsPerPixel = 1.0f;

const ImU32 kColors[4] = {IM_COL32(240, 240, 240, 255), IM_COL32(230, 80, 70, 255),
                          IM_COL32(90, 200, 90, 255), IM_COL32(90, 140, 250, 255)};

float Component(const PlotPoint& p, PlotQuantity q, int c) {
  const std::array<float, 3>& v = q == PlotQuantity::kForce ? p.f : p.tau;
  if (c == 0) return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return v[static_cast<std::size_t>(c - 1)];
}

// First index inside the time window.
std::size_t FirstInWindow(const PlotHistory& h, double t0) {
  std::size_t lo = 0, hi = h.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (h[mid].t < t0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

}  // namespace

void PlotHistory::Push(const TickSample& s) {
  PlotPoint& p = points_[head_];
  p.t = s.t;
  for (int i = 0; i < 3; ++i) {
    p.f[static_cast<std::size_t>(i)] = static_cast<float>(s.displayed_W.f[i]);
    p.tau[static_cast<std::size_t>(i)] = static_cast<float>(s.displayed_W.tau[i]);
  }
  head_ = (head_ + 1) % points_.size();
  size_ = std::min(size_ + 1, points_.size());
}

namespace {

// The plot's range label (top left) and its legend (top right, in the line colours).
void DrawLabels(ImDrawList* draw, const ImVec2& origin, const ImVec2& size, PlotQuantity q,
                float range) {
  const char* unit = q == PlotQuantity::kForce ? "N" : "N m";
  const std::string label = fmt::format("+/-{:.3g} {}", range, unit);
  draw->AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(180, 180, 180, 255), label.c_str());
  // Legend, right-aligned, in the line colours.
  static constexpr const char* kNames[4] = {"|v|", "x", "y", "z"};
  float x = origin.x + size.x - 4;
  for (int c = 3; c >= 0; --c) {
    x -= ImGui::CalcTextSize(kNames[c]).x;
    draw->AddText(ImVec2(x, origin.y + 2), kColors[c], kNames[c]);
    x -= ImGui::CalcTextSize(" ").x;
  }
}

}  // namespace

void DrawPlot(const char* id, const PlotHistory& h, PlotQuantity q, float seconds, float width,
              float height) {
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size(width, height);
  ImGui::InvisibleButton(id, size);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(25, 25, 30, 255));
  if (h.size() < 2) return;
  const double t1 = h[h.size() - 1].t;
  const double t0 = t1 - seconds;
  const std::size_t first = FirstInWindow(h, t0);
  float range = q == PlotQuantity::kForce ? kMinForceRange : kMinTorqueRange;
  for (std::size_t i = first; i < h.size(); ++i) range = std::max(range, Component(h[i], q, 0));
  const std::size_t count = h.size() - first;
  const auto max_points = static_cast<std::size_t>(std::max(1.0f, size.x * kPointsPerPixel));
  const std::size_t stride = std::max<std::size_t>(1, count / max_points);
  const float mid_y = origin.y + 0.5f * size.y;
  draw->AddLine(ImVec2(origin.x, mid_y), ImVec2(origin.x + size.x, mid_y),
                IM_COL32(70, 70, 80, 255));
  std::vector<ImVec2> line;
  line.reserve(count / stride + 1);
  for (int c = 3; c >= 0; --c) {
    line.clear();
    for (std::size_t i = first; i < h.size(); i += stride) {
      const float x = origin.x + size.x * static_cast<float>((h[i].t - t0) / seconds);
      const float y = mid_y - 0.5f * size.y * 0.95f * Component(h[i], q, c) / range;
      line.emplace_back(x, y);
    }
    draw->AddPolyline(line.data(), static_cast<int>(line.size()), kColors[c], 0, 1.5f);
  }
  DrawLabels(draw, origin, size, q, range);
}

}  // namespace mrh::viewer::internal
