// SPDX-License-Identifier: Apache-2.0
// TickFile: one CSV row per tick with lossless shortest-form numbers.
#include "viewer/tick_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <system_error>

#include "mrh/core/error.h"

namespace mrh::viewer::internal {
namespace {

[[noreturn]] void Fail(const char* what, const std::filesystem::path& path, int error) {
  throw RuntimeError(fmt::format("cannot {} {}: {}; check that the folder is writable", what,
                                 path.string(), std::generic_category().message(error)));
}

}  // namespace

TickFile::TickFile(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) Fail("open", path, errno);
  fmt::print(file_, "t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts\n");
}

TickFile::~TickFile() {
  if (file_ != nullptr) std::fclose(file_);  // Close() reports errors; a destructor cannot
}

void TickFile::Write(const TickSample& s) {
  if (file_ == nullptr) return;
  if (rows_ == 0) t0_ = s.t;
  const Pose& X = s.X_WP;
  const Wrench& w = s.displayed_W;
  fmt::print(file_, "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.t - t0_, X.p.x(), X.p.y(),
             X.p.z(), X.q.w(), X.q.x(), X.q.y(), X.q.z(), w.f.x(), w.f.y(), w.f.z(), w.tau.x(),
             w.tau.y(), w.tau.z(), s.contacts);
  ++rows_;
}

void TickFile::Close() {
  if (file_ == nullptr) return;
  const bool had_error = std::ferror(file_) != 0;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (had_error || rc != 0) Fail("write", path_, errno);
}

}  // namespace mrh::viewer::internal
