// SPDX-License-Identifier: Apache-2.0
// Method `local-dynamics-6dof`: the haptic half — the 6-DOF proxy rendered
// against planes fixed on the neighbors while the neighbors' contact island is simulated at 1 kHz.
#pragma once

#include <array>
#include <cstdint>

#include "mrh/haptic/method_haptic.h"
#include "mrh/haptic/methods.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/tick_ir.h"

namespace mrh::haptic::internal {

/// TickOutput::status bit of local-dynamics-6dof beyond render::ProxyStatusBits (bits 0–2): an
/// island body's local state became non-finite and was stopped.
inline constexpr std::uint32_t kLocal6dofBodyFault = kLocalDynamics6dofBodyFault;

/// The haptic half of `local-dynamics-6dof`. Per tick (RT-safe: fixed capacity, no allocation,
/// lock, throw or I/O):
///  1. the geometric IR is evaluated as in proxy-6dof (IrInterpolator, α = min(1, (j+1)/n));
///  2. every pair whose object is a body of the snapshot's ir::LocalContactModel island is
///     re-posed on that body's CURRENT local pose: its plane point p_BC follows the locally
///     simulated body (a round object's, ir::GeometricPair::round, follows its COM without
///     turning), and its normal turns with the body whose face it is
///     (ir::GeometricPair::normal_frame): the object's (an object face), the pointer's (an
///     object edge or vertex, or a cylinder's side, on a pointer face: held in the object, it
///     would tilt the plane by the object's turn against the pointer face the contact lies on
///     and pull the object back toward the snapshot's orientation, a step late), or neither (a
///     round object); the points' depths are recomputed. Static pairs and non-island bodies
///     keep the interpolated IR. The normal is blended over the period (thesis §3.2.2, α as in
///     step 1) from the one the pair was last rendered with to the snapshot's, in its frame, so
///     it is continuous across the snapshot switch, as the interpolator's is;
///  3. render::ProxyRenderer solves the proxy (eq. 3.4–3.10) and renders eq. 3.7–3.8;
///  4. each island pair's reaction, the renderer's wrench (render::ProxyPairReaction: force in N
///     and moment about the COM in N·m, world), is applied to the local body in the same tick
///     (LocalContactSolver::AddForce: the force at the COM plus a couple), and the island is
///     stepped (gravity, its own contacts with friction). Every non-static pair's reaction is
///     summed into the period's impulses for the global step. So action = reaction holds in force
///     and in moment with the wrench the user feels, as in proxy-6dof.
/// EndPeriod reports the impulses and every island body's local end state (eq. 4.16–4.17), which
/// the physics half (physics::internal::LocalDynamics6dofPhysics) writes into the world.
/// One instance per pointer; haptic thread only.
class LocalDynamics6dofHaptic final : public MethodHaptic {
 public:
  /// All buffers are sized here. @throws mrh::InvalidArgument from settings.Validate(). Not
  /// RT-safe.
  explicit LocalDynamics6dofHaptic(const render::ProxyRendererSettings& settings,
                                   const render::LocalContactSolverSettings& solver = {});

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  /// The last tick's renderer output and the (re-posed) IR it rendered; valid until the next
  /// HapticTick. Haptic thread, or between lockstep ticks.
  const render::ProxyOutput& last_output() const noexcept { return output_; }

  const render::TickIr& last_tick_ir() const noexcept { return tick_ir_; }

  /// The haptic side's island (haptic thread; tests read it between ticks).
  const render::LocalContactSolver& solver() const noexcept { return solver_; }

  /// Several pointers: this half renders its own pointer against `owner`'s island (null: its
  /// own, it is the owner). The owner (pointer 0, ticked first) adopts the island, every pointer
  /// re-poses its planes on it and adds its reactions, and the half with `steps` (the last
  /// pointer, ticked last) steps it once per tick with all of them and reports its end states.
  /// The owner must outlive the others. Setup only.
  void ShareIsland(LocalDynamics6dofHaptic* owner, bool steps) noexcept {
    owner_ = owner;
    steps_ = steps;
  }

 private:
  render::LocalContactSolver& island() noexcept { return owner_ ? owner_->solver_ : solver_; }

  /// Maps the snapshot's motions to the island's bodies, or to none while the island holds
  /// another step's model (a follower's snapshot arrived a tick apart from the owner's).
  void MapMotions() noexcept;

  /// The frame an island pair's normal is held in over the period: the world (a round object),
  /// the object's body frame or the pointer's (ir::GeometricPair::normal_frame).
  enum class Frame : std::uint8_t { kWorld, kBody, kPointer };

  void RePoseOnLocalBodies(double alpha, const Pose& X_WP) noexcept;
  void RememberRenderedNormals(const Pose& X_WP) noexcept;
  /// n_W in `frame` with the last rendered tick's pointer pose, or the body orientation q_WB.
  Vec3 InFrame(Frame frame, const Vec3& n_W, const Quat& q_WB) const noexcept;
  void PushLocalBodies() noexcept;
  void AddWrench(std::size_t l, const Wrench& w, const Vec3& c) noexcept;

  render::IrInterpolator interpolator_;
  render::ProxyRenderer renderer_;
  render::LocalContactSolver solver_;
  LocalDynamics6dofHaptic* owner_ = nullptr;  ///< several pointers: the island's owner
  bool steps_ = true;                         ///< this half steps the island each tick
  std::int64_t snapshot_step_ = -2;           ///< step of the adopted snapshot
  std::size_t snapshot_bodies_ = 0;           ///< its number of bodies
  std::int64_t adopted_step_ = -2;            ///< snapshot step of the island's model (owner)
  std::int64_t mapped_step_ = -2;             ///< island step local_of_motion_ was mapped to
  render::TickIr tick_ir_;
  render::ProxyOutput output_;
  double tick_dt_ = 0.0;
  // Per snapshot motion: the island body index, or -1.
  std::array<int, ir::kMaxNeighborBodies> local_of_motion_{};
  // Per tick pair (the interpolator's output order): the frame its normal is held in, the
  // snapshot's normal in that frame, and the one the blend starts from (the last rendered one of
  // the same pair, in that frame; the snapshot's own for a new pair).
  std::array<Frame, ir::kMaxGeometricPairs> frame_{};
  std::array<Vec3, ir::kMaxGeometricPairs> n_F_{};
  std::array<Vec3, ir::kMaxGeometricPairs> start_n_F_{};
  // What the last tick rendered, per tick pair: its key, frame, normal in that frame and in the
  // world, and its body's orientation (and the pointer's), the start of the next snapshot's
  // blends.
  std::array<std::uint64_t, ir::kMaxGeometricPairs> rendered_key_{};
  std::array<Frame, ir::kMaxGeometricPairs> rendered_frame_{};
  std::array<Vec3, ir::kMaxGeometricPairs> rendered_n_{};
  std::array<Vec3, ir::kMaxGeometricPairs> rendered_n_W_{};
  std::array<Quat, ir::kMaxGeometricPairs> rendered_q_WB_{};
  Quat rendered_q_WP_ = Quat::Identity();
  std::size_t rendered_count_ = 0;
  // The plane point of a round object relative to its COM (world).
  std::array<Vec3, ir::kMaxGeometricPairs> c_Cm_{};
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
};

}  // namespace mrh::haptic::internal
