// SPDX-License-Identifier: Apache-2.0
// PlotReport: writes report.gp next to ticks.csv and runs gnuplot on it to draw report.png.
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "mrh/engine/method.h"
#include "mrh/report/report.h"
#include "report/report_script.h"

extern char** environ;

namespace mrh::report {
namespace {

// gnuplot's error text can be long (it echoes the offending script line); the caller prints
// `why` on one line, so keep its tail, where the actual error is.
constexpr std::size_t kMaxWhyChars = 400;

// The same search `command -v gnuplot` does: the first executable named gnuplot on PATH.
std::optional<std::filesystem::path> FindOnPath(const std::string& program) {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): setup path; nothing in mrhaptics calls setenv.
  const char* path_env = std::getenv("PATH");
  if (path_env == nullptr) return std::nullopt;
  std::stringstream dirs(path_env);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate =
        std::filesystem::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) {
      return candidate;
    }
  }
  return std::nullopt;
}

// Reads a pipe to its end (gnuplot's stderr).
std::string ReadAll(int fd) {
  std::string text;
  std::array<char, 4096> chunk{};
  for (;;) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n > 0) {
      text.append(chunk.data(), static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      return text;
    }
  }
}

// One line out of gnuplot's multi-line stderr: lines joined by " | ", tail kept.
std::string OneLine(const std::string& text) {
  std::string out;
  std::stringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto first = line.find_first_not_of(" \t\r^");
    if (first == std::string::npos) continue;
    if (!out.empty()) out += " | ";
    out += line.substr(first);
  }
  if (out.size() > kMaxWhyChars) out = "..." + out.substr(out.size() - kMaxWhyChars);
  return out;
}

struct SpawnResult {
  int status = -1;  ///< exit status, or -1 if it did not exit normally
  std::string stderr_text;
};

// Starts `program report.gp` in `dir` with stdin/stdout on /dev/null and stderr on
// `stderr_fd`. Returns 0 or an errno value.
int Spawn(const std::string& program, const std::filesystem::path& dir,
          const std::string& script_name, int stderr_fd, pid_t* pid) {
  posix_spawn_file_actions_t actions;
  int rc = posix_spawn_file_actions_init(&actions);
  if (rc != 0) return rc;
  rc = posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (rc == 0) rc = posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  if (rc == 0) rc = posix_spawn_file_actions_adddup2(&actions, stderr_fd, 2);
  if (rc == 0) rc = posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  std::string argv0 = program;
  std::string script = script_name;
  std::array<char*, 3> argv{argv0.data(), script.data(), nullptr};
  if (rc == 0) rc = posix_spawn(pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc;
}

// Runs gnuplot on dir/report.gp and collects its exit status and stderr.
std::optional<SpawnResult> RunGnuplot(const std::filesystem::path& gnuplot,
                                      const std::filesystem::path& dir,
                                      const std::string& script_name, std::string* why) {
  // Close-on-exec keeps the read end out of the child; dup2 onto fd 2 clears the flag there.
  std::array<int, 2> pipe_fds{};
  if (::pipe2(pipe_fds.data(), O_CLOEXEC) != 0) {
    *why =
        fmt::format("cannot create a pipe for gnuplot: {}", std::generic_category().message(errno));
    return std::nullopt;
  }
  pid_t pid = 0;
  const int rc = Spawn(gnuplot.string(), dir, script_name, pipe_fds[1], &pid);
  ::close(pipe_fds[1]);
  if (rc != 0) {
    ::close(pipe_fds[0]);
    *why =
        fmt::format("cannot start {}: {}", gnuplot.string(), std::generic_category().message(rc));
    return std::nullopt;
  }
  SpawnResult result;
  result.stderr_text = ReadAll(pipe_fds[0]);
  ::close(pipe_fds[0]);
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0) {
    if (errno != EINTR) {
      *why = fmt::format("cannot wait for gnuplot: {}", std::generic_category().message(errno));
      return std::nullopt;
    }
  }
  result.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
  return result;
}

bool WriteScript(const std::filesystem::path& dir, const std::string& title,
                 const ReportOptions& options, std::string* why) {
  const std::filesystem::path path = dir / "report.gp";
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << internal::ReportScript(title, options, internal::ScanTicks(dir / "ticks.csv"),
                                 internal::ScanBodies(dir / "bodies.csv"));
  file.close();
  if (!file)
    *why =
        fmt::format("cannot write {}: {}", path.string(), std::generic_category().message(errno));
  return static_cast<bool>(file);
}

}  // namespace

bool RunGnuplotScript(const std::filesystem::path& dir, const std::string& script,
                      const std::string& png, std::string* why) {
  std::string ignored;
  if (why == nullptr) why = &ignored;
  const std::optional<std::filesystem::path> gnuplot = FindOnPath("gnuplot");
  if (!gnuplot) {
    *why = "gnuplot not found; install gnuplot-nox";
    return false;
  }
  const std::filesystem::path png_path = dir / png;
  std::error_code ec;
  std::filesystem::remove(png_path, ec);  // so a stale plot never passes for a new one
  const std::optional<SpawnResult> result = RunGnuplot(*gnuplot, dir, script, why);
  if (!result) return false;
  if (result->status != 0 || !std::filesystem::exists(png_path)) {
    std::filesystem::remove(png_path, ec);  // gnuplot creates it at `set output`, even if it fails
    *why = fmt::format("gnuplot failed (exit {}) on {}: {}", result->status,
                       (dir / script).string(), OneLine(result->stderr_text));
    return false;
  }
  why->clear();
  return true;
}

bool PlotReport(const std::filesystem::path& dir, const std::string& title, std::string* why,
                const ReportOptions& options) {
  std::string ignored;
  if (why == nullptr) why = &ignored;
  if (!WriteScript(dir, title, options, why)) return false;
  return RunGnuplotScript(dir, "report.gp", "report.png", why);
}

bool PlotReport(const std::filesystem::path& dir, const std::string& title, std::string* why,
                bool renders_torque) {
  return PlotReport(dir, title, why, ReportOptions{.six_dof = renders_torque});
}

bool PlotRunReport(const std::filesystem::path& dir, const std::filesystem::path& session_file,
                   const engine::RunStats& stats, std::string* why) {
  const std::string title = fmt::format("{}: {} ({})", session_file.filename().string(),
                                        stats.method, settings::ModeName(stats.mode));
  // The 3-DOF methods render a force only (their torque column is zero or noise).
  const std::optional<engine::MethodDescriptor> descriptor = engine::FindMethod(stats.method);
  ReportOptions options{.six_dof = !descriptor || descriptor->settings.torque};
  for (const engine::PointerRunStats& pointer : stats.pointers) {
    options.pointers.push_back(pointer.body);
  }
  for (const physics::BodyImpulseTotal& impulse : stats.impulses) {
    if (impulse.linear.norm() > 0.0 || impulse.angular.norm() > 0.0) {
      options.touched_bodies.push_back(impulse.name);
    }
  }
  return PlotReport(dir, title, why, options);
}

}  // namespace mrh::report
