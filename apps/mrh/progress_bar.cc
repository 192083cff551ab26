// SPDX-License-Identifier: Apache-2.0
// ProgressBar: throttled redraws of one stderr line, cleared at the end.
#include "progress_bar.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace mrh::cli {
namespace {

// Runs shorter than this finish before a bar would help; it would only flicker.
constexpr std::chrono::duration<double> kMinWallForBar{2.0};
// Redrawing more often than 10 times a second costs terminal time and shows nothing new.
constexpr std::chrono::milliseconds kRedrawPeriod{100};
constexpr int kBarWidth = 30;

}  // namespace

ProgressBar::ProgressBar(const ProgressSettings& settings)
    : settings_(settings), start_(Clock::now()), last_draw_(start_ - kRedrawPeriod) {}

ProgressBar::~ProgressBar() {
  Finish();
}

void ProgressBar::Update(double fraction) {
  if (!settings_.enabled) return;
  const Clock::time_point now = Clock::now();
  const bool long_run = settings_.realtime ? settings_.duration > kMinWallForBar.count()
                                           : now - start_ >= kMinWallForBar;
  if (!long_run || now - last_draw_ < kRedrawPeriod) return;
  last_draw_ = now;

  const double done = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(done * kBarWidth));
  const std::string line = fmt::format(
      "[{}{}] {:3d}%  t={:.1f}/{:.1f} s", std::string(static_cast<std::size_t>(filled), '#'),
      std::string(static_cast<std::size_t>(kBarWidth - filled), '.'),
      static_cast<int>(std::lround(done * 100.0)), done * settings_.duration, settings_.duration);
  // Pad to the previous length so a shorter line leaves no stale characters.
  fmt::print(stderr, "\r{:<{}}", line, std::max(line.size(), drawn_chars_));
  std::fflush(stderr);
  drawn_chars_ = std::max(line.size(), drawn_chars_);
}

void ProgressBar::Finish() {
  if (drawn_chars_ == 0) return;
  fmt::print(stderr, "\r{}\r", std::string(drawn_chars_, ' '));
  std::fflush(stderr);
  drawn_chars_ = 0;
}

}  // namespace mrh::cli
