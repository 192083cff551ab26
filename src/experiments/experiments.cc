// SPDX-License-Identifier: Apache-2.0
// The experiment registry: names → drivers.
#include "mrh/experiments/experiments.h"

#include <fmt/format.h>

#include "d2_impl.h"
#include "experiments_impl.h"
#include "mrh/core/error.h"

namespace mrh::experiments {
namespace {

struct Entry {
  const char* name;
  const char* summary;
  int (*run)(const std::filesystem::path&, bool);
  int (*run_full)(const std::filesystem::path&, bool) = nullptr;  ///< --full; null: as run
};

constexpr Entry kExperiments[] = {
    {"t3.1", "6-DOF proxy: cube edge -> roll -> face on a floor, thesis gains (figs. 3.10-3.11)",
     internal::RunT31},
    {"t3.2", "6-DOF proxy friction: strokes and twist with mu = 0.5 (figs. 3.13-3.14)",
     internal::RunT32},
    {"t3.3",
     "real-time computation ratio vs cubes: proxy-6dof, contact-volume (B2), virtual-coupling "
     "(B3), penalty-sum (B5) (figs. 3.15-3.16); --full: each method to its real-time limit",
     internal::RunT33, internal::RunT33Full},
    {"t3.4",
     "6-DOF proxy tick time vs contact points, N-gon prism, with/without friction "
     "(fig. 3.17)",
     internal::RunT34},
    {"t3.5", "6-DOF proxy rotation-weight sweep: free-vertex penetration and torque (fig. 3.18)",
     internal::RunT35},
    {"t4.1",
     "impulse delivered to a moving 60 kg cube per method, mass/speed sweep (fig. 4.13, tab. 4.3)",
     internal::RunT41},
    {"t4.2",
     "2AFC mass study with simulated observers: PSE per method, predicted table 4.4 "
     "(figs. 4.14-4.15)",
     internal::RunT42},
    {"t4.3",
     "computation occupancy per physics step, 1-100 cubes with/without friction (figs. "
     "4.17-4.20); --full: 1-1000 frictionless, 1-500 with friction",
     internal::RunT43, internal::RunT43Full},
    {"t4.4", "felt mass steps up as cubes join a pushed line; an edge push turns the cube",
     internal::RunT44},
    {"t4.5", "haptic tick cost and physics occupancy vs 1-128 neighbors simulated locally",
     internal::RunT45},
    {"t4.6",
     "6x6 accelerance estimates (thesis 1+18 runs, 2-run, analytic island) vs converged MuJoCo: "
     "accuracy, cost per physics step, occupancy with 10 cubes; --full: 10 and 100 cubes",
     internal::RunT46, internal::RunT46Full},
    {"t3.6",
     "a box pointer pushes, turns, tips and presses boxes on a floor: proxy-6dof at 1 and 20 ms, "
     "local-dynamics-6dof at 20 ms",
     internal::RunT36},
    {"t3.7",
     "6-DOF methods on spheres, capsules, cylinders, ellipsoids, meshes and compounds, centred "
     "and off centre, vs virtual coupling at 1 ms and mechanics; --full: the sphere pointer too",
     internal::RunT37, internal::RunT37Full},
    {"t4.push",
     "pushing resting boxes across a floor with friction: force and trajectory vs single-rate",
     internal::RunT4Push},
    {"grasp",
     "two fingertips squeeze a box, lift it 5 cm, hold it and put it down; two hands push two "
     "boxes apart; a squeezed box dragged sideways: "
     "local-dynamics and impulse at 20 ms vs single-rate at 1 ms",
     internal::RunGrasp},
    {"d1",
     "demo D1: a simulated hand sweeps through 80 boxes, spheres, capsules and meshes on a table "
     "in real time (local-dynamics): haptic rate, overruns, step times, peak memory; --full: 60 s",
     internal::RunD1, internal::RunD1Full},
    {"d2",
     "demo D2: a desk lamp, a door, a drawer and a lever (hinge and slide joints) pushed at "
     "0.05 m/s: local-dynamics and local-dynamics-6dof at 20 ms vs single-rate at 1 ms; "
     "--full: also at 40 ms",
     internal::RunD2, internal::RunD2Full},
    {"d3",
     "demo D3: taps on aluminium, wood and rubber at three speeds; the contact transient's f, B "
     "and a*v fitted back, and each material's stiffness at rest",
     internal::RunD3},
    {"t4.latency", "haptic ticks from the user's force onset to the touched object's response",
     internal::RunLatency},
};

}  // namespace

int Run(const std::string& name, const std::filesystem::path& out, bool quiet) {
  return Run(name, out, quiet, /*full=*/false);
}

int Run(const std::string& name, const std::filesystem::path& out, bool quiet, bool full) {
  for (const Entry& e : kExperiments) {
    if (name == e.name)
      return full && e.run_full != nullptr ? e.run_full(out, quiet) : e.run(out, quiet);
  }
  std::string known;
  for (const Entry& e : kExperiments) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw InvalidArgument(
      fmt::format("experiment '{}' is unknown; expected one of: {}", name, known));
}

std::vector<std::pair<std::string, std::string>> List() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Entry& e : kExperiments) out.emplace_back(e.name, e.summary);
  return out;
}

}  // namespace mrh::experiments
