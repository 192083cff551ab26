// SPDX-License-Identifier: Apache-2.0
// The study settings, the schedule, the stimuli and the run loop with stop and resume.
#include "mrh/psychophysics/study.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "mrh/core/error.h"
#include "mrh/psychophysics/trials.h"
#include "mrh/world/world.h"

namespace mrh::psychophysics {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kSession = fs::path(MRH_SOURCE_DIR) / "scenes" / "t4_2.json";

fs::path TempDir(const std::string& stem) {
  const fs::path dir = fs::temp_directory_path() / (stem + std::to_string(getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string ErrorOf(const std::vector<std::string>& overrides) {
  try {
    (void)LoadStudy(kSession, overrides);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

TEST(StudySettingsTest, TheShippedSessionHasTheThesisDesign) {
  const Study study = LoadStudy(kSession);
  EXPECT_EQ(study.settings.standard_method, "single-rate");
  EXPECT_EQ(study.settings.standard_mass, 60.0);
  EXPECT_THAT(study.settings.masses, ::testing::ElementsAre(30, 45, 60, 75, 90, 105));
  EXPECT_THAT(study.settings.methods, ::testing::ElementsAre("local-dynamics", "impulse"));
  EXPECT_EQ(study.settings.trials_per_mass, 20);
  EXPECT_EQ(study.settings.speed, 0.017);
}

TEST(StudySettingsTest, BadValuesNameTheFileAndTheKey) {
  EXPECT_THAT(ErrorOf({"psychophysics.masses=[30,-1]"}), HasSubstr("psychophysics.masses[1]"));
  EXPECT_THAT(ErrorOf({"psychophysics.masses=[30,30]"}), HasSubstr("distinct"));
  EXPECT_THAT(ErrorOf({"psychophysics.methods=[\"nope\"]"}), HasSubstr("psychophysics.methods[0]"));
  EXPECT_THAT(ErrorOf({"psychophysics.trials_per_mass=0"}),
              HasSubstr("psychophysics.trials_per_mass"));
  EXPECT_THAT(ErrorOf({"psychophysics.speed=0"}), HasSubstr("psychophysics.speed"));
  EXPECT_THAT(ErrorOf({"psychophysics.seed=-3"}), HasSubstr("psychophysics.seed"));
  EXPECT_THAT(ErrorOf({"psychophysics.bogus=1"}), HasSubstr("psychophysics.bogus"));
  EXPECT_THAT(ErrorOf({"psychophysics.speed=1"}), HasSubstr("no error"));
  EXPECT_THAT(ErrorOf({"psychophysics.masses=[30,-1]"}), HasSubstr("t4_2.json"));
}

TEST(StudySettingsTest, ASessionWithoutTheObjectIsAnError) {
  const fs::path plain = fs::path(MRH_SOURCE_DIR) / "scenes" / "t4_1_impulse.json";
  try {
    (void)LoadStudy(plain);
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("psychophysics = (missing)"));
  }
}

TEST(ScheduleTest, HoldsEveryCellTrialsPerMassTimesHalfOfThemComparisonFirst) {
  const StudySettings s;
  const std::vector<Trial> trials = MakeSchedule(s, 1234);
  ASSERT_EQ(trials.size(), 2u * 6u * 20u);
  std::map<std::pair<std::string, double>, std::pair<int, int>> cells;  // (count, first)
  for (std::size_t i = 0; i < trials.size(); ++i) {
    EXPECT_EQ(trials[i].index, static_cast<int>(i));
    auto& c = cells[{trials[i].method, trials[i].comparison_mass}];
    ++c.first;
    c.second += trials[i].comparison_first ? 1 : 0;
  }
  EXPECT_EQ(cells.size(), 12u);
  for (const auto& [cell, c] : cells) {
    EXPECT_EQ(c.first, 20);
    EXPECT_EQ(c.second, 10);
  }
}

TEST(ScheduleTest, TheSeedFixesTheOrder) {
  const StudySettings s;
  const auto a = MakeSchedule(s, 7), b = MakeSchedule(s, 7), c = MakeSchedule(s, 8);
  int same = 0, differs = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    same += a[i].method == b[i].method && a[i].comparison_mass == b[i].comparison_mass &&
            a[i].comparison_first == b[i].comparison_first;
    differs += a[i].comparison_mass != c[i].comparison_mass || a[i].method != c[i].method;
  }
  EXPECT_EQ(same, static_cast<int>(a.size()));
  EXPECT_GT(differs, static_cast<int>(a.size()) / 2);  // a shuffle, not a rotation
  StudySettings seeded;
  seeded.seed = 99;
  EXPECT_EQ(StudySeed(seeded, "A"), 99u);
  EXPECT_NE(StudySeed(s, "A"), StudySeed(s, "B"));
  // FNV-1a 64 of "a" (the published test vector).
  EXPECT_EQ(StudySeed(s, "a"), 0xaf63dc4c8601ec8cull);
}

TEST(StimulusTest, SetsTheMassAndTheSpeedOfTheCube) {
  const Study study = LoadStudy(kSession, {"psychophysics.speed=0.034"});
  const fs::path dir = TempDir("mrh_psychophysics_stimulus_");
  const session::Session s = StimulusSession(study, "impulse", 75.0, dir);
  EXPECT_EQ(s.engine.method, "impulse");
  EXPECT_EQ(s.engine.duration, study.settings.stimulus_duration);
  const world::World world = session::LoadWorld(s);
  const int cube = world.FindBody("cube");
  EXPECT_DOUBLE_EQ(world.body(cube).mass, 75.0);
  EXPECT_NEAR(world.body_state(cube).V_WCm.v.x(), 0.034, 1e-12);
  fs::remove_all(dir);
}

// Answers "1" always, and stops after `stop_after` questions.
class FakeApparatus final : public Apparatus {
 public:
  explicit FakeApparatus(int stop_after) : left_(stop_after) {}

  void Cue(int interval, double) override { cues.push_back(interval); }

  void Present(const session::Session& s) override {
    presented.emplace_back(s.engine.method, s.scene.filename().string());
  }

  std::optional<Response> Ask() override {
    if (left_-- <= 0) return std::nullopt;
    return Response{.answer = 1, .response_time = 0.5};
  }

  std::vector<int> cues;
  std::vector<std::pair<std::string, std::string>> presented;

 private:
  int left_;
};

std::string ReadAll(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RunStudyTest, RecordsWhichStimulusWasTheComparisonAndResumesWhereItStopped) {
  const Study study =
      LoadStudy(kSession, {"psychophysics.masses=[45,75]", "psychophysics.trials_per_mass=3"});
  const fs::path stopped = TempDir("mrh_psychophysics_resume_"), whole = stopped / "whole";
  RunSettings run{.subject = "S", .out = stopped, .mode = settings::Mode::kLockstep, .sync = false};
  FakeApparatus first(5), second(100);
  EXPECT_EQ(RunStudy(study, run, &first).answered, 5);
  const RunResult resumed = RunStudy(study, run, &second);
  EXPECT_EQ(resumed.answered_before, 5);
  EXPECT_EQ(resumed.answered, 12);
  EXPECT_EQ(second.presented.size(), 2u * 7u);
  FakeApparatus straight(100);
  run.out = whole;
  (void)RunStudy(study, run, &straight);
  EXPECT_EQ(ReadAll(stopped / "trials.csv"), ReadAll(whole / "trials.csv"));
  // Answer 1 names the comparison exactly when it came first; the standard is single-rate 60 kg.
  const std::vector<Trial> schedule = MakeSchedule(study.settings, resumed.seed);
  const std::vector<TrialRow> rows = ReadTrials(whole / "trials.csv");
  ASSERT_EQ(rows.size(), 12u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].comparison_heavier, schedule[i].comparison_first);
    EXPECT_EQ(rows[i].comparison_mass, schedule[i].comparison_mass);
    const auto& standard = straight.presented[2 * i + (schedule[i].comparison_first ? 1 : 0)];
    EXPECT_EQ(standard.first, "single-rate");
    EXPECT_THAT(standard.second, HasSubstr("_m60_"));
  }
  EXPECT_THAT(straight.cues, ::testing::Each(::testing::AnyOf(1, 2)));
  // Another subject's folder is refused, untouched.
  run.subject = "T";
  FakeApparatus other(100);
  EXPECT_THROW((void)RunStudy(study, run, &other), InvalidArgument);
  EXPECT_EQ(ReadTrials(whole / "trials.csv").size(), 12u);
  fs::remove_all(stopped);
}

}  // namespace
}  // namespace mrh::psychophysics
