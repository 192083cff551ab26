// SPDX-License-Identifier: Apache-2.0
// The one MJCF attribute scanner (experiments' scene edits and psychophysics' stimuli).
#include "mrh/session/mjcf_text.h"

#include <fmt/format.h>

#include <optional>
#include <string>
#include <utility>

namespace mrh::session {
namespace {

constexpr std::string_view kXmlSpace = " \t\n\r";

// The value of `attribute="..."` in the tag text `tag` (from '<' to before '>'), as an offset
// and length within `tag`.
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

MjcfAttributeSpan FindMjcfAttribute(std::string_view text, std::string_view element,
                                    std::string_view name, std::string_view attribute) {
  const std::string open = fmt::format("<{}", element);
  for (std::size_t at = text.find('<'); at != std::string_view::npos; at = text.find('<', at + 1)) {
    if (text.substr(at, 4) == "<!--") {
      at = text.find("-->", at);
      if (at == std::string_view::npos) break;
      continue;
    }
    const std::size_t end = text.find('>', at);
    if (end == std::string_view::npos) break;
    const std::string_view tag = text.substr(at, end - at);
    const bool is_element = tag.substr(0, open.size()) == open && open.size() < tag.size() &&
                            kXmlSpace.find(tag[open.size()]) != std::string_view::npos;
    const auto name_value = is_element ? FindAttributeValue(tag, "name") : std::nullopt;
    if (!name_value || tag.substr(name_value->first, name_value->second) != name) continue;
    const auto value = FindAttributeValue(tag, attribute);
    if (!value) return {.element = true};
    return {.element = true, .found = true, .offset = at + value->first, .size = value->second};
  }
  return {};
}

}  // namespace mrh::session
