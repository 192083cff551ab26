// SPDX-License-Identifier: Apache-2.0
// CsvRecorder: streams tick, body and step records into three CSV files through large buffers.
#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/report/column_recorder.h"
#include "mrh/report/report.h"
#include "mrh/world/world.h"

namespace mrh::report {
namespace {

// Records arrive at 1 kHz or more; writing in ~1 MB chunks keeps the syscall count negligible
// while bounding the memory a long run holds.
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

// A CSV header line: the column names (mrh/report/column_recorder.h) joined by commas.
std::string Header(std::span<const std::string_view> columns) {
  std::string header;
  for (const std::string_view name : columns) {
    if (!header.empty()) header += ',';
    header += name;
  }
  return header + '\n';
}

// One output file with its write buffer. fmt's default `{}` for doubles prints the shortest text
// that parses back to the same value, so the CSV is lossless.
class BufferedFile {
 public:
  BufferedFile(std::filesystem::path path, std::string_view header) : path_(std::move(path)) {
    file_ = std::fopen(path_.c_str(), "wb");
    if (file_ == nullptr) {
      throw RuntimeError(
          fmt::format("cannot open {} for writing: {}; check that the folder is "
                      "writable",
                      path_.string(), std::generic_category().message(errno)));
    }
    buffer_.append(header);
  }

  BufferedFile(const BufferedFile&) = delete;
  BufferedFile& operator=(const BufferedFile&) = delete;

  ~BufferedFile() {
    if (file_ != nullptr) std::fclose(file_);  // Close() reports errors; a destructor cannot.
  }

  fmt::memory_buffer& buffer() { return buffer_; }

  void MaybeFlush() {
    if (buffer_.size() >= kFlushBytes) Flush();
  }

  void Flush() {
    if (file_ == nullptr || buffer_.size() == 0) return;
    const std::size_t size = buffer_.size();
    const std::size_t written = std::fwrite(buffer_.data(), 1, size, file_);
    buffer_.clear();
    if (written != size) Fail("write");
  }

  void Close() {
    if (file_ == nullptr) return;
    Flush();
    const bool had_error = std::ferror(file_) != 0;
    const int rc = std::fclose(file_);
    file_ = nullptr;
    if (had_error || rc != 0) Fail("close");
  }

 private:
  [[noreturn]] void Fail(const char* what) {
    throw RuntimeError(fmt::format("cannot {} {}: {}; check free disk space and permissions", what,
                                   path_.string(), std::generic_category().message(errno)));
  }

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  fmt::memory_buffer buffer_;
};

// CSV field for a body name: quoted only if it contains a separator, a quote or a line break.
void AppendName(fmt::memory_buffer& out, const std::string& name, int id) {
  if (name.empty()) {
    fmt::format_to(std::back_inserter(out), "body{}", id);
    return;
  }
  if (name.find_first_of(",\"\r\n") == std::string::npos) {
    out.append(std::string_view(name));
    return;
  }
  out.push_back('"');
  for (const char c : name) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
}

void AppendVec(fmt::memory_buffer& out, const Vec3& v) {
  fmt::format_to(std::back_inserter(out), ",{},{},{}", v.x(), v.y(), v.z());
}

void AppendQuat(fmt::memory_buffer& out, const Quat& q) {
  fmt::format_to(std::back_inserter(out), ",{},{},{},{}", q.w(), q.x(), q.y(), q.z());
}

std::filesystem::path CreateDir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw RuntimeError(fmt::format("cannot create output folder {}: {}; choose a writable --out",
                                   dir.string(), ec ? ec.message() : "not a directory"));
  }
  return dir;
}

// ticks.csv's header: with several pointers a last column names each row's pointer.
std::string TickHeader(bool several_pointers) {
  std::string header = Header(kTickColumns);
  if (several_pointers) header.insert(header.size() - 1, ",pointer");
  return header;
}

}  // namespace

struct CsvRecorder::Impl {
  Impl(const std::filesystem::path& dir, std::vector<std::string> names)
      : pointer_names(names.size() >= 2 ? std::move(names) : std::vector<std::string>{}),
        ticks(CreateDir(dir) / "ticks.csv", TickHeader(!pointer_names.empty())),
        bodies(dir / "bodies.csv", Header(kBodyColumns)),
        steps(dir / "steps.csv", Header(kStepColumns)) {}

  std::vector<std::string> pointer_names;  ///< empty with one pointer
  BufferedFile ticks;
  BufferedFile bodies;
  BufferedFile steps;
};

CsvRecorder::CsvRecorder(const std::filesystem::path& dir, std::vector<std::string> pointer_names)
    : impl_(std::make_unique<Impl>(dir, std::move(pointer_names))) {}

CsvRecorder::~CsvRecorder() = default;

void CsvRecorder::OnTick(const ir::TickRecord& tick) {
  fmt::memory_buffer& out = impl_->ticks.buffer();
  fmt::format_to(std::back_inserter(out), "{}", tick.t);
  AppendVec(out, tick.X_WP.p);
  AppendQuat(out, tick.X_WP.q);
  AppendVec(out, tick.displayed_W.f);
  AppendVec(out, tick.displayed_W.tau);
  fmt::format_to(std::back_inserter(out), ",{},{}", tick.contacts, tick.safety_bits);
  if (!impl_->pointer_names.empty()) {
    const auto i = static_cast<std::size_t>(tick.pointer);
    out.push_back(',');
    if (i < impl_->pointer_names.size()) {
      AppendName(out, impl_->pointer_names[i], tick.pointer);
    } else {
      fmt::format_to(std::back_inserter(out), "pointer{}", tick.pointer);
    }
  }
  out.push_back('\n');
  impl_->ticks.MaybeFlush();
}

void CsvRecorder::OnStep(const physics::StepRecord& step, const world::World& world) {
  fmt::format_to(std::back_inserter(impl_->steps.buffer()), "{},{},{},{},{},{},{},{},{},{},{}\n",
                 step.t, step.step, step.compute_ms, step.sim_contacts, step.neighbors,
                 step.point_contacts, step.solver_iterations, step.world_step_ms, step.ir_ms,
                 step.model_ms, step.sync_ms);
  impl_->steps.MaybeFlush();

  fmt::memory_buffer& out = impl_->bodies.buffer();
  for (int id = 0; id < world.num_bodies(); ++id) {
    const world::BodyInfo& info = world.body(id);
    if (info.is_static) continue;
    const world::BodyState state = world.body_state(id);
    fmt::format_to(std::back_inserter(out), "{},", step.t);
    AppendName(out, info.name, id);
    AppendVec(out, state.X_WB.p);
    AppendQuat(out, state.X_WB.q);
    AppendVec(out, state.V_WCm.v);
    AppendVec(out, state.V_WCm.w);
    AppendVec(out, state.p_WCm);
    out.push_back('\n');
  }
  impl_->bodies.MaybeFlush();
}

void CsvRecorder::Close() {
  impl_->ticks.Close();
  impl_->bodies.Close();
  impl_->steps.Close();
}

}  // namespace mrh::report
