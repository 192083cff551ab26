// SPDX-License-Identifier: Apache-2.0
// Run output: ticks.csv, bodies.csv, steps.csv, summary.json and report.png in one folder.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "mrh/engine/engine.h"

namespace mrh::report {

/// Writes ticks.csv, bodies.csv and steps.csv into `dir` as records arrive (buffered). Not
/// RT-safe: the engine calls it from its non-RT side.
///
/// bodies.csv has one row per moving body per physics step:
/// `t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,cx,cy,cz` — t (s), the body's name, its body
/// frame's origin (m) and orientation (body → world) as in the scene's MJCF, its centre of mass's
/// linear velocity (m/s) and its angular velocity (rad/s), both world frame, and the centre of
/// mass's position (m, world frame).
class CsvRecorder : public engine::Recorder {
 public:
  /// Creates `dir` if needed. @throws mrh::RuntimeError if a file cannot be opened.
  explicit CsvRecorder(const std::filesystem::path& dir);
  ~CsvRecorder() override;
  void OnTick(const engine::TickRecord& tick) override;
  void OnStep(const engine::StepRecord& step, const world::World& world) override;
  /// Flushes and closes the files. @throws mrh::RuntimeError on a write error.
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes summary.json (method, mode, rates, ticks, overruns, jitter, max force, per-body
/// impulses, faults, warnings) into `dir`. `extra` names the session and scene.
void WriteSummary(const std::filesystem::path& dir, const engine::RunStats& stats,
                  const std::string& session_file, const std::string& scene_file);

/// Plots force/torque and pointer traces from dir/ticks.csv into dir/report.png with gnuplot.
/// A fourth panel plots the objects' x and z from dir/bodies.csv. `renders_torque` false (a
/// 3-DOF method) labels the torque panel "(3-DOF method: no torque rendered)".
/// Returns false (and a reason in *why) if gnuplot is missing or fails; the run still counts.
bool PlotReport(const std::filesystem::path& dir, const std::string& title, std::string* why,
                bool renders_torque = true);

/// Runs gnuplot on dir/script (working directory `dir`) and checks that it wrote dir/png.
/// Returns false with a one-line reason in *why if gnuplot is missing or fails.
bool RunGnuplotScript(const std::filesystem::path& dir, const std::string& script,
                      const std::string& png, std::string* why);

}  // namespace mrh::report
