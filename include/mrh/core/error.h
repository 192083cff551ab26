// SPDX-License-Identifier: Apache-2.0
// The exception types thrown on the setup path for bad user input (never on the RT path).
#pragma once

#include <stdexcept>
#include <string>

namespace mrh {

/// `text` made printable on one line: line breaks become spaces, NUL and other control
/// characters "\xNN", so a value such as "a\0b" cannot cut or split the message.
inline std::string PrintableMessage(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r' || c == '\t') {
      out += ' ';
    } else if (u < 0x20 || u == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0xf];
    } else {
      out += c;
    }
  }
  return out;
}

/// Base of every error mrhaptics throws. The message is one line: where, what, expected, fix.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(PrintableMessage(message)) {}

  explicit Error(const char* message) : Error(std::string(message)) {}
};

/// Bad settings, session keys, CLI values or device data. The CLI maps it to exit code 2.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A scene (MJCF) that cannot be loaded or lacks what a session needs. The CLI maps it to exit 2.
class SceneError : public Error {
 public:
  using Error::Error;
};

/// A failure while running (I/O, a physics blow-up that cannot be recovered). CLI exit code 1.
class RuntimeError : public Error {
 public:
  using Error::Error;
};

}  // namespace mrh
