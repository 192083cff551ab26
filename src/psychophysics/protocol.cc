// SPDX-License-Identifier: Apache-2.0
// The stimuli (the T4.1 scene with a mass and a speed) and the 2AFC run loop with resume.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>

#include "mrh/core/error.h"
#include "mrh/psychophysics/study.h"
#include "mrh/psychophysics/trials.h"
#include "mrh/session/mjcf_text.h"

namespace mrh::psychophysics {
namespace {

// The value of attribute="..." of the first <element ... name="name" ...> in the MJCF text,
// comments skipped: its offset and length, or nullopt.
std::optional<std::pair<std::size_t, std::size_t>> FindAttribute(const std::string& text,
                                                                 std::string_view element,
                                                                 std::string_view name,
                                                                 std::string_view attribute) {
  const session::MjcfAttributeSpan span =
      session::FindMjcfAttribute(text, element, name, attribute);
  if (!span.found) return std::nullopt;
  return std::pair{span.offset, span.size};
}

// The scene text with the geom's mass and the keyframe's qvel rescaled to `speed`.
std::string EditScene(const Study& study, double mass) {
  const std::filesystem::path& file = study.base.scene;
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const auto qvel = FindAttribute(text, "key", study.base.keyframe, "qvel");
  std::vector<double> v;
  if (qvel) {
    std::stringstream numbers(text.substr(qvel->first, qvel->second));
    for (double x; numbers >> x;) v.push_back(x);
  }
  double norm = 0.0;
  for (const double x : v) norm += x * x;
  norm = std::sqrt(norm);
  if (!(norm > 0.0)) {
    throw InvalidArgument(fmt::format(
        "{}: keyframe \"{}\" has no non-zero qvel=\"...\"; expected the moving cube's velocity "
        "(psychophysics rescales it to psychophysics.speed)",
        file.string(), study.base.keyframe));
  }
  std::string scaled;
  for (const double x : v)
    scaled += fmt::format("{}{}", scaled.empty() ? "" : " ", x / norm * study.settings.speed);
  text.replace(qvel->first, qvel->second, scaled);
  const auto m = FindAttribute(text, "geom", study.settings.geom, "mass");
  if (!m) {
    throw InvalidArgument(
        fmt::format("{}: no <geom name=\"{}\" mass=\"...\">; expected the stimulus geom named by "
                    "psychophysics.geom, with its mass",
                    file.string(), study.settings.geom));
  }
  return text.replace(m->first, m->second, fmt::format("{}", mass));
}

void CheckSubject(const std::string& subject) {
  if (subject.empty() || subject.find_first_of(",\"\r\n") != std::string::npos) {
    throw InvalidArgument(fmt::format(
        "--subject \"{}\"; expected a non-empty name without commas, quotes or line breaks",
        subject));
  }
}

// The answered rows must be this subject's run of this schedule, from trial 0 in order.
void CheckResume(const std::filesystem::path& file, const std::vector<TrialRow>& rows,
                 const std::vector<Trial>& schedule, const std::string& subject, std::uint64_t seed,
                 const StudySettings& s) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TrialRow& r = rows[i];
    const bool same = i < schedule.size() && r.subject == subject && r.seed == seed &&
                      r.trial == static_cast<int>(i) && r.method == schedule[i].method &&
                      r.comparison_mass == schedule[i].comparison_mass &&
                      r.comparison_first == schedule[i].comparison_first &&
                      r.standard_method == s.standard_method &&
                      r.standard_mass == s.standard_mass && r.speed == s.speed;
    if (!same) {
      throw InvalidArgument(fmt::format(
          "{}:{}: trial {} of subject \"{}\" (seed {}) is not trial {} of this run (subject "
          "\"{}\", seed {}, this session's design); expected another --out folder or the same "
          "session and subject",
          file.string(), i + 2, r.trial, r.subject, r.seed, i, subject, seed));
    }
  }
}

}  // namespace

session::Session StimulusSession(const Study& study, const std::string& method, double mass,
                                 const std::filesystem::path& dir) {
  session::Session s = study.base;
  s.engine.method = method;
  s.engine.duration = study.settings.stimulus_duration;
  const std::filesystem::path scene =
      dir /
      fmt::format("{}_m{}_v{}.xml", study.base.scene.stem().string(), mass, study.settings.speed);
  if (!std::filesystem::exists(scene)) {
    const std::string text = EditScene(study, mass);
    std::filesystem::create_directories(dir);
    std::ofstream out(scene, std::ios::binary);
    out << text;
    if (!out.flush()) throw RuntimeError(fmt::format("cannot write {}", scene.string()));
  }
  s.scene = std::filesystem::absolute(scene);
  return s;
}

namespace {

// Presents trial t's two stimuli, in its order, and asks; nullopt when the subject stopped.
std::optional<Response> PresentTrial(const Study& study, const RunSettings& settings,
                                     const Trial& t, Apparatus* apparatus) {
  const StudySettings& s = study.settings;
  const std::filesystem::path stimuli = settings.out / "stimuli";
  session::Session standard = StimulusSession(study, s.standard_method, s.standard_mass, stimuli);
  session::Session comparison = StimulusSession(study, t.method, t.comparison_mass, stimuli);
  standard.engine.mode = comparison.engine.mode = settings.mode;
  apparatus->Cue(1, s.pause);
  apparatus->Present(t.comparison_first ? comparison : standard);
  apparatus->Cue(2, s.pause);
  apparatus->Present(t.comparison_first ? standard : comparison);
  std::optional<Response> response = apparatus->Ask();
  if (response && response->answer != 1 && response->answer != 2) {
    throw RuntimeError(fmt::format("apparatus answered {}; expected 1 or 2", response->answer));
  }
  return response;
}

TrialRow RowOf(const StudySettings& s, const RunSettings& settings, const Trial& t,
               const Response& response, std::uint64_t seed) {
  return TrialRow{.subject = settings.subject,
                  .trial = t.index,
                  .method = t.method,
                  .standard_method = s.standard_method,
                  .standard_mass = s.standard_mass,
                  .comparison_mass = t.comparison_mass,
                  .speed = s.speed,
                  .comparison_first = t.comparison_first,
                  .answer = response.answer,
                  .comparison_heavier = (response.answer == 1) == t.comparison_first,
                  .response_time = response.response_time,
                  .seed = seed};
}

}  // namespace

RunResult RunStudy(const Study& study, const RunSettings& settings, Apparatus* apparatus) {
  CheckSubject(settings.subject);
  const StudySettings& s = study.settings;
  RunResult result;
  result.seed = StudySeed(s, settings.subject);
  const std::vector<Trial> schedule = MakeSchedule(s, result.seed);
  result.total = static_cast<int>(schedule.size());
  std::filesystem::create_directories(settings.out);
  const std::filesystem::path file = settings.out / "trials.csv";
  if (std::filesystem::exists(file) && std::filesystem::file_size(file) > 0) {
    const std::vector<TrialRow> rows = ReadTrials(file);
    CheckResume(file, rows, schedule, settings.subject, result.seed, s);
    result.answered_before = static_cast<int>(rows.size());
  }
  result.answered = result.answered_before;
  TrialsWriter writer(file, settings.sync);
  for (std::size_t i = result.answered_before; i < schedule.size(); ++i) {
    const std::optional<Response> response = PresentTrial(study, settings, schedule[i], apparatus);
    if (!response) break;
    writer.Append(RowOf(s, settings, schedule[i], *response, result.seed));
    ++result.answered;
  }
  return result;
}

}  // namespace mrh::psychophysics
