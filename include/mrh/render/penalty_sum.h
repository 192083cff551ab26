// SPDX-License-Identifier: Apache-2.0
// Baseline B5 (Berkelman & Hollis 2000, thesis ref. [43], §3.1.1): independent per-contact penalty
// springs summed over the geometric IR's contact points.
#pragma once

#include <array>
#include <cstdint>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"
#include "mrh/core/status_bits.h"
#include "mrh/ir/snapshot.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/tick_ir.h"

namespace mrh::render {

/// Gains of the per-contact penalty sum.
struct PenaltySumSettings {
  double k = 1000.0;  ///< spring per contact point (N/m, >= 0)
  double d = 0.0;     ///< damper per contact point on the depth rate (N·s/m, >= 0)

  /// @throws mrh::InvalidArgument naming the field and its value. Not RT-safe.
  void Validate() const;
};

/// The names of the status bits a PenaltySum tick sets (a subset of ProxyStatusBits).
inline constexpr std::array<StatusBitName, 1> kPenaltySumStatusNames{{
    {kProxyStatusBadInput, "bad_input"},
}};
static_assert(ValidStatusBitNames(kPenaltySumStatusNames));

/// What one PenaltySum tick produces.
struct PenaltySumOutput {
  /// Wrench on the user's hand, world frame: f = Σᵢ fᵢ nᵢ (N) and τ = Σᵢ rᵢ × fᵢ nᵢ (N·m) about
  /// the pointer origin X_WP.p, with fᵢ = max(0, k δᵢ + d δ̇ᵢ) for every penetrating point (δᵢ > 0)
  /// and rᵢ = v_W,i − X_WP.p; k and d are the pair's material's (TickPair::material) when it
  /// has one, else the settings'.
  Wrench w_W;
  /// One entry per TickIr pair, same order: −(Σ_pair fᵢ nᵢ) on the object, moment about its COM
  /// (zero for a static pair or one without penetrating points). Summed over all pairs (static
  /// ones included) that is minus the rendered force; the moments are taken about each COM.
  FixedVector<ProxyPairReaction, ir::kMaxGeometricPairs> reactions;
  int contacts = 0;          ///< penetrating points
  std::uint32_t status = 0;  ///< kProxyStatusBadInput on non-finite input (zero wrench)
};

/// The pure wrench law of B5 with no damping: f = Σᵢ k δᵢ nᵢ, τ = Σᵢ rᵢ × (k δᵢ nᵢ) over the
/// points of `ir` with δᵢ > 0 (depth and normal from the tick IR; rᵢ from X_WP.p). RT-safe.
Wrench PenaltySumWrench(const TickIr& ir, const Pose& X_WP, double k) noexcept;

/// Haptic-thread renderer of B5 with per-point damping. δ̇ᵢ is the finite difference of the
/// point's depth over one tick when the previous tick had the same (pair key, point index) at the
/// same position in its list of penetrating points, else 0 (a new contact, or one after a
/// snapshot change, starts undamped). One instance per pointer; haptic thread
/// only; no allocation after construction.
class PenaltySumRenderer {
 public:
  /// @throws mrh::InvalidArgument from settings.Validate(). Not RT-safe.
  explicit PenaltySumRenderer(const PenaltySumSettings& settings);

  /// Renders one tick. @param ir the tick's IR evaluated at X_WP. @param dt haptic period (s,
  /// > 0). On non-finite input the output is zero with kProxyStatusBadInput. RT-safe.
  void Tick(const TickIr& ir, const Pose& X_WP, double dt, PenaltySumOutput* out) noexcept;

  /// Forgets the previous depths. RT-safe.
  void Reset() noexcept { previous_count_ = 0; }

  const PenaltySumSettings& settings() const noexcept { return settings_; }

 private:
  double DepthRate(std::uint64_t id, std::size_t index, double depth, double dt) const noexcept;
  void AddPair(const TickIr& ir, const TickPair& pair, const Pose& X_WP, double dt,
               std::size_t* count, PenaltySumOutput* out) noexcept;

  PenaltySumSettings settings_;
  std::array<std::uint64_t, ir::kMaxPairPoints> ids_{};
  std::array<double, ir::kMaxPairPoints> depths_{};
  std::array<std::uint64_t, ir::kMaxPairPoints> previous_ids_{};
  std::array<double, ir::kMaxPairPoints> previous_depths_{};
  std::size_t previous_count_ = 0;
};

}  // namespace mrh::render
