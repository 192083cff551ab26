// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the experiment drivers.
#include "experiment_util.h"

#include <fmt/format.h>
#include <sys/utsname.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <thread>
#include <utility>

#include "mrh/core/error.h"

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

namespace {

constexpr std::string_view kXmlSpace = " \t\n\r";

// The value of `attribute="..."` in the tag text `tag` (from '<' to before '>'), as an offset
// and length within `tag`; the attribute name must follow whitespace, so `name` never matches
// inside `mesh_name`.
std::optional<std::pair<std::size_t, std::size_t>> FindAttributeValue(std::string_view tag,
                                                                      std::string_view attribute) {
  const std::string key = fmt::format("{}=\"", attribute);
  for (std::size_t at = tag.find(key); at != std::string_view::npos; at = tag.find(key, at + 1)) {
    if (at == 0 || kXmlSpace.find(tag[at - 1]) == std::string_view::npos) continue;
    const std::size_t begin = at + key.size();
    const std::size_t end = tag.find('"', begin);
    if (end == std::string_view::npos) return std::nullopt;
    return std::pair{begin, end - begin};
  }
  return std::nullopt;
}

}  // namespace

std::string ReplaceAttribute(std::string text, std::string_view element, std::string_view name,
                             std::string_view attribute, std::string_view value,
                             const std::filesystem::path& file, std::string_view why) {
  const std::string open = fmt::format("<{}", element);
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1)) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) break;
      continue;
    }
    const std::size_t end = text.find('>', at);
    if (end == std::string::npos) break;
    const std::string_view tag = std::string_view(text).substr(at, end - at);
    const bool is_element = tag.substr(0, open.size()) == open && open.size() < tag.size() &&
                            kXmlSpace.find(tag[open.size()]) != std::string_view::npos;
    const auto name_value = is_element ? FindAttributeValue(tag, "name") : std::nullopt;
    if (!name_value || tag.substr(name_value->first, name_value->second) != name) continue;
    const auto old_value = FindAttributeValue(tag, attribute);
    if (!old_value) {
      throw RuntimeError(fmt::format(R"({}: <{} name="{}"> has no {}="..." attribute; {})",
                                     file.string(), element, name, attribute, why));
    }
    return text.replace(at + old_value->first, old_value->second, value);
  }
  throw RuntimeError(
      fmt::format(R"({}: no <{} name="{}"> element; {})", file.string(), element, name, why));
}

}  // namespace mrh::experiments::internal
