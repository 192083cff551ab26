// SPDX-License-Identifier: Apache-2.0
// Text-level look-up in MJCF scenes, for the drivers that edit a scene's text before loading it
// (experiments, psychophysics stimuli). Pure functions: thread-safe, no allocation beyond the
// search, no exceptions.
#pragma once

#include <cstddef>
#include <string_view>

namespace mrh::session {

/// Where the value of `attribute="..."` of the first element `<element ... name="name" ...>`
/// stands in the MJCF `text`.
struct MjcfAttributeSpan {
  bool element = false;    ///< there is such an element
  bool found = false;      ///< and it has the attribute (offset and size are valid)
  std::size_t offset = 0;  ///< of the value's first character (after the opening quote)
  std::size_t size = 0;    ///< of the value, quotes excluded
};

/// Finds the double-quoted `attribute` of the first `<element>` whose name is `name`
/// (attributes in any order, comments skipped; an attribute must follow whitespace, so `name`
/// never matches inside `mesh_name`).
MjcfAttributeSpan FindMjcfAttribute(std::string_view text, std::string_view element,
                                    std::string_view name, std::string_view attribute);

}  // namespace mrh::session
