// SPDX-License-Identifier: Apache-2.0
// The registry of rendering methods: names → factories, filled at static-initialization time.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <mutex>

#include "mrh/core/error.h"
#include "mrh/engine/method.h"
#include "local_contact_method.h"
#include "local_dynamics_method.h"
#include "penalty_sum_method.h"
#include "point_penalty_method.h"
#include "proxy_method.h"
#include "virtual_coupling_method.h"

namespace mrh::engine {
namespace {

struct Entry {
  std::string summary;
  MethodFactory factory;
};

std::map<std::string, Entry>& Registry() {
  static std::map<std::string, Entry> registry;
  return registry;
}

std::mutex& RegistryMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

namespace {

// Built-in methods register on first use: self-registering statics would be dropped by the
// linker from a static library.
void RegisterBuiltins() {
  static std::once_flag once;
  std::call_once(once, [] {
    RegisterMethod("single-rate",
                   "B1: world stepped at the haptic rate, 3-DOF penalty force applied every tick",
                   internal::MakeSingleRateMethod);
    RegisterMethod("impulse",
                   "B4: conventional multi-rate, reaction impulse sent to the next physics step",
                   internal::MakeImpulseMethod);
    RegisterMethod("proxy-6dof",
                   "Ch. 3: geometric IR + 6-DOF proxy with friction cones, reaction one step late",
                   internal::MakeProxyMethod);
    RegisterMethod("penalty-sum",
                   "B5: proxy-6dof's geometric IR, wrench = sum of per-contact springs k·depth·n "
                   "(stiffness grows with the contact count)",
                   internal::MakePenaltySumMethod);
    RegisterMethod("virtual-coupling",
                   "B3: pointer as a dynamic tool in MuJoCo at the haptic rate, spring-damper to "
                   "the device (the tool's inertia is felt)",
                   internal::MakeVirtualCouplingMethod);
    RegisterMethod("local-dynamics",
                   "Ch. 4: neighbors simulated at the haptic rate; rendering.local_model "
                   "\"contact\" (their contact island with friction, default) or "
                   "\"perturbation\" (thesis: accelerance + bias)",
                   internal::MakeLocalDynamicsAnyModel);
  });
}

}  // namespace

void RegisterMethod(const std::string& name, const std::string& summary, MethodFactory factory) {
  const std::lock_guard lock(RegistryMutex());
  Registry()[name] = Entry{summary, std::move(factory)};
}

std::vector<std::pair<std::string, std::string>> ListMethods() {
  RegisterBuiltins();
  const std::lock_guard lock(RegistryMutex());
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, entry] : Registry()) out.emplace_back(name, entry.summary);
  return out;
}

std::unique_ptr<Method> MakeMethod(const std::string& name, const MethodContext& context) {
  RegisterBuiltins();
  MethodFactory factory;
  {
    const std::lock_guard lock(RegistryMutex());
    const auto it = Registry().find(name);
    if (it == Registry().end()) {
      std::string known;
      for (const auto& [n, e] : Registry()) known += (known.empty() ? "" : ", ") + n;
      throw InvalidArgument(
          fmt::format("method = \"{}\" is unknown; expected one of: {}", name, known));
    }
    factory = it->second.factory;
  }
  return factory(context);
}

}  // namespace mrh::engine
