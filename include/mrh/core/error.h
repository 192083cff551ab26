// SPDX-License-Identifier: Apache-2.0
// The exception types thrown on the setup path for bad user input (never on the RT path).
#pragma once

#include <stdexcept>
#include <string>

namespace mrh {

/// Base of every error mrhaptics throws. The message is one line: where, what, expected, fix.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
