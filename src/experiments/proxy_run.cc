// SPDX-License-Identifier: Apache-2.0
// The proxy-6dof session runner of the chapter-3 experiments (RunProxySession): the method's
// output sampled after every tick, next to the engine's tick records.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

#include "experiments_impl.h"
#include "mrh/core/error.h"
#include "mrh/haptic/methods.h"
#include "mrh/report/report.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

// Forwards everything to the real device and, after each tick's command (HapticSide calls
// SetWrench right after Method::HapticTick), copies the method's output. Lockstep only: it
// allocates, which is fine off the real-time path.
class SamplingDevice final : public device::Device {
 public:
  explicit SamplingDevice(std::unique_ptr<device::Device> inner) : inner_(std::move(inner)) {}

  const device::Specifications& specifications() const override { return inner_->specifications(); }

  void Open() override { inner_->Open(); }

  void Close() override { inner_->Close(); }

  device::DeviceState Read(double t) noexcept override { return inner_->Read(t); }

  void SetWrench(const Wrench& w_D) noexcept override {
    inner_->SetWrench(w_D);
    if (method != nullptr) Sample();
  }

  const haptic::MethodHaptic* method = nullptr;  // proxy-6dof's haptic half
  std::vector<ProxyTick> samples;

 private:
  void Sample() noexcept {
    const render::ProxyOutput& out = *haptic::ProxyLastOutput(*method);
    const render::TickIr& tick_ir = *haptic::ProxyLastTickIr(*method);
    ProxyTick tick;
    tick.w_W = out.w_W;
    tick.X_WQ = out.X_WQ;
    tick.dr = out.dr;
    tick.dtheta = out.dtheta;
    tick.diagnostics = out.diagnostics;
    for (std::size_t k = 0; k < out.rows.size(); ++k) {
      if (out.row_info[k].kind != render::ProxyRowKind::kNormal) continue;
      const auto point = static_cast<std::size_t>(out.row_info[k].point);
      tick.constrained_p_PV.push_back(tick_ir.points[point].p_PV);
    }
    samples.push_back(std::move(tick));
  }

  std::unique_ptr<device::Device> inner_;
};

// Keeps the pointer pose and time of every tick and forwards to the CSV recorder, if any.
class PoseTap final : public physics::Recorder {
 public:
  explicit PoseTap(report::CsvRecorder* csv) : csv_(csv) {}

  void OnTick(const ir::TickRecord& tick) override {
    if (csv_ != nullptr) csv_->OnTick(tick);
    ticks.push_back(tick);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (csv_ != nullptr) csv_->OnStep(step, world);
  }

  std::vector<ir::TickRecord> ticks;

 private:
  report::CsvRecorder* csv_;
};

}  // namespace

ProxyRun RunProxySession(const session::Session& session, const std::filesystem::path& dir,
                         const std::string& title, bool quiet) {
  if (session.engine.method != "proxy-6dof") {
    throw InvalidArgument(
        fmt::format("{}: method = \"{}\"; expected \"proxy-6dof\" for a chapter-3 experiment",
                    session.file.string(), session.engine.method));
  }
  settings::EngineSettings settings = session.engine;
  settings.mode = settings::Mode::kLockstep;
  auto sampler = std::make_unique<SamplingDevice>(session::MakeDevice(session));
  SamplingDevice* device = sampler.get();
  engine::Engine engine(session::LoadWorld(session), std::move(sampler), session.device.calibration,
                        settings);
  device->method = &engine.haptic_method();
  device->samples.reserve(static_cast<std::size_t>(settings.duration / settings.haptic_dt) + 2);
  std::optional<report::CsvRecorder> csv;
  if (!dir.empty()) csv.emplace(dir);
  PoseTap tap(csv ? &*csv : nullptr);
  ProxyRun run;
  run.stats = engine.Run(&tap);
  // HapticSide::Stop sends one more (zero) command after the last tick: samples ⊇ ticks.
  run.ticks = std::move(device->samples);
  run.ticks.resize(std::min(run.ticks.size(), tap.ticks.size()));
  for (std::size_t i = 0; i < run.ticks.size(); ++i) {
    run.ticks[i].t = tap.ticks[i].t;
    run.ticks[i].X_WP = tap.ticks[i].X_WP;
  }
  if (csv) {
    csv->Close();
    report::WriteSummary(dir, run.stats, session.file.string(), session.scene.string());
    std::string why;
    if (!report::PlotReport(dir, title, &why) && !quiet) {
      std::cerr << "mrh: warning: no report plot in " << dir.string() << ": " << why << "\n";
    }
  }
  return run;
}

}  // namespace mrh::experiments::internal
