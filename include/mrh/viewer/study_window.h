// SPDX-License-Identifier: Apache-2.0
// The window a subject of `mrh psychophysics run` sees: blank stimuli, cues, key answers.
#pragma once

#include <memory>

#include "mrh/psychophysics/study.h"
#include "mrh/session/session.h"

namespace mrh::viewer {

/// How the study window runs.
struct StudyWindowSettings {
  /// true: the pointer follows the mouse cursor (0.5 mm per pixel in the device's x-y plane from
  /// where the cursor was when the stimulus began); false: the session's own device.
  bool mouse = false;
  int width = 800;  ///< screen coordinates
  int height = 600;
};

/// A psychophysics::Apparatus on a window of the current X display. Every stimulus runs its
/// session in real-time mode (the engine's physics thread plus a 1 kHz haptic thread, as in
/// `mrh view`) while the window stays blank; cues name the next stimulus during the pause; the
/// question waits for the key 1 or 2 (also on the keypad). Esc, Q or closing the window stops
/// the run at the next question. `base` gives the device, its calibration and specifications.
/// @throws mrh::RuntimeError when there is no display or no usable OpenGL. Not RT-safe; the
/// calling thread must be the one that calls the apparatus.
std::unique_ptr<psychophysics::Apparatus> MakeStudyWindow(const session::Session& base,
                                                          const StudyWindowSettings& settings);

}  // namespace mrh::viewer
