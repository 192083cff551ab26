// SPDX-License-Identifier: Apache-2.0
// `--set dotted.key=value` overrides, applied to the session document before validation.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "session/json_node.h"

namespace mrh::session::internal {

/// Applies each "a.b.c=value" in order to `document` (an object): the value is parsed as JSON
/// if it parses, else kept as a plain string; missing objects along the path are created.
/// Records each written key in `context` so later errors say they came from `--set`.
/// @throws mrh::InvalidArgument naming the override for a missing '=', an empty key or a path
/// through a value that is not an object.
void ApplyOverrides(const std::vector<std::string>& overrides, nlohmann::json* document,
                    Context* context);

}  // namespace mrh::session::internal
