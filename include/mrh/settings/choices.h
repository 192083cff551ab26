// SPDX-License-Identifier: Apache-2.0
// The string choices of the session's `rendering` block as enums, with their session names.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mrh::settings {

/// rendering.torque_model: how the 6-DOF proxy's wrench relates to its contacts.
enum class TorqueModel {
  kContact,  ///< "contact": R_w = (k_r / k_t)·I, every force a contact force (default)
  kThesis,   ///< "thesis": eq. 3.8 with the rotation weight R_w
};

/// rendering.proxy_solver: the algorithm of the proxy LCP (eq. 3.4).
enum class ProxySolver {
  kActiveSet,  ///< "active-set": exact dual active-set method (default)
  kPgs,        ///< "pgs": the thesis' projected Gauss–Seidel, eq. 3.6
};

/// rendering.proxy_reaction: how proxy-6dof's physics step applies the reaction.
enum class ProxyReaction {
  kLocal,    ///< "local": a physics-side proxy run at the haptic rate over the step (default)
  kImpulse,  ///< "impulse": the thesis' constant wrench J/Δt^G of the haptic period
};

/// rendering.local_model: the local model of local-dynamics.
enum class LocalModel {
  kContact,       ///< "contact": the neighbors' contact island with friction (default)
  kPerturbation,  ///< "perturbation": the thesis' accelerance A and bias b, eq. 4.3–4.10
};

/// One value of a choice and its name in the session file.
template <typename E>
struct Choice {
  E value;
  std::string_view name;
};

inline constexpr std::array<Choice<TorqueModel>, 2> kTorqueModels{
    {{TorqueModel::kContact, "contact"}, {TorqueModel::kThesis, "thesis"}}};
inline constexpr std::array<Choice<ProxySolver>, 2> kProxySolvers{
    {{ProxySolver::kActiveSet, "active-set"}, {ProxySolver::kPgs, "pgs"}}};
inline constexpr std::array<Choice<ProxyReaction>, 2> kProxyReactions{
    {{ProxyReaction::kLocal, "local"}, {ProxyReaction::kImpulse, "impulse"}}};
inline constexpr std::array<Choice<LocalModel>, 2> kLocalModels{
    {{LocalModel::kContact, "contact"}, {LocalModel::kPerturbation, "perturbation"}}};

/// The table of each choice enum, found by overload on the enum type.
constexpr std::span<const Choice<TorqueModel>> ChoicesOf(TorqueModel) {
  return kTorqueModels;
}

constexpr std::span<const Choice<ProxySolver>> ChoicesOf(ProxySolver) {
  return kProxySolvers;
}

constexpr std::span<const Choice<ProxyReaction>> ChoicesOf(ProxyReaction) {
  return kProxyReactions;
}

constexpr std::span<const Choice<LocalModel>> ChoicesOf(LocalModel) {
  return kLocalModels;
}

/// The session name of `value` ("contact", "pgs", ...); "" for a value outside the table.
template <typename E>
constexpr std::string_view ChoiceName(E value) {
  for (const Choice<E>& c : ChoicesOf(E{})) {
    if (c.value == value) return c.name;
  }
  return {};
}

/// The value named `name`; nullopt if the table has no such name (case-sensitive).
template <typename E>
constexpr std::optional<E> ParseChoice(std::string_view name) {
  for (const Choice<E>& c : ChoicesOf(E{})) {
    if (c.name == name) return c.value;
  }
  return std::nullopt;
}

/// The names of E's values for messages: "\"contact\", \"thesis\"".
template <typename E>
std::string ChoiceNames() {
  std::string out;
  for (const Choice<E>& c : ChoicesOf(E{})) {
    out += (out.empty() ? "\"" : ", \"") + std::string(c.name) + "\"";
  }
  return out;
}

}  // namespace mrh::settings
