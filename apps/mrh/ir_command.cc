// SPDX-License-Identifier: Apache-2.0
// `mrh ir`: prints the geometric IR (thesis §3.2.1) for the pointer at a given world pose, as
// JSON.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "mrh/ir/snapshot.h"
#include "mrh/physics/geometric_ir.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::cli {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kIrFooter =
    R"(Prints the 6-DOF contact IR that the physics thread builds for the pointer at --pose, in
the session's initial state (scene + keyframe), as one line of JSON on stdout, world frame:
  {"pairs":[{"object":GEOM,"normal":[x,y,z],"plane_point":[x,y,z],"contacts":[[x,y,z],...],
             "depths":[d,...],"body":BODY,"pointer_geom":GEOM,"distance":D,"penetrating":B}],
   "status":[...]}
One pair per pointer geom / object geom within rendering.neighbor_distance. normal points from
the object to the pointer; depths are normal . (plane_point - contact) in m (> 0: below the
plane). A pair that is not penetrating has one contact: the pointer's closest point.

Examples:
  mrh ir scenes/cube_on_floor.json --pose 0 0 0.095 1 0 0 0
  mrh ir scenes/cube_on_floor.json --pose 0 0 0.137 0.9238795 0.3826834 0 0 | python3 -m json.tool
  mrh ir session.json --pose 0.1 0 0.2 1 0 0 0 --set rendering.neighbor_distance=0.1
)";

Pose ParsePose(const std::vector<double>& v) {
  if (v.size() != 7) {
    throw InvalidArgument(fmt::format(
        "--pose: got {} numbers; expected 7: x y z qw qx qy qz (m, unit quaternion)", v.size()));
  }
  for (const double x : v) {
    if (!std::isfinite(x)) {
      throw InvalidArgument(
          fmt::format("--pose: {} is not a finite number; expected 7 numbers "
                      "x y z qw qx qy qz",
                      x));
    }
  }
  // The rules of session poses (mrh/core/validate.h): any nonzero quaternion, normalised.
  const Pose X{Vec3(v[0], v[1], v[2]), Quat(v[3], v[4], v[5], v[6])};
  const Problem problem = PoseProblem(X.p, X.q);
  if (problem) throw InvalidArgument("--pose: " + problem.Text());
  return Pose{X.p, X.q.normalized()};
}

std::string BodyName(const world::World& world, int body) {
  const std::string& name = world.body(body).name;
  if (!name.empty()) return name;
  return body == 0 ? "world" : fmt::format("body {}", body);
}

// Pairs are per geom; an unnamed geom is called after its body, which users name more often.
std::string GeomName(const world::World& world, int geom) {
  const world::GeomInfo& info = world.geom(geom);
  if (!info.name.empty()) return info.name;
  if (!world.body(info.body).name.empty()) return world.body(info.body).name;
  return fmt::format("geom {}", geom);
}

Json Vector(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

Json StatusNames(std::uint32_t status) {
  Json names = Json::array();
  if (status & ir::kStatusBodiesFull) names.push_back("bodies_full");
  if (status & ir::kStatusPairsFull) names.push_back("pairs_full");
  if (status & ir::kStatusPointsFull) names.push_back("points_full");
  if (status & ir::kStatusRegionFallback) names.push_back("region_fallback");
  return names;
}

Json PairJson(const world::World& world, const Pose& X_WP, const ir::PhysicsSnapshot& s,
              const ir::GeometricPair& pair) {
  const ir::BodyMotion& body = s.bodies[static_cast<std::size_t>(pair.motion)];
  Json contacts = Json::array();
  Json depths = Json::array();
  for (int k = pair.first_point; k < pair.first_point + pair.num_points; ++k) {
    const ir::PairPoint& point = s.points[static_cast<std::size_t>(k)];
    contacts.push_back(Vector(X_WP * point.p_PV));
    depths.push_back(point.depth);
  }
  Json j;
  j["object"] = GeomName(world, pair.object_geom);
  j["normal"] = Vector(pair.n_W);
  j["plane_point"] = Vector(body.X_WB * pair.p_BC);
  j["contacts"] = std::move(contacts);
  j["depths"] = std::move(depths);
  j["body"] = BodyName(world, body.body);
  j["pointer_geom"] = GeomName(world, pair.pointer_geom);
  j["distance"] = pair.distance;
  j["penetrating"] = pair.penetrating;
  return j;
}

}  // namespace

CLI::App* AddIrCommand(CLI::App& app, IrOptions* o) {
  CLI::App* command = app.add_subcommand(
      "ir", "Print the 6-DOF contact IR (planes, contact points, depths) at a pointer pose");
  command->add_option("SESSION", o->session, "Session file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--pose", o->pose,
                   "Pointer body pose in the world: x y z (m), then unit quaternion qw qx qy qz")
      ->expected(7)
      ->required()
      ->type_name("NUM");
  AddSetOption(*command, &o->sets);
  command->footer(kIrFooter);
  return command;
}

int IrCommand(const IrOptions& o) {
  const Pose X_WP = ParsePose(o.pose);
  const session::Session s = session::LoadSession(o.session, o.sets);
  world::World world = session::LoadWorld(s);
  const int pointer = world.pointer_body();
  if (pointer < 0) {
    throw SceneError(
        fmt::format("{}: no pointer body; expected `pointer.body` to name a mocap "
                    "body of the scene",
                    o.session.string()));
  }
  world.SetMocapPose(pointer, X_WP);
  const auto snapshot = std::make_unique<ir::PhysicsSnapshot>();
  physics::BuildGeometricIr(world, pointer, s.engine.rendering, X_WP, snapshot.get());

  Json pairs = Json::array();
  for (const ir::GeometricPair& pair : snapshot->pairs) {
    pairs.push_back(PairJson(world, X_WP, *snapshot, pair));
  }
  Json out;
  out["pairs"] = std::move(pairs);
  out["status"] = StatusNames(snapshot->status);
  fmt::print("{}\n", out.dump());
  return kExitOk;
}

}  // namespace mrh::cli
