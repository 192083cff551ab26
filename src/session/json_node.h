// SPDX-License-Identifier: Apache-2.0
// A typed, path-aware view of a JSON value that turns every mismatch into a one-line error.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "session/schema.h"

namespace mrh::session::internal {

/// What every error needs: the session's name, the folder relative paths resolve against, and
/// which key paths `--set` overrides wrote.
class Context {
 public:
  Context(std::string origin, std::filesystem::path base_dir);

  const std::string& origin() const { return origin_; }

  /// Absolute folder of the session file.
  const std::filesystem::path& base_dir() const { return base_dir_; }

  /// Records that `--set <text>` wrote the dotted key `path`.
  void AddOverride(std::string path, std::string text);

  /// Throws InvalidArgument "<origin>: <path>: <what>; expected <expected>", plus
  /// " (from --set ...)" when an override wrote `path`, a key inside it or a key around it.
  [[noreturn]] void Fail(std::string_view path, std::string_view what,
                         std::string_view expected) const;

 private:
  std::string origin_;
  std::filesystem::path base_dir_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // (dotted key, override text)
};

/// A JSON value at a dotted key path ("" is the document). Holds references: the context and
/// the document must outlive it.
class Node {
 public:
  Node(const Context& context, const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }

  const nlohmann::json& value() const { return *value_; }

  const Context& context() const { return *context_; }

  [[noreturn]] void Fail(std::string_view what, std::string_view expected) const;

  /// Checks that this is an object whose keys are all in `allowed`; an unknown key is an error
  /// listing the allowed ones (and the closest match). `what` describes the object.
  void ExpectObject(const std::vector<std::string_view>& allowed, std::string_view what) const;
  /// The member `key`, if present. @pre ExpectObject passed.
  std::optional<Node> Find(std::string_view key) const;
  /// The member `key`; missing is an error expecting `expected`.
  Node Require(std::string_view key, std::string_view expected) const;

  /// A finite number; `unit` goes into the message ("" for dimensionless).
  double Number(std::string_view unit) const;
  /// A whole number that fits an int (e.g. 50, not 50.5).
  int Integer() const;
  bool Bool() const;
  std::string String() const;
  /// An array of exactly `count` finite numbers; `layout` names them, e.g. "[x, y, z] (m)".
  std::vector<double> Numbers(std::size_t count, std::string_view layout) const;
  /// The elements of an array (checked to be one, described by `expected` otherwise).
  std::vector<Node> Elements(std::string_view expected) const;
  /// A path (non-empty string) resolved against the session's folder, to an existing file.
  /// `what` names the file kind in messages, e.g. "the MJCF scene".
  std::filesystem::path ExistingFile(std::string_view what) const;

 private:
  const Context* context_;
  const nlohmann::json* value_;
  std::string path_;
};

/// The name in `allowed` closest to `name`, if close enough to be a likely typo.
std::optional<std::string_view> ClosestName(std::string_view name,
                                            const std::vector<std::string_view>& allowed);

/// Short description of a JSON value for "found ..." messages, e.g. `a string ("abc")`.
std::string Describe(const nlohmann::json& value);

/// The keys of a field table, in table order.
template <typename Table>
std::vector<std::string_view> KeysOf(const Table& fields) {
  std::vector<std::string_view> keys;
  for (const auto& field : fields) keys.push_back(field.key);
  return keys;
}

/// The value of a choice enum (settings/choices.h) that `node` names; any other string is an
/// error naming the file, the key and the value, listing the choices.
template <typename E>
E ReadChoice(const Node& node) {
  const std::string name = node.String();
  if (const std::optional<E> value = settings::ParseChoice<E>(name)) return *value;
  node.Fail("unknown value \"" + name + "\"", "one of " + settings::ChoiceNames<E>());
}

/// Reads every field of `fields` present in `object` into `out` (absent ones keep their value).
template <typename Table, typename S>
void ReadFields(const Node& object, const Table& fields, S* out) {
  for (const auto& field : fields) {
    const std::optional<Node> node = object.Find(field.key);
    if (!node) continue;
    std::visit(
        [&](auto member) {
          auto& target = out->*member;
          using T = std::remove_reference_t<decltype(target)>;
          if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>) {
            target = node->Number(field.unit);
          } else if constexpr (std::is_same_v<T, int>) {
            target = node->Integer();
          } else if constexpr (std::is_same_v<T, bool>) {
            target = node->Bool();
          } else if constexpr (std::is_enum_v<T>) {
            target = ReadChoice<T>(*node);
          } else {
            target = node->String();
          }
        },
        field.member);
  }
}

/// Reads the optional block `key` of `parent` made only of the fields of `fields`.
template <typename Table, typename S>
void ReadBlock(const Node& parent, std::string_view key, const Table& fields, S* out) {
  const std::optional<Node> block = parent.Find(key);
  if (!block) return;
  block->ExpectObject(KeysOf(fields), "an object");
  ReadFields(*block, fields, out);
}

}  // namespace mrh::session::internal
