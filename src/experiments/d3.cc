// SPDX-License-Identifier: Apache-2.0
// Demo D3, material display: taps on aluminium, wood and rubber at three speeds; the contact
// transient's f, B and a·v fitted back from the rendered force, and each block's stiffness at rest.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "d3_fit.h"
#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"

namespace mrh::experiments::internal {
namespace {

// scenes/d3.xml: block tops at z = 0.06 m, centres along x; 5 mm sphere pointer.
constexpr double kTop = 0.06;         // m
constexpr double kRadius = 0.005;     // m
constexpr double kAbove = 0.005;      // m, start of a tap above the contact
constexpr double kDepth = 0.001;      // m, held depth at rest
constexpr double kHold = 0.5;         // s, at rest after the stop: every transient decays first
constexpr double kRestWindow = 0.05;  // s, the end of the hold averaged for the resting force
constexpr double kFitWindow = 0.3;    // s after the stop that the fit uses
const std::vector<double> kSpeeds{0.05, 0.1, 0.2};  // m/s

struct Block {
  const char* material;
  double x;  // m
};

const std::vector<Block> kBlocks{{"aluminium", -0.15}, {"wood", 0.0}, {"rubber", 0.15}};
// Acceptance: f within 5 %, B within 25 %, a·v ∝ v within 15 %; stiffness at rest 1 %.
constexpr double kFrequencyTol = 0.05, kDecayTol = 0.25, kAmplitudeTol = 0.15;
constexpr double kStiffnessTol = 0.01;

class Tap final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override {
    t.push_back(tick.t);
    fz.push_back(tick.rendered_W.f.z());
  }

  void OnStep(const physics::StepRecord& /*step*/, const world::World& /*world*/) override {}

  std::vector<double> t, fz;
};

struct TapResult {
  std::vector<double> t, fz;  // whole run
  double t_onset = 0.0, t_stop = 0.0, f_rest = 0.0;
  std::vector<double> tau, residual;  // after the stop
};

// One tap at speed v: from kAbove above contact down to kDepth inside, then held.
TapResult RunTap(session::Session s, double x, double v) {
  const double above = kTop + kRadius + kAbove, down = kTop + kRadius - kDepth;
  const double t_stop = (kAbove + kDepth) / v;
  s.device.type = "scripted";
  s.device.trajectory.clear();
  s.device.keyframes = {device::Keyframe{0.0, Pose{Vec3(x, 0, above), Quat::Identity()}},
                        device::Keyframe{t_stop, Pose{Vec3(x, 0, down), Quat::Identity()}}};
  s.engine.duration = t_stop + kHold;
  Tap tap;
  (void)session::MakeEngine(s)->Run(&tap);
  TapResult r;
  r.t = tap.t;
  r.fz = tap.fz;
  r.t_stop = t_stop;
  std::size_t onset = 0;
  while (onset < r.fz.size() && !(r.fz[onset] != 0.0)) ++onset;
  r.t_onset = onset < r.t.size() ? r.t[onset] : 0.0;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] > r.t.back() - kRestWindow) sum += r.fz[i], ++n;
  }
  r.f_rest = n > 0 ? sum / n : 0.0;
  // After the stop the spring force is constant: what is left is the transient alone.
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] < t_stop - 1e-9 || r.t[i] > t_stop + kFitWindow) continue;
    r.tau.push_back(r.t[i] - r.t_onset);
    r.residual.push_back(r.fz[i] - r.f_rest);
  }
  return r;
}

// A tap's residual transient and its spectrum, rows of d3_transients.csv and d3_spectra.csv.
void AddTrace(const char* material, double v, const TapResult& r, double haptic_dt, double f_max,
              Table* traces, Table* spectra) {
  for (std::size_t i = 0; i < r.tau.size(); ++i) {
    traces->AddFormatted("{},{},{:.4f},{:.6e}", material, v, r.tau[i], r.residual[i]);
  }
  const std::vector<double> spectrum = Spectrum(r.residual, haptic_dt, 1.0, f_max);
  for (std::size_t i = 0; i < spectrum.size(); ++i) {
    spectra->AddFormatted("{},{},{},{:.6e}", material, v, i, spectrum[i]);
  }
}

// A tap's bars: the fitted transient's f, B and a·v and the stiffness felt at rest.
void AddTapChecks(const std::string& tag, const DecayFit& fit,
                  const settings::VibrationSettings& vib, double v, double k_rest, double k,
                  Checks* checks) {
  const double f_err = std::abs(fit.frequency / vib.frequency - 1.0);
  const double b_err = std::abs(fit.decay / vib.decay - 1.0);
  const double a_err = std::abs(fit.amplitude / (vib.amplitude * v) - 1.0);
  const double k_err = std::abs(k_rest / k - 1.0);
  checks->Add(tag + "_frequency_within_5pct", f_err <= kFrequencyTol, f_err, kFrequencyTol);
  checks->Add(tag + "_decay_within_25pct", b_err <= kDecayTol, b_err, kDecayTol);
  checks->Add(tag + "_amplitude_a_v_within_15pct", a_err <= kAmplitudeTol, a_err, kAmplitudeTol);
  checks->Add(tag + "_rest_stiffness_within_1pct", k_err <= kStiffnessTol, k_err, kStiffnessTol);
}

}  // namespace

int RunD3(const std::filesystem::path& out, bool quiet) {
  std::filesystem::create_directories(out);
  const session::Session base = session::LoadSession(ScenesDir() / "d3.json");
  const double f_max = 0.5 / base.engine.haptic_dt;
  Table fits({"material", "speed_m_s", "f_hz", "f_fit_hz", "decay_1_s", "decay_fit_1_s", "a_v_n",
              "a_v_fit_n", "stiffness_n_m", "stiffness_rest_n_m", "rms_n"});
  Table traces({"material", "speed_m_s", "tau_s", "residual_n"});
  Table spectra({"material", "speed_m_s", "freq_hz", "magnitude_n_s"});
  Checks checks;
  nlohmann::json summary;
  for (const Block& block : kBlocks) {
    const settings::MaterialSettings& m = base.engine.rendering.materials.at(block.material);
    const settings::VibrationSettings& vib = *m.vibration;
    const double k = m.stiffness.value_or(base.engine.rendering.stiffness);
    for (const double v : kSpeeds) {
      const TapResult r = RunTap(base, block.x, v);
      const DecayFit fit = FitDecayingSinusoid(r.tau, r.residual, f_max - 1.0);
      const double k_rest = r.f_rest / kDepth;
      fits.AddFormatted("{},{},{},{:.3f},{},{:.3f},{:.4f},{:.4f},{},{:.3f},{:.2e}", block.material,
                        v, vib.frequency, fit.frequency, vib.decay, fit.decay, vib.amplitude * v,
                        fit.amplitude, k, k_rest, fit.rms_error);
      AddTrace(block.material, v, r, base.engine.haptic_dt, f_max, &traces, &spectra);
      AddTapChecks(fmt::format("{}_{}m_s", block.material, v), fit, vib, v, k_rest, k, &checks);
    }
  }
  WriteText(out / "d3.csv", fits.Csv());
  WriteText(out / "d3.md", fits.Markdown() + "\n" + checks.Markdown());
  WriteText(out / "d3_transients.csv", traces.Csv());
  WriteText(out / "d3_spectra.csv", spectra.Csv());
  PlotD3(out, quiet);
  summary["experiment"] = "d3";
  summary["machine"] = MachineTag();
  summary["fits"] = fits.Json();
  return FinishExperiment(out, summary, checks, quiet);
}

}  // namespace mrh::experiments::internal
