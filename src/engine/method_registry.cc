// SPDX-License-Identifier: Apache-2.0
// The registry of rendering methods: names → factories, filled at static-initialization time.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <map>
#include <mutex>

#include "mrh/core/error.h"
#include "mrh/engine/method.h"
#include "mrh/haptic/methods.h"
#include "mrh/physics/methods.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

std::map<std::string, MethodDescriptor>& Registry() {
  static std::map<std::string, MethodDescriptor> registry;
  return registry;
}

std::mutex& RegistryMutex() {
  static std::mutex mutex;
  return mutex;
}

void Add(MethodDescriptor descriptor) {
  const std::lock_guard lock(RegistryMutex());
  std::string name = descriptor.name;
  Registry()[std::move(name)] = std::move(descriptor);
}

}  // namespace

namespace {

// Each built-in method is a physics half (mrh_physics) and a haptic half (mrh_haptic) built
// from plain parameters: they share no object.
Method PointPenalty(const physics::MethodContext& c, bool single_rate) {
  const settings::RenderingSettings& r = c.settings->rendering;
  return Method{single_rate ? "single-rate" : "impulse",
                single_rate,
                physics::MakePointPenaltyPhysics(c),
                haptic::MakePointPenaltyHaptic(physics::PointerRadiusFor3Dof(c), r.stiffness,
                                               r.damping, r.friction),
                {},
                /*multi_pointer=*/true};
}

Method SingleRate(const physics::MethodContext& c) {
  return PointPenalty(c, true);
}

Method Impulse(const physics::MethodContext& c) {
  return PointPenalty(c, false);
}

// A method of several pointers: pointer 0's haptic half first, the others' in more_haptic.
Method PointerGroupMethod(std::string name, std::unique_ptr<physics::MethodPhysics> physics,
                          std::vector<std::unique_ptr<haptic::MethodHaptic>> group,
                          std::vector<std::string> status_bits) {
  Method method{std::move(name),        false,
                std::move(physics),     std::move(group[0]),
                std::move(status_bits), /*multi_pointer=*/true};
  for (std::size_t i = 1; i < group.size(); ++i) method.more_haptic.push_back(std::move(group[i]));
  return method;
}

// Every pointer's proxy settings (pointer 0's alone with one pointer): its geometry and gains,
// the device bound on one contact pair.
std::vector<render::ProxyRendererSettings> PointerProxySettings(const physics::MethodContext& c) {
  if (c.pointers.size() < 2) return {physics::ProxySettingsFor(c)};
  std::vector<render::ProxyRendererSettings> settings;
  for (const physics::PointerContext& p : c.pointers) {
    render::ProxyRendererSettings s = physics::ProxySettingsFor(*c.world, p.body, *p.rendering);
    s.max_pair_force = c.max_pair_force;
    settings.push_back(s);
  }
  return settings;
}

Method Proxy(const physics::MethodContext& c) {
  // The renderer settings first: they carry the session-key errors.
  const std::vector<render::ProxyRendererSettings> settings = PointerProxySettings(c);
  // Several pointers: the haptic halves share nothing (the objects move on the physics side).
  std::vector<std::unique_ptr<haptic::MethodHaptic>> group;
  for (const render::ProxyRendererSettings& s : settings)
    group.push_back(haptic::MakeProxyHaptic(s));
  return PointerGroupMethod("proxy-6dof", physics::MakeProxyPhysics(c), std::move(group), {});
}

// B5: proxy-6dof's physics half (reaction one step late, geometric IR), per-contact springs.
Method PenaltySum(const physics::MethodContext& c) {
  const settings::RenderingSettings& r = c.settings->rendering;
  return Method{
      "penalty-sum",
      false,
      physics::MakeProxyPhysics(c),
      haptic::MakePenaltySumHaptic(render::PenaltySumSettings{.k = r.stiffness, .d = r.damping}),
      {}};
}

// B3: single-rate; the tool is a free body of the world (session::LoadWorld).
Method VirtualCoupling(const physics::MethodContext& c) {
  return Method{"virtual-coupling",
                true,
                physics::MakeVirtualCouplingPhysics(c),
                haptic::MakeVirtualCouplingHaptic(physics::ResolveCouplingGains(c)),
                {}};
}

// B2: single-rate; the whole scene is one penalty simulation (session::LoadWorld switches
// MuJoCo's contacts off), the device connected directly to the pointer.
Method ContactVolume(const physics::MethodContext& c) {
  return Method{"contact-volume",
                true,
                physics::MakeContactVolumePhysics(c),
                haptic::MakeContactVolumeHaptic(),
                {}};
}

// rendering.local_model picks the local model: "contact" (default; free bodies and mechanisms)
// or the thesis' "perturbation".
Method LocalDynamics(const physics::MethodContext& c) {
  const settings::RenderingSettings& r = c.settings->rendering;
  if (physics::UsesContactLocalModel(c) && c.pointers.size() >= 2) {
    // Several pointers: one island, every pointer's reaction in the same tick.
    std::vector<haptic::PointerGains> gains;
    for (const physics::PointerContext& p : c.pointers) {
      gains.push_back(
          {p.radius, p.rendering->stiffness, p.rendering->damping, p.rendering->friction});
    }
    if (gains[0].radius <= 0.0) gains[0].radius = physics::PointerRadiusFor3Dof(c);
    for (std::size_t i = 1; i < gains.size(); ++i) {
      if (gains[i].radius > 0.0) continue;
      throw SceneError(fmt::format(
          "pointers[{}].body = '{}' has no sphere geom and pointers[{}].radius is not set, which "
          "method 'local-dynamics' (3-DOF) needs; set the radius (m)",
          i, c.world->body(c.pointers[i].body).name, i));
    }
    return PointerGroupMethod("local-dynamics", physics::MakeLocalContactPhysics(c),
                              haptic::MakeLocalContactHapticGroup(gains), {});
  }
  if (physics::UsesContactLocalModel(c)) {
    return Method{"local-dynamics",
                  false,
                  physics::MakeLocalContactPhysics(c),
                  haptic::MakeLocalContactHaptic(physics::PointerRadiusFor3Dof(c), r.stiffness,
                                                 r.damping, r.friction),
                  {}};
  }
  return Method{
      "local-dynamics",
      false,
      physics::MakeLocalDynamicsPhysics(c),
      haptic::MakeLocalDynamicsHaptic(physics::PointerRadiusFor3Dof(c), r.stiffness, r.damping),
      {}};
}

// The 6-DOF proxy against the neighbors' contact island simulated at the haptic rate.
Method LocalDynamics6dof(const physics::MethodContext& c) {
  const std::vector<render::ProxyRendererSettings> settings = PointerProxySettings(c);
  if (settings.size() >= 2) {
    // Several pointers: one island, every pointer's proxy with its own gains and geometry.
    return PointerGroupMethod("local-dynamics-6dof", physics::MakeLocalDynamics6dofPhysics(c),
                              haptic::MakeLocalDynamics6dofHapticGroup(settings), {});
  }
  return Method{"local-dynamics-6dof",
                false,
                physics::MakeLocalDynamics6dofPhysics(c),
                haptic::MakeLocalDynamics6dofHaptic(settings[0]),
                {}};
}

// The status-bit groups of the built-in methods' haptic halves.
constexpr StatusBitGroup kProxyBits{"proxy", render::kProxyStatusNames};
constexpr StatusBitGroup kLocalDynamicsBits{"local_dynamics", haptic::kLocalDynamicsStatusNames};

// The baselines B1–B5: one call per method.
void RegisterBaselines() {
  Add({"single-rate",
       "B1: world stepped at the haptic rate, 3-DOF penalty force applied every tick",
       {},
       SingleRate});
  Add({"impulse",
       "B4: conventional multi-rate, reaction impulse sent to the next physics step",
       {},
       Impulse});
  Add({"penalty-sum",
       "B5: proxy-6dof's geometric IR, wrench = sum of per-contact springs "
       "k·depth·n (stiffness grows with the contact count)",
       {{"penalty_sum", render::kPenaltySumStatusNames}},
       PenaltySum,
       {},
       {.torque = true}});
  Add({"virtual-coupling",
       "B3: pointer as a dynamic tool in MuJoCo at the haptic rate, spring-damper to "
       "the device (the tool's inertia is felt)",
       {{"virtual_coupling", haptic::kVirtualCouplingStatusNames}},
       VirtualCoupling,
       {.dynamic_pointer = true},
       {.stiffness = false, .coupling = true, .torque = true}});
  Add({"contact-volume",
       "B2: whole scene as one penalty simulation at the haptic rate, force "
       "k·(V/A)·n per intersection volume, anchored friction; device on the pointer",
       {{"contact_volume", haptic::kContactVolumeStatusNames}},
       ContactVolume,
       {.penalty_contacts = true},
       {.friction = true, .torque = true}});
}

// The thesis' methods (chapters 3 and 4) and their combination: one call per method.
void RegisterThesisMethods() {
  Add({"proxy-6dof",
       "Ch. 3: geometric IR + 6-DOF proxy with friction cones, reaction one step late",
       {kProxyBits},
       Proxy,
       {},
       {.friction = true, .rot_stiffness = true, .torque = true}});
  Add({"local-dynamics",
       "Ch. 4: neighbors simulated at the haptic rate; rendering.local_model "
       "\"contact\" (their contact island with friction, default) or "
       "\"perturbation\" (thesis: accelerance + bias)",
       {kLocalDynamicsBits},
       LocalDynamics});
  Add({"local-dynamics-6dof",
       "Ch. 3 + 4: proxy-6dof's geometric IR and 6-DOF proxy against the neighbors' "
       "contact island simulated at the haptic rate (the push moves them in the same "
       "tick, with rotation)",
       {kProxyBits, {"local_dynamics", haptic::kLocalDynamics6dofStatusNames}},
       LocalDynamics6dof,
       {},
       {.friction = true, .rot_stiffness = true, .torque = true}});
}

// Built-in methods register on first use: self-registering statics would be dropped by the
// linker from a static library.
void RegisterBuiltins() {
  static std::once_flag once;
  std::call_once(once, [] {
    RegisterBaselines();
    RegisterThesisMethods();
  });
}

}  // namespace

