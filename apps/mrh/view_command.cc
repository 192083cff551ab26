// SPDX-License-Identifier: Apache-2.0
// `mrh view`: the interactive viewer, or N headless frames and a screenshot.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "commands.h"
#include "mrh/core/error.h"
#include "mrh/session/session.h"
#ifdef MRH_HAVE_VIEWER
#include "mrh/viewer/viewer.h"
#endif

namespace mrh::cli {
namespace {

constexpr const char* kViewFooter = R"(Mouse and keys (also under Help in the panel):
  left drag            move the pointer in the view plane
  Shift+left / wheel   move it in depth
  right drag           turn it
  arrows, PgUp/PgDn    nudge it (Shift: finer)
  Ctrl+left/right/wheel  orbit / pan / zoom the camera (C swaps plain and Ctrl drags)
  Space  pause   S  step   Backspace  reset   H  panel   Home  camera

Examples:
  mrh view scenes/demo.json
  mrh view scenes/demo.json --method single-rate --set rendering.stiffness=2000
  xvfb-run -a mrh view scenes/demo.json --at 2.5 --screenshot view.png
)";

// CLI11's NonNegativeNumber would print DBL_MAX in full in its message; this one says what to give.
std::string CheckSimulatedTime(std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || value < 0.0) {
    return fmt::format("expected a simulated time in seconds >= 0, got '{}'", text);
  }
  return {};
}

std::vector<std::string> Overrides(const ViewOptions& o) {
  std::vector<std::string> overrides = o.sets;
  if (!o.method.empty()) overrides.push_back("method=" + o.method);
  return overrides;
}

}  // namespace

CLI::App* AddViewCommand(CLI::App& app, ViewOptions* o) {
  CLI::App* view = app.add_subcommand(
      "view",
      "Open the interactive viewer: the session in real time, the pointer on the mouse, forces "
      "drawn as arrows, gains and plots in a panel");
  view->add_option("SESSION", o->session, "Session file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  view->add_option("--method", o->method, "Override the rendering method (see `mrh methods`)")
      ->type_name("NAME");
  AddSetOption(*view, &o->sets);
  CLI::Option* frames =
      view->add_option("--frames", o->frames,
                       "Headless: render N frames with the session's own device, then exit. "
                       "The session runs in real time and frames are drawn at up to 60 fps, so "
                       "the last one shows roughly N/60 s or later (slow drawing); use --at to "
                       "aim at a simulated time")
          ->type_name("N")
          ->check(CLI::PositiveNumber);
  CLI::Option* at =
      view->add_option("--at", o->at,
                       "Headless: run the session with its own device to simulated time T (s), "
                       "hold it there and draw that moment, then exit")
          ->type_name("T")
          ->check(CLI::Validator(CheckSimulatedTime, ""))
          ->excludes(frames);
  view->add_option("--screenshot", o->screenshot,
                   "With --frames or --at: write the last frame as PNG")
      ->type_name("PNG");
  view->add_flag("--hide-panel", o->hide_panel, "Draw the scene only, without the panel");
  view->footer(kViewFooter);
  view->callback([view, frames, at] {
    if (view->count("--screenshot") > 0 && frames->count() == 0 && at->count() == 0) {
      throw CLI::ValidationError("--screenshot requires --frames or --at");
    }
  });
  return view;
}

int ViewCommand(const ViewOptions& o) {
  const session::Session session = session::LoadSession(o.session, Overrides(o));
#ifdef MRH_HAVE_VIEWER
  const double t = viewer::RunViewer(session, viewer::ViewerSettings{
                                                  .frames = o.frames,
                                                  .at = o.at,
                                                  .screenshot = o.screenshot,
                                                  .panel = !o.hide_panel,
                                              });
  if (!o.screenshot.empty()) {
    fmt::print("screenshot: {} (t = {:.3f} s)\n", o.screenshot.string(), t);
  }
  return kExitOk;
#else
  (void)session;
  throw RuntimeError(
      "this mrh was built without the viewer (MRH_BUILD_VIEWER=OFF: libglfw3-dev and "
      "libimgui-dev were not found); install them with scripts/install-deps.sh, reconfigure "
      "with -DMRH_BUILD_VIEWER=ON, or use 'mrh run' for a headless session");
#endif
}

}  // namespace mrh::cli
