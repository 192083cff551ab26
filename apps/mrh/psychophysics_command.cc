// SPDX-License-Identifier: Apache-2.0
// `mrh psychophysics run|analyze`: a 2AFC study with a person, and its psychometric analysis.
#include "psychophysics_command.h"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "commands.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/psychophysics/analysis.h"
#include "mrh/psychophysics/study.h"
#ifdef MRH_HAVE_VIEWER
#include "mrh/viewer/study_window.h"
#endif

namespace mrh::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFooter = R"(Examples:
  mrh psychophysics run scenes/t4_2.json --subject A --out out/study/A
  mrh psychophysics run scenes/t4_2.json --subject A --out out/study/A --mouse
  mrh psychophysics run scenes/t4_2.json --subject A --out out/study/A --terminal
  mrh psychophysics analyze out/study/*/trials.csv --out out/study/analysis

In the window: the screen stays blank while a stimulus runs; between stimuli it shows which
one comes next; after the second it asks which was heavier: press 1 or 2 (Esc or Q stops;
running the same command again resumes at the first unanswered trial).
With --terminal: stimuli run with the session's device and answers are typed (1, 2, q).
See docs/psychophysics.md.
)";

// Stimuli on the session's own device, answers from standard input: for builds without the
// viewer, scripted runs, and devices that need no window.
class TerminalApparatus final : public psychophysics::Apparatus {
 public:
  void Cue(int interval, double pause) override {
    std::cerr << fmt::format("stimulus {} in {:.1f} s\n", interval, pause);
    std::this_thread::sleep_for(std::chrono::duration<double>(pause));
  }

  void Present(const session::Session& stimulus) override {
    const auto engine = session::MakeEngine(stimulus);
    (void)engine->Run(nullptr);
  }

  std::optional<psychophysics::Response> Ask() override {
    const auto start = std::chrono::steady_clock::now();
    for (std::string line;;) {
      std::cerr << "which was heavier? 1 or 2 (q stops): " << std::flush;
      if (!std::getline(std::cin, line) || line == "q" || line == "Q") return std::nullopt;
      if (line == "1" || line == "2") {
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        return psychophysics::Response{.answer = line == "1" ? 1 : 2,
                                       .response_time = took.count()};
      }
    }
  }
};

std::unique_ptr<psychophysics::Apparatus> MakeApparatus(const PsychophysicsOptions& o,
                                                        const psychophysics::Study& study) {
  if (o.terminal) return std::make_unique<TerminalApparatus>();
#ifdef MRH_HAVE_VIEWER
  return viewer::MakeStudyWindow(study.base, viewer::StudyWindowSettings{.mouse = o.mouse});
#else
  (void)study;
  throw RuntimeError(
      "this mrh was built without the viewer, so `psychophysics run` has no window; use "
      "--terminal (answers typed on standard input) or install the viewer's packages with "
      "scripts/install-deps.sh and reconfigure with -DMRH_BUILD_VIEWER=ON");
#endif
}

int RunStudyCommand(const PsychophysicsOptions& o) {
  const psychophysics::Study study = psychophysics::LoadStudy(o.session, o.sets);
  const auto apparatus = MakeApparatus(o, study);
  const psychophysics::RunResult r = psychophysics::RunStudy(
      study, psychophysics::RunSettings{.subject = o.subject, .out = o.out}, apparatus.get());
  fmt::print("subject {}: {} of {} trials answered ({} this run), seed {}\n", o.subject, r.answered,
             r.total, r.answered - r.answered_before, r.seed);
  fmt::print("trials: {}\n", (o.out / "trials.csv").string());
  return kExitOk;
}

int AnalyzeCommand(const PsychophysicsOptions& o) {
  std::vector<psychophysics::TrialRow> rows;
  for (const fs::path& file : o.trials) {
    std::vector<psychophysics::TrialRow> more = psychophysics::ReadTrials(file);
    rows.insert(rows.end(), more.begin(), more.end());
  }
  const std::vector<psychophysics::SubjectFit> fits = psychophysics::FitAll(rows);
  std::string why;
  if (!psychophysics::WriteAnalysis(o.out, fits, &why)) {
    fmt::print(stderr, "mrh: warning: curves.png not drawn: {}\n", why);
  }
  fmt::print("{}results: {}\n", psychophysics::PseTableMarkdown(fits), o.out.string());
  return kExitOk;
}

}  // namespace

PsychophysicsCommands AddPsychophysicsCommand(CLI::App& app, PsychophysicsOptions* o) {
  CLI::App* top =
      app.add_subcommand("psychophysics",
                         "Run a 2AFC mass-discrimination study with a person (thesis §4.5.4) and "
                         "analyse its trials");
  top->require_subcommand(1);
  top->footer(kFooter);
  CLI::App* run = top->add_subcommand("run", "Run (or resume) one subject's session");
  run->add_option("SESSION", o->session, "Session file with a psychophysics object")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--subject", o->subject, "Subject name (recorded in every row)")->required();
  run->add_option("--out,-o", o->out, "Folder of trials.csv (resumed if present)")
      ->required()
      ->type_name("DIR");
  run->add_flag("--mouse", o->mouse, "Drive the pointer with the mouse in the window");
  run->add_flag("--terminal", o->terminal,
                "No window: the session's device, answers typed on standard input");
  AddSetOption(*run, &o->sets);
  run->footer(kFooter);
  CLI::App* analyze = top->add_subcommand("analyze", "Fit psychometric functions to trials files");
  analyze->add_option("TRIALS", o->trials, "trials.csv files")
      ->required()
      ->check(CLI::ExistingFile);
  analyze->add_option("--out,-o", o->out, "Output folder")->required()->type_name("DIR");
  analyze->footer(kFooter);
  return PsychophysicsCommands{.top = top, .run = run, .analyze = analyze};
}

int PsychophysicsCommand(const PsychophysicsCommands& c, const PsychophysicsOptions& o) {
  if (c.run->parsed()) return RunStudyCommand(o);
  return AnalyzeCommand(o);
}

}  // namespace mrh::cli
