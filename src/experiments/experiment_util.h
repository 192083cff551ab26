// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the experiment drivers: locating scenes, machine tags, result files.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace mrh::experiments::internal {

/// The folder holding the shared scenes: $MRH_SCENES_DIR, else the source tree's scenes/, else
/// the installed share/mrhaptics/scenes. @throws mrh::RuntimeError if none exists.
std::filesystem::path ScenesDir();

/// One line naming the machine (CPU model, cores, kernel) for tagging results.
std::string MachineTag();

/// `name` with every '/' replaced by `replacement`, for file names ("local-dynamics/perturbation"
/// → "local-dynamics-perturbation").
std::string Slug(std::string_view name, char replacement = '-');

/// Writes `text` to `path`. @throws mrh::RuntimeError naming the path on failure.
void WriteText(const std::filesystem::path& path, const std::string& text);

/// The whole content of the file at `path`. @throws mrh::RuntimeError naming the path if it
/// cannot be read.
std::string ReadText(const std::filesystem::path& path);

/// `text` (the content of the scene `file`) with its first occurrence of `from` replaced by `to`,
/// for drivers that edit a shared scene.
/// @throws mrh::RuntimeError naming `file` and `from`, followed by `why` (what the driver does
/// with it and what to keep in the scene), if `text` has no `from`.
std::string ReplaceOnce(std::string text, std::string_view from, std::string_view to,
                        const std::filesystem::path& file, std::string_view why);

/// `text` (the content of the MJCF `file`) with the double-quoted `attribute` of the first
/// element `<element name="name" ...>` set to `value` (attributes in any order; comments are
/// skipped), for drivers that edit a shared scene.
/// @throws mrh::RuntimeError naming `file`, the element and the attribute, followed by `why`, if
/// there is no such element or it has no such attribute.
std::string ReplaceAttribute(std::string text, std::string_view element, std::string_view name,
                             std::string_view attribute, std::string_view value,
                             const std::filesystem::path& file, std::string_view why);

}  // namespace mrh::experiments::internal
