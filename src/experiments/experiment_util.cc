// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the experiment drivers.
#include "experiment_util.h"

#include <fmt/format.h>
#include <sys/utsname.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>

#include "mrh/core/error.h"
#include "mrh/session/mjcf_text.h"

#ifndef MRH_SOURCE_SCENES_DIR
#define MRH_SOURCE_SCENES_DIR ""
#endif
#ifndef MRH_INSTALL_SCENES_DIR
#define MRH_INSTALL_SCENES_DIR ""
#endif

namespace mrh::experiments::internal {

std::filesystem::path ScenesDir() {
  const char* const candidates[] = {std::getenv("MRH_SCENES_DIR"), MRH_SOURCE_SCENES_DIR,
                                    MRH_INSTALL_SCENES_DIR};
  for (const char* candidate : candidates) {
    if (candidate != nullptr && *candidate != '\0' && std::filesystem::is_directory(candidate)) {
      return candidate;
    }
  }
  throw RuntimeError(
      "cannot find the scenes folder; set MRH_SCENES_DIR to the mrhaptics scenes/ directory");
}

std::string MachineTag() {
  std::string cpu = "unknown cpu";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) cpu = line.substr(colon + 2);
      break;
    }
  }
  utsname u{};
  const std::string kernel = uname(&u) == 0 ? std::string(u.sysname) + " " + u.release : "";
  return fmt::format("{}, {} cores, {}", cpu, std::thread::hardware_concurrency(), kernel);
}

std::string Slug(std::string_view name, char replacement) {
  std::string s(name);
  std::replace(s.begin(), s.end(), '/', replacement);
  return s;
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw RuntimeError(fmt::format("cannot write {}", path.string()));
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError(fmt::format("cannot read {}", path.string()));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw RuntimeError(fmt::format("cannot read {}", path.string()));
  return text;
}

std::string ReplaceOnce(std::string text, std::string_view from, std::string_view to,
                        const std::filesystem::path& file, std::string_view why) {
  const auto at = text.find(from);
  if (at == std::string::npos) {
    throw RuntimeError(fmt::format("{}: '{}' not found; {}", file.string(), from, why));
  }
  return text.replace(at, from.size(), to);
}

std::string ReplaceAttribute(std::string text, std::string_view element, std::string_view name,
                             std::string_view attribute, std::string_view value,
                             const std::filesystem::path& file, std::string_view why) {
  const session::MjcfAttributeSpan span =
      session::FindMjcfAttribute(text, element, name, attribute);
  if (!span.element) {
    throw RuntimeError(
        fmt::format(R"({}: no <{} name="{}"> element; {})", file.string(), element, name, why));
  }
  if (!span.found) {
    throw RuntimeError(fmt::format(R"({}: <{} name="{}"> has no {}="..." attribute; {})",
                                   file.string(), element, name, attribute, why));
  }
  return text.replace(span.offset, span.size, value);
}

}  // namespace mrh::experiments::internal
