// SPDX-License-Identifier: Apache-2.0
// Device → world calibration: a rigid transform plus a uniform position scale.
#pragma once

#include "mrh/core/spatial.h"

namespace mrh::device {

/// Maps device-frame tool poses into the world: p_W = X_WD.p + R_WD (scale p_D),
/// R_WT = R_WD R_DT. Wrenches go back by rotation only (forces are not scaled). RT-safe.
struct Calibration {
  Pose X_WD;
  double scale = 1.0;

  Pose ToWorld(const Pose& X_DT) const {
    return Pose{X_WD.p + X_WD.q * (scale * X_DT.p), X_WD.q * X_DT.q};
  }

  Twist ToWorld(const Twist& V_D) const { return Twist{X_WD.q * (scale * V_D.v), X_WD.q * V_D.w}; }

  Pose ToDevice(const Pose& X_WT) const {
    const Quat q_DW = X_WD.q.conjugate();
    return Pose{(q_DW * (X_WT.p - X_WD.p)) / scale, q_DW * X_WT.q};
  }

  Wrench ToDevice(const Wrench& w_W) const {
    const Quat q_DW = X_WD.q.conjugate();
    return Wrench{q_DW * w_W.f, q_DW * w_W.tau};
  }
};

}  // namespace mrh::device
