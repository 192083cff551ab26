// SPDX-License-Identifier: Apache-2.0
// The method-of-constant-stimuli 2AFC protocol of thesis §4.5.4: settings, schedule, run loop.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mrh/session/session.h"

namespace mrh::psychophysics {

/// The session's `psychophysics` object (docs/psychophysics.md). Defaults are the thesis' design.
struct StudySettings {
  std::string standard_method = "single-rate";          ///< method of the standard stimulus
  double standard_mass = 60.0;                          ///< kg
  std::vector<double> masses{30, 45, 60, 75, 90, 105};  ///< kg, comparison masses
  std::vector<std::string> methods{"local-dynamics", "impulse"};  ///< comparison methods
  int trials_per_mass = 20;           ///< per comparison method and mass
  double speed = 0.017;               ///< m/s, initial speed of the cube in both stimuli
  std::optional<std::uint64_t> seed;  ///< random order; unset: from the subject's name
  std::string geom = "cube";          ///< MJCF geom whose mass="..." each stimulus sets
  double stimulus_duration = 2.0;     ///< s of each stimulus
  double pause = 1.0;                 ///< s of blank pause before each stimulus (with its cue)

  /// @throws mrh::InvalidArgument naming the `psychophysics.*` key, its value and what is
  /// expected (empty lists, non-positive masses or times, unknown methods, repeated entries).
  void Validate() const;
};

/// A session with its `psychophysics` object: the base session (scene = the T4.1 world) and the
/// study settings.
struct Study {
  session::Session base;
  StudySettings settings;
};

/// Reads the session file and its `psychophysics` object (which must exist). `overrides` are
/// the session's `--set` overrides (the psychophysics object is not overridable).
/// @throws mrh::InvalidArgument with a one-line message naming the file and the key.
Study LoadStudy(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// One trial of the schedule.
struct Trial {
  int index = 0;
  std::string method;            ///< comparison method
  double comparison_mass = 0.0;  ///< kg
  bool comparison_first = false;
};

/// The seed a subject's run uses: settings.seed, else the FNV-1a hash of the subject's name.
std::uint64_t StudySeed(const StudySettings& settings, const std::string& subject);

/// All trials (methods × masses × trials_per_mass) in a random order drawn from `seed` with
/// std::mt19937_64 and a Fisher–Yates shuffle written out here (so that the order is the same
/// with every standard library). For each method and mass, the comparison comes first in half
/// of the trials (the first ⌈n/2⌉ repetitions before shuffling).
std::vector<Trial> MakeSchedule(const StudySettings& settings, std::uint64_t seed);

/// The session of one stimulus: `base` with `method`, the stimulus duration, and a copy of its
/// scene (written into `dir`, reused if present) where geom settings.geom has `mass` and the
/// session's keyframe's qvel is rescaled to settings.speed.
/// @throws mrh::InvalidArgument if the scene has no such geom with a mass attribute or the
/// keyframe has no non-zero qvel; mrh::RuntimeError on I/O failure.
session::Session StimulusSession(const Study& study, const std::string& method, double mass,
                                 const std::filesystem::path& dir);

/// The subject's answer.
struct Response {
  int answer = 0;              ///< 1 or 2: the stimulus that felt heavier
  double response_time = 0.0;  ///< s
};

/// How stimuli reach the subject and answers come back: a window and a device for people, a
/// simulated observer for predictions. Called on one thread, in the order Cue(1), Present,
/// Cue(2), Present, Ask for every trial.
class Apparatus {
 public:
  virtual ~Apparatus() = default;
  /// The blank pause (seconds) before stimulus `interval` (1 or 2) and its cue.
  virtual void Cue(int interval, double pause) = 0;
  /// Presents one stimulus: runs `stimulus` (its method, mass and duration) with the device.
  virtual void Present(const session::Session& stimulus) = 0;
  /// "Which was heavier?". nullopt: the subject stopped the run (the trial stays unanswered).
  virtual std::optional<Response> Ask() = 0;
};

/// Where a run writes and who it is for.
struct RunSettings {
  std::string subject;                              ///< non-empty, no comma, quote or line break
  std::filesystem::path out;                        ///< created; holds trials.csv and stimuli/
  settings::Mode mode = settings::Mode::kRealtime;  ///< of every stimulus
  /// fsync trials.csv after each row (people: yes; simulated observers, who answer a thousand
  /// trials a second, only flush).
  bool sync = true;
};

/// What a run did.
struct RunResult {
  int answered_before = 0;  ///< rows already in trials.csv (resumed run)
  int answered = 0;         ///< rows in trials.csv now
  int total = 0;            ///< trials in the schedule
  std::uint64_t seed = 0;
};

/// Runs the schedule from the first trial not yet in out/trials.csv, appending each answered
/// trial (flushed) until the schedule ends or the apparatus reports a stop.
/// @throws mrh::InvalidArgument if trials.csv belongs to another subject, seed or design (it is
/// left untouched), or the subject name is unusable; what StimulusSession and the apparatus
/// throw.
RunResult RunStudy(const Study& study, const RunSettings& settings, Apparatus* apparatus);

}  // namespace mrh::psychophysics
