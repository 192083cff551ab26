// SPDX-License-Identifier: Apache-2.0
// Typed reads of session JSON values with one-line errors naming the dotted key.
#include "session/json_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::session::internal {
namespace {

namespace fs = std::filesystem;

// Long string values are cut in messages so an error stays one readable line.
constexpr std::size_t kMaxQuotedChars = 40;

// True when `inner` is `outer` or a key below it ("a.b" is below "a"; "a[1]" is below "a").
bool IsWithin(std::string_view inner, std::string_view outer) {
  if (inner.size() < outer.size() || inner.substr(0, outer.size()) != outer) return false;
  return inner.size() == outer.size() || inner[outer.size()] == '.' || inner[outer.size()] == '[';
}

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

}  // namespace

// The allowed key closest to a misspelt one, if it is close enough to be a likely typo.
std::optional<std::string_view> ClosestName(std::string_view key,
                                            const std::vector<std::string_view>& allowed) {
  std::optional<std::string_view> best;
  std::size_t best_distance = std::max<std::size_t>(2, key.size() / 3) + 1;
  for (const std::string_view candidate : allowed) {
    const std::size_t distance = EditDistance(key, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

Context::Context(std::string origin, fs::path base_dir)
    : origin_(std::move(origin)), base_dir_(std::move(base_dir)) {}

void Context::AddOverride(std::string path, std::string text) {
  overrides_.emplace_back(std::move(path), std::move(text));
}

void Context::Fail(std::string_view path, std::string_view what, std::string_view expected) const {
  std::string source;
  // The last override wins, so it is the one that wrote the offending value.
  for (auto it = overrides_.rbegin(); it != overrides_.rend() && !path.empty(); ++it) {
    if (IsWithin(path, it->first) || IsWithin(it->first, path)) {
      source = fmt::format(" (from --set {})", it->second);
      break;
    }
  }
  throw InvalidArgument(fmt::format("{}: {}: {}{}; expected {}", origin_,
                                    path.empty() ? "(top level)" : path, what, source, expected));
}

std::string Describe(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return fmt::format("a boolean ({})", value.dump());
    case nlohmann::json::value_t::string: {
      std::string text = value.get<std::string>();
      if (text.size() > kMaxQuotedChars) text = text.substr(0, kMaxQuotedChars) + "...";
      return fmt::format("a string ({})", nlohmann::json(text).dump());
    }
    case nlohmann::json::value_t::array:
      return fmt::format("an array of {} element{}", value.size(), value.size() == 1 ? "" : "s");
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::number_float:
      return fmt::format("a number ({})", FormatNumber(value.get<double>()));
    default:
      return fmt::format("a number ({})", value.dump());
  }
}

Node::Node(const Context& context, const nlohmann::json& value, std::string path)
    : context_(&context), value_(&value), path_(std::move(path)) {}

void Node::Fail(std::string_view what, std::string_view expected) const {
  context_->Fail(path_, what, expected);
}

void Node::ExpectObject(const std::vector<std::string_view>& allowed, std::string_view what) const {
  const std::string keys = fmt::format("{}", fmt::join(allowed, ", "));
  if (!value_->is_object()) {
    Fail("found " + Describe(*value_), fmt::format("{} with keys: {}", what, keys));
  }
  for (const auto& [key, unused] : value_->items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    const auto closest = ClosestName(key, allowed);
    const std::string hint = closest ? fmt::format(" (did you mean \"{}\"?)", *closest) : "";
    const std::string child = path_.empty() ? key : path_ + "." + key;
    context_->Fail(child, "unknown key", fmt::format("one of: {}{}", keys, hint));
  }
}

std::optional<Node> Node::Find(std::string_view key) const {
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return Node(*context_, *it, path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key));
}

Node Node::Require(std::string_view key, std::string_view expected) const {
  std::optional<Node> node = Find(key);
  if (!node) {
    context_->Fail(path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key), "missing",
                   expected);
  }
  return *node;
}

double Node::Number(std::string_view unit) const {
  const std::string expected =
      unit.empty() ? std::string("a number") : fmt::format("a number in {}", unit);
  if (!value_->is_number()) Fail("found " + Describe(*value_), expected);
  const double number = value_->get<double>();
  if (!std::isfinite(number)) Fail("found " + Describe(*value_), "a finite " + expected);
  return number;
}

int Node::Integer() const {
  constexpr const char* kExpected = "a whole number (e.g. 50)";
  if (!value_->is_number()) Fail("found " + Describe(*value_), kExpected);
  const double number = value_->get<double>();
  if (!std::isfinite(number) || number != std::floor(number) || std::abs(number) > 1e9) {
    Fail("found " + Describe(*value_), kExpected);
  }
  return static_cast<int>(number);
}

bool Node::Bool() const {
  if (!value_->is_boolean()) Fail("found " + Describe(*value_), "true or false");
  return value_->get<bool>();
}

std::string Node::String() const {
  if (!value_->is_string()) Fail("found " + Describe(*value_), "a string");
  return value_->get<std::string>();
}

std::vector<double> Node::Numbers(std::size_t count, std::string_view layout) const {
  if (!value_->is_array() || value_->size() != count) {
    Fail("found " + Describe(*value_), fmt::format("an array of {} numbers {}", count, layout));
  }
  std::vector<double> numbers;
  for (const Node& element : Elements(layout)) numbers.push_back(element.Number(""));
  return numbers;
}

std::vector<Node> Node::Elements(std::string_view expected) const {
  if (!value_->is_array()) Fail("found " + Describe(*value_), expected);
  std::vector<Node> elements;
  for (std::size_t i = 0; i < value_->size(); ++i) {
    elements.emplace_back(*context_, (*value_)[i], fmt::format("{}[{}]", path_, i));
  }
  return elements;
}

fs::path Node::ExistingFile(std::string_view what) const {
  const std::string text = String();
  const std::string expected = fmt::format("{} as a path relative to the session file's folder {}",
                                           what, context_->base_dir().string());
  if (text.empty()) Fail("the path is empty", expected);
  fs::path path = (context_->base_dir() / text).lexically_normal();
  std::error_code error;
  if (fs::is_directory(path, error)) {
    Fail(fmt::format("{} is a directory", path.string()), expected);
  }
  if (!fs::is_regular_file(path, error)) {
    Fail(fmt::format("file {} does not exist", path.string()), expected);
  }
  return path;
}

}  // namespace mrh::session::internal