// The built-ins first, so that a program's method of the same name replaces the built-in one.
void RegisterMethod(MethodDescriptor descriptor) {
  RegisterBuiltins();
  Add(std::move(descriptor));
}

void RegisterMethod(const std::string& name, const std::string& summary, MethodFactory factory) {
  RegisterMethod(MethodDescriptor{name, summary, {}, std::move(factory)});
}

std::vector<std::string> StatusBitNames(std::span<const StatusBitGroup> groups) {
  std::vector<std::string> out;
  for (const StatusBitGroup& group : groups) {
    for (const StatusBitName& bit : group.names) {
      const auto i = static_cast<std::size_t>(std::countr_zero(bit.mask));
      if (out.size() <= i) out.resize(i + 1);
      out[i] = fmt::format("{}.{}", group.prefix, bit.name);
    }
  }
  return out;
}

std::optional<MethodDescriptor> FindMethod(const std::string& name) {
  RegisterBuiltins();
  const std::lock_guard lock(RegistryMutex());
  const auto it = Registry().find(name);
  if (it == Registry().end()) return std::nullopt;
  return it->second;
}

std::vector<MethodDescriptor> MethodDescriptors() {
  RegisterBuiltins();
  const std::lock_guard lock(RegistryMutex());
  std::vector<MethodDescriptor> out;
  for (const auto& [name, descriptor] : Registry()) out.push_back(descriptor);
  return out;
}

std::vector<std::pair<std::string, std::string>> ListMethods() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const MethodDescriptor& d : MethodDescriptors()) out.emplace_back(d.name, d.summary);
  return out;
}

Method MakeMethod(const std::string& name, const physics::MethodContext& context) {
  RegisterBuiltins();
  MethodDescriptor descriptor;
  {
    const std::lock_guard lock(RegistryMutex());
    const auto it = Registry().find(name);
    if (it == Registry().end()) {
      std::string known;
      for (const auto& [n, e] : Registry()) known += (known.empty() ? "" : ", ") + n;
      throw InvalidArgument(
          fmt::format("method = \"{}\" is unknown; expected one of: {}", name, known));
    }
    descriptor = it->second;
  }
  physics::CheckMaterialsUsed(*context.world, context.settings->rendering);
  Method method = descriptor.factory(context);
  if (!descriptor.status_bits.empty()) method.status_bits = StatusBitNames(descriptor.status_bits);
  return method;
}

}  // namespace mrh::engine
