// SPDX-License-Identifier: Apache-2.0
// Demo D2, articulated mechanisms: a desk lamp, a door, a drawer and a lever pushed by a scripted
// sphere pointer; the 20 ms local methods against single-rate at 1 ms (the reference).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::experiments::internal {

/// A joint of a D2 scene: a hinge (reported in degrees) or a slide (in millimetres).
struct D2Joint {
  std::string name;
  bool slide = false;
};

/// A mechanism: scenes/d2_<name>.xml. The pointer (sphere, r 0.015 m) moves at D2Options::speed
/// along the unit vector `direction`, its centre reaching `contact` (m, world: where it first
/// touches the resting mechanism) at D2Options::touch_time, pushes on for `push_time` and then
/// holds still. `joints` lists the
/// scene's joints in declaration order: the scene's qpos is exactly these coordinates (each
/// joint a hinge or a slide, the pointer a mocap body), which is how the driver reads them.
struct D2Case {
  std::string name;
  Vec3 contact = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  double push_time = 2.0;  ///< s of pushing after the touch
  std::vector<D2Joint> joints;
  /// The drawer: its slide's damping (N·s/m) and frictionloss (N), the analytic force d v + F of
  /// a steady push at `speed`. Zero elsewhere (no analytic reference).
  double damping = 0.0, frictionloss = 0.0;
};

/// One run of a case: a method at a physics step. The first run of D2Options::runs is the
/// reference; `checked` runs are held to the acceptance bars, the others reported.
struct D2Method {
  std::string method;
  double physics_dt = 0.02;  ///< s
  bool checked = true;
  /// "<method>" at 20 ms and for the reference, "<method>@<ms>ms" otherwise: the label in tables,
  /// file names and summary.json.
  std::string Label() const;
};

struct D2Options {
  std::vector<D2Case> cases;
  std::vector<D2Method> runs;
  double speed = 0.05;      ///< m/s, pointer push speed
  double touch_time = 0.5;  ///< s, the pointer reaches the surface
  /// s after the touch excluded from the push window: the impact bounces the mechanism off the
  /// pointer (in the reference too, for up to 0.5 s on the lever), and the bars compare the push.
  double settle = 0.6;
  double steady_from = 1.5;        ///< s after the touch: the drawer moves steadily
  double stiffness = 1200.0;       ///< N/m, rendering.stiffness
  double rendering_damping = 3.0;  ///< N·s/m, rendering.damping
  double after = 0.5;              ///< s simulated after the push ends
};

/// What one run recorded: every tick's rendered |f| (N), every physics step's joint coordinates
/// (rad or m, in D2Case::joints order).
struct D2Trace {
  std::vector<double> tick_t, force;
  std::vector<double> step_t;
  std::vector<std::vector<double>> q;  ///< q[step][joint]
};

/// A run's metrics over its case's push window [touch + settle, touch + push_time].
struct D2Metrics {
  double mean_force = 0.0;    ///< N
  double sd_force = 0.0;      ///< N
  double contact_lost = 0.0;  ///< share of the window's ticks with |f| = 0
  /// Largest RMS joint error against the reference over the window, over the case's hinges (deg)
  /// and over its slides (mm); 0 for the reference itself, and when there is no such joint.
  double hinge_rms_deg = 0.0, slide_rms_mm = 0.0;
  double steady_force = 0.0;  ///< N, mean |f| from touch + steady_from to the push's end
};

/// The acceptance bars of a run against the reference's metrics.
struct D2Bars {
  bool mean = false, sd = false, lost = false, joints = false;

  bool all() const { return mean && sd && lost && joints; }
};

D2Options DefaultD2Options();
/// `--full`: also the two local methods at 40 ms (reported, not checked).
D2Options FullD2Options();

/// Runs one case with one method (lockstep); writes runs/<case>_<label>_{force,joints}.csv under
/// `out` unless it is empty. @throws mrh::RuntimeError if the scene's qpos is not the case's
/// joints.
D2Trace RunD2Case(const std::filesystem::path& out, const D2Options& o, const D2Case& c,
                  const D2Method& m);

/// The metrics of `trace` over its push window; joint errors against `reference` (the reference
/// trace itself gives zeros).
D2Metrics AnalyzeD2(const D2Options& o, const D2Case& c, const D2Trace& trace,
                    const D2Trace& reference);

/// Mean |f| within 5 % of the reference's, sd ≤ 2× the reference's, contact lost ≤ the
/// reference's, hinge angles ≤ 2° RMS and slide positions ≤ 5 mm RMS from the reference's.
D2Bars D2Check(const D2Metrics& r, const D2Metrics& reference);

/// The analytic force of a steady push on case `c` at `speed`: d v + F (N).
inline double D2AnalyticForce(const D2Case& c, double speed) {
  return c.damping * speed + c.frictionloss;
}

/// Demo D2: every case × run; writes runs/*.csv, d2.csv, d2.md, d2.png (force and joints vs time
/// per mechanism) and summary.json. Returns 0 if every check passes: each checked run meets the
/// bars (D2Check) and the drawer's reference force is within 5 % of d v + F.
int RunD2(const std::filesystem::path& out, bool quiet);
int RunD2(const std::filesystem::path& out, bool quiet, const D2Options& options);
int RunD2Full(const std::filesystem::path& out, bool quiet);

}  // namespace mrh::experiments::internal
