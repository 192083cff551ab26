// SPDX-License-Identifier: Apache-2.0
// JSON text → document, with errors located by line and column and repeated keys rejected.
#include "session/json_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <string_view>
#include <vector>

#include "mrh/core/error.h"

namespace mrh::session::internal {
namespace {

using Json = nlohmann::json;

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line 3, column 8: "
// (its column counts differ from editors' at line ends); keep only the part after that prefix so
// the position comes from PositionOf alone.
std::string StripPrefix(const std::string& message) {
  std::size_t start = message.find("] ");
  start = start == std::string::npos ? 0 : start + 2;
  const std::size_t located = message.find("parse error", start);
  if (located != std::string::npos) {
    const std::size_t colon = message.find(": ", located);
    if (colon != std::string::npos) start = colon + 2;
  }
  return message.substr(start);
}

// One open object or array while parsing, to name the key path of a repeated key.
struct Frame {
  bool is_object = true;
  std::string key;       // object: the key being read
  long long index = -1;  // array: the element being read
  std::set<std::string> seen;
};

std::string PathOf(const std::vector<Frame>& frames) {
  std::string path;
  for (const Frame& frame : frames) {
    if (frame.is_object) {
      path += (path.empty() ? "" : ".") + frame.key;
    } else {
      path += fmt::format("[{}]", frame.index);
    }
  }
  return path;
}

// Rejects a key that appears twice in one object: nlohmann keeps the last value silently, and
// the user almost certainly meant something else by one of the two.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& origin) : origin_(&origin) {}

  bool operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
    const bool starts_value = event == Json::parse_event_t::object_start ||
                              event == Json::parse_event_t::array_start ||
                              event == Json::parse_event_t::value;
    if (starts_value && !frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
    switch (event) {
      case Json::parse_event_t::object_start:
        frames_.push_back(Frame{});
        break;
      case Json::parse_event_t::array_start:
        frames_.push_back(Frame{});
        frames_.back().is_object = false;
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case Json::parse_event_t::key:
        OnKey(parsed.get<std::string>());
        break;
      case Json::parse_event_t::value:
        break;
    }
    return true;
  }

 private:
  void OnKey(const std::string& key) {
    Frame& frame = frames_.back();
    frame.key = key;
    if (frame.seen.insert(key).second) return;
    throw InvalidArgument(fmt::format(
        "{}: {}: duplicate key; expected each key at most once in an object (JSON would keep "
        "only the last value)",
        *origin_, PathOf(frames_)));
  }

  const std::string* origin_;
  std::vector<Frame> frames_;
};

}  // namespace

TextPosition PositionOf(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  TextPosition position;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else {
      ++position.column;
    }
  }
  return position;
}

Json ParseJsonText(const std::string& text, const std::string& origin) {
  try {
    return Json::parse(text, DuplicateKeyCheck(origin));
  } catch (const Json::parse_error& e) {
    // e.byte is the 1-based offset of the last character read: where the error was detected.
    const TextPosition at = PositionOf(text, e.byte == 0 ? 0 : e.byte - 1);
    throw InvalidArgument(
        fmt::format("{}:{}:{}: {}", origin, at.line, at.column, StripPrefix(e.what())));
  } catch (const Json::out_of_range& e) {
    // A number too large for a double ("number overflow parsing '1e400'"); locate the literal.
    const std::string message = StripPrefix(e.what());
    const std::size_t open = message.find('\'');
    const std::size_t close = message.rfind('\'');
    std::string where = origin;
    if (open != std::string::npos && close > open) {
      const std::size_t offset = text.find(message.substr(open + 1, close - open - 1));
      if (offset != std::string::npos) {
        const TextPosition at = PositionOf(text, offset);
        where = fmt::format("{}:{}:{}", origin, at.line, at.column);
      }
    }
    throw InvalidArgument(
        fmt::format("{}: {}; expected a number of magnitude below 1.8e308", where, message));
  }
}

}  // namespace mrh::session::internal
