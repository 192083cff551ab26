// SPDX-License-Identifier: Apache-2.0
// Strict parsing of session JSON text with `file:line:column` errors and duplicate-key checks.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace mrh::session::internal {

/// 1-based line and column of the character at 0-based byte `offset` of `text` (an offset at
/// or past the end means the position just after the last character).
struct TextPosition {
  std::size_t line = 1;
  std::size_t column = 1;
};

TextPosition PositionOf(const std::string& text, std::size_t offset);

/// Parses JSON text. `origin` names it in messages.
/// @throws mrh::InvalidArgument "<origin>:<line>:<column>: <parser message>" on a syntax error
/// or an out-of-range number, and "<origin>: <dotted.key>: duplicate key; ..." when an object
/// repeats a key (JSON parsers would silently keep only one of the values).
nlohmann::json ParseJsonText(const std::string& text, const std::string& origin);

}  // namespace mrh::session::internal
