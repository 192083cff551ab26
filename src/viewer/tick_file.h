// SPDX-License-Identifier: Apache-2.0
// Records viewer ticks as a ticks.csv that the replay device (and `mrh run` tools) can read.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "viewer/live_feed.h"

namespace mrh::viewer::internal {

/// A ticks.csv being written: header `t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts` (as
/// `mrh run` writes), world frame, t from 0 at the first row. UI thread only; not RT-safe.
class TickFile {
 public:
  /// Creates the file (and its folder). @throws mrh::RuntimeError naming the file.
  explicit TickFile(const std::filesystem::path& path);
  ~TickFile();
  TickFile(const TickFile&) = delete;
  TickFile& operator=(const TickFile&) = delete;

  void Write(const TickSample& sample);
  /// Flushes and closes. @throws mrh::RuntimeError on a write error.
  void Close();

  const std::filesystem::path& path() const { return path_; }

  std::int64_t rows() const { return rows_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  double t0_ = 0.0;
  std::int64_t rows_ = 0;
};

}  // namespace mrh::viewer::internal
