// SPDX-License-Identifier: Apache-2.0
// Export of the contact local model: the pointer neighbors' contact island with its
// contact rows, from MuJoCo's collision detection at the end of a physics step.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mrh/ir/local_contact.h"
#include "mrh/world/world.h"

namespace mrh::world {

/// Builds ir::LocalContactModel from a World. Physics thread only; not RT-safe (buffers sized
/// from the model at construction; Export() does not allocate after that).
class ContactExporter {
 public:
  /// @param world must outlive the exporter.
  /// @param margin extra collision margin (m, >= 0) for the export: contacts whose gap is below
  ///   it are exported, so contacts that close during the next haptic period are in the model.
  ///   A free body's geoms get more when they move fast: the distance their points may travel
  ///   in two physics steps (the rows' horizon).
  /// @param whole_world collide the whole world (the reference for tests); by default only the
  ///   geoms that may touch the island take part (the same contacts of island bodies, a
  ///   fraction of the cost in a large world).
  /// @param articulated also simulate mechanisms: a body with one hinge, slide or ball joint, two
  ///   or three orthogonal slides, or none (riding on a moving parent) joins the island with every
  ///   moving body of its kinematic tree, and the tree's joints are exported (ir::LocalJoint). A
  ///   tree with a body of another joint configuration stays the static environment, named in
  ///   warnings().
  explicit ContactExporter(World* world, double margin = 0.005, bool whole_world = false,
                           bool articulated = false);

  /// The island of `seeds` (world body ids of the pointer's dynamic neighbors; `motions` their
  /// indices into the snapshot's bodies, same length) at the world's current state: every
  /// island body (IsIslandBody) reachable through contacts, up to ir::kMaxLocalBodies, and every
  /// contact of an island body. Bodies beyond the capacity, static, mocap and other bodies
  /// are the static environment of the model. Recomputes collisions at the current state (the
  /// contacts MuJoCo holds after mj_step are those of the step's start) around the island, so
  /// the world holds only those contacts afterwards (World::num_contacts); the next
  /// World::Step recomputes them anyway, so stepping is unaffected. Returns ir::StatusBits for
  /// overflow.
  std::uint32_t Export(std::span<const int> seeds, std::span<const int> motions,
                       ir::LocalContactModel* out);

  /// True if `body` can be simulated by the contact local model (a free-jointed body).
  bool IsFreeBody(int body) const;

  /// True if `body` joins the island: a free body, or with `articulated` a body of a
  /// mechanism whose every moving body has a supported joint configuration.
  bool IsIslandBody(int body) const;

  /// One line per moving body the local simulation cannot take (with `articulated`): the body,
  /// its joint and why; the world steps it and the island treats it as static.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  double GeomMargin(int g) const;
  void Collide(bool refresh_kinematics);
  bool Reaches(int geom, int other_geom) const;
  bool NearIsland(int geom) const;
  void CloseNear();
  void DisableFarGeoms();
  void RestoreFilters();
  void SetNear(std::span<const int> seeds);
  void AddNear(int body);
  void ClearIsland(ir::LocalContactModel* out);
  std::uint32_t GrowIsland(ir::LocalContactModel* out);
  std::uint32_t AddRows(ir::LocalContactModel* out);
  bool AddBody(int body, int motion, ir::LocalContactModel* out);
  bool AddOne(int body, int motion, ir::LocalContactModel* out);
  void ClassifyBodies();
  std::string Unsupported(int body) const;
  double JointedMargin(int g, double margin) const;
  std::uint32_t AddJoints(ir::LocalContactModel* out) const;

  World* world_;
  double margin_;
  bool whole_world_;
  std::vector<double> saved_margin_;       // per geom
  std::vector<double> margins_;            // per geom, this export (GeomMargin)
  std::vector<int> saved_filter_;          // per geom: contype, conaffinity
  std::vector<double> saved_body_margin_;  // per body: MuJoCo's body_margin (broadphase bound)
  std::vector<char> near_;        // per world body: its neighbourhood takes part in Collide
  std::vector<int> near_bodies_;  // the bodies with near_ set
  std::vector<int> local_index_;  // per world body: index into out->bodies, or -1
  bool articulated_;
  std::size_t island_joints_ = 0;  // joints the island's mechanisms need, this export
  std::vector<char> mechanism_;    // per world body: a jointed body of a supported tree
  std::vector<std::string> warnings_;
};

}  // namespace mrh::world
