// SPDX-License-Identifier: Apache-2.0
// Parsing and applying `--set dotted.key=value` overrides to a session document.
#include "session/overrides.h"

#include <fmt/format.h>

#include <cstdlib>
#include <string_view>

#include "mrh/core/error.h"

namespace mrh::session::internal {
namespace {

[[noreturn]] void FailOverride(const Context& context, std::string_view text, std::string_view what,
                               std::string_view expected) {
  throw InvalidArgument(
      fmt::format("{}: --set {}: {}; expected {}", context.origin(), text, what, expected));
}

std::vector<std::string> SplitKey(const Context& context, std::string_view text,
                                  std::string_view key) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(key.find('.', begin), key.size());
    if (end == begin) {
      FailOverride(context, text, fmt::format("empty key in \"{}\"", key),
                   "a dotted key such as rendering.stiffness");
    }
    parts.emplace_back(key.substr(begin, end - begin));
    if (end == key.size()) return parts;
    begin = end + 1;
  }
}

// Plain words (impulse, scenes/a.xml) are not JSON; taking them as strings saves shell quoting.
nlohmann::json ParseValue(std::string_view value) {
  nlohmann::json parsed = nlohmann::json::parse(value, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) {
    // A number too large for a double (1e309) is a number to the user, not a string.
    const std::string text(value);
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    const bool numeric = text.find_first_not_of("0123456789+-.eE") == std::string::npos &&
                         text.find_first_of("0123456789") != std::string::npos;
    if (numeric && end == text.c_str() + text.size()) return number;
    return text;  // not {...}: that would be an array
  }
  return parsed;
}

void ApplyOne(const std::string& text, nlohmann::json* document, Context* context) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    FailOverride(*context, text, "missing '='", "KEY=VALUE, e.g. --set rendering.stiffness=2000");
  }
  const std::string_view key = std::string_view(text).substr(0, equals);
  const std::vector<std::string> parts = SplitKey(*context, text, key);
  nlohmann::json* target = document;
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    target = &(*target)[parts[i]];  // creates a null member when missing
    if (target->is_null()) *target = nlohmann::json::object();
    if (!target->is_object()) {
      FailOverride(*context, text,
                   fmt::format("{} is {}, not an object", walked, Describe(*target)),
                   fmt::format("a key path through objects only (set {} as a whole: --set {}=...)",
                               walked, walked));
    }
  }
  (*target)[parts.back()] = ParseValue(std::string_view(text).substr(equals + 1));
  context->AddOverride(std::string(key), text);
}

}  // namespace

void ApplyOverrides(const std::vector<std::string>& overrides, nlohmann::json* document,
                    Context* context) {
  for (const std::string& text : overrides) ApplyOne(text, document, context);
}

}  // namespace mrh::session::internal
