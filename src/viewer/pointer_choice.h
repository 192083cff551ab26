// SPDX-License-Identifier: Apache-2.0
// Which of a session's pointers the viewer's mouse drives, and that pointer's device block.
#pragma once

#include <string>
#include <vector>

#include "mrh/session/session.h"

namespace mrh::viewer::internal {

/// The pointers' bodies in order: one name (`pointer.body`) for a one-pointer session.
std::vector<std::string> PointerNames(const session::Session& session);

/// The pointer the mouse drives: `chosen` if it is one of `count` pointers, else the first.
int ChoosePointer(int chosen, int count) noexcept;

/// Pointer i's device block (the session's `device` for a one-pointer session).
/// @pre 0 <= i < PointerNames(session).size().
const session::DeviceConfig& PointerDevice(const session::Session& session, int i);

}  // namespace mrh::viewer::internal
