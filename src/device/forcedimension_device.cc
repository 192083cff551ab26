// SPDX-License-Identifier: Apache-2.0
// Force Dimension devices (omega, sigma, lambda, delta, Novint Falcon) through the DHD C API,
// loaded at run time.
#include <atomic>
#include <string>

#include "device/dynamic_library.h"
#include "device/hardware_impl.h"
#include "mrh/core/error.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

// The DHD C API as the SDK's dhdc.h declares it (C linkage; the device ID `char` comes last,
// as dhdOpen / dhdOpenID returned it; an int return < 0 is an error). Only these signatures are
// used; no SDK header is needed. Source: Force Dimension SDK, include/dhdc.h.
constexpr int kMaxDeviceIndex = 127;  // the ID is a signed char
using DhdOpenFn = int();
using DhdOpenIdFn = int(char);
using DhdCloseFn = int(char);
using DhdGet3Fn = int(double*, double*, double*, char);
using DhdGetFrameFn = int(double[3][3], char);
using DhdSetForceAndTorqueFn = int(double, double, double, double, double, double, char);
using DhdEnableForceFn = int(unsigned char, char);
using DhdGetButtonMaskFn = int(char);
using DhdErrorGetLastStrFn = const char*();
using DhdGetSystemNameFn = const char*(char);

struct DhdApi {
  DhdOpenFn* open = nullptr;
  DhdOpenIdFn* open_id = nullptr;  // required only for ForceDimensionSettings::id >= 0
  DhdCloseFn* close = nullptr;
  DhdGet3Fn* get_position = nullptr;
  DhdGetFrameFn* get_orientation_frame = nullptr;
  DhdGet3Fn* get_linear_velocity = nullptr;
  DhdSetForceAndTorqueFn* set_force_and_torque = nullptr;
  DhdEnableForceFn* enable_force = nullptr;
  DhdGetButtonMaskFn* get_button_mask = nullptr;
  DhdErrorGetLastStrFn* error_get_last_str = nullptr;
  DhdGetSystemNameFn* get_system_name = nullptr;
  DhdGet3Fn* get_angular_velocity_rad = nullptr;  // optional (SDK 3.x and later)
};

DhdApi ResolveDhd(const internal::DynamicLibrary& lib) {
  DhdApi api;
  lib.Require("dhdOpen", &api.open);
  lib.Require("dhdClose", &api.close);
  lib.Require("dhdGetPosition", &api.get_position);
  lib.Require("dhdGetOrientationFrame", &api.get_orientation_frame);
  lib.Require("dhdGetLinearVelocity", &api.get_linear_velocity);
  lib.Require("dhdSetForceAndTorque", &api.set_force_and_torque);
  lib.Require("dhdEnableForce", &api.enable_force);
  lib.Require("dhdGetButtonMask", &api.get_button_mask);
  lib.Require("dhdErrorGetLastStr", &api.error_get_last_str);
  lib.Require("dhdGetSystemName", &api.get_system_name);
  lib.Probe("dhdGetAngularVelocityRad", &api.get_angular_velocity_rad);
  lib.Probe("dhdOpenID", &api.open_id);
  return api;
}

class ForceDimensionDevice final : public Device {
 public:
  ForceDimensionDevice(const ForceDimensionSettings& settings, const Specifications& specs)
      : lib_(settings.library, "Force Dimension DHD library (device.library)"),
        api_(ResolveDhd(lib_)),
        specs_(specs),
        index_(settings.id) {
    if (index_ < -1 || index_ > kMaxDeviceIndex) {
      throw InvalidArgument("forcedimension device.id = " + std::to_string(index_) +
                            "; expected -1 (the default device) or 0.." +
                            std::to_string(kMaxDeviceIndex));
    }
    if (index_ >= 0 && api_.open_id == nullptr) {
      throw InvalidArgument("forcedimension device.id = " + std::to_string(index_) + ": " +
                            settings.library + " has no dhdOpenID");
    }
  }

  ~ForceDimensionDevice() override { Close(); }

  const Specifications& specifications() const override { return specs_; }

  void Open() override {
    if (open_) return;
    const int id = index_ < 0 ? api_.open() : api_.open_id(static_cast<char>(index_));
    if (id < 0) {
      const std::string call =
          index_ < 0 ? std::string("dhdOpen") : "dhdOpenID(" + std::to_string(index_) + ")";
      throw RuntimeError("forcedimension device: " + call + " failed: " + VendorError() +
                         " (is the device plugged in, powered and allowed by udev?)");
    }
    id_ = static_cast<char>(id);
    open_ = true;
    const char* name = api_.get_system_name(id_);
    system_name_ = name != nullptr ? name : "";
    // Zero before enabling, so the first tick cannot display a stale command.
    if (api_.set_force_and_torque(0, 0, 0, 0, 0, 0, id_) < 0 || api_.enable_force(1, id_) < 0) {
      const std::string why = VendorError();
      Close();
      throw RuntimeError("forcedimension device \"" + system_name_ +
                         "\": cannot enable forces: " + why);
    }
  }

  void Close() override {
    if (!open_) return;
    // Best effort on the way out: a failure here is counted, never thrown from a destructor.
    if (api_.set_force_and_torque(0, 0, 0, 0, 0, 0, id_) < 0) CountError();
    if (api_.enable_force(0, id_) < 0) CountError();
    if (api_.close(id_) < 0) CountError();
    open_ = false;
  }

  DeviceState Read(double t) noexcept override {
    DeviceState s = last_;
    s.t = t;
    double px = 0, py = 0, pz = 0, vx = 0, vy = 0, vz = 0;
    double frame[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    // A failed read keeps the last good reading (the engine sees a held pose, not garbage).
    if (api_.get_position(&px, &py, &pz, id_) < 0 || api_.get_orientation_frame(frame, id_) < 0 ||
        api_.get_linear_velocity(&vx, &vy, &vz, id_) < 0) {
      CountError();
      return s;
    }
    s.X_DT.p = Vec3(px, py, pz);
    Mat3 R;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) R(i, j) = frame[i][j];  // frame[row][column]
    }
    s.X_DT.q = Quat(R).normalized();
    s.V_DT.v = Vec3(vx, vy, vz);
    double wx = 0, wy = 0, wz = 0;
    if (api_.get_angular_velocity_rad != nullptr &&
        api_.get_angular_velocity_rad(&wx, &wy, &wz, id_) >= 0) {
      s.V_DT.w = Vec3(wx, wy, wz);
    }
    const int buttons = api_.get_button_mask(id_);
    s.buttons = buttons >= 0 ? static_cast<std::uint32_t>(buttons) : 0u;
    last_ = s;
    return s;
  }

  void SetWrench(const Wrench& w_D) noexcept override {
    const Wrench w = internal::DropTorqueIfNoTorque(specs_, w_D, &counters_);
    if (api_.set_force_and_torque(w.f.x(), w.f.y(), w.f.z(), w.tau.x(), w.tau.y(), w.tau.z(), id_) <
        0) {
      CountError();
    }
  }

  DeviceCounters counters() const override { return counters_.Load(); }

  std::string last_error() const override {
    return counters_.vendor_errors.load() > 0 ? VendorError() : std::string();
  }

 private:
  std::string VendorError() const {
    const char* text = api_.error_get_last_str();
    return text != nullptr ? std::string(text) : std::string("unknown DHD error");
  }

  void CountError() noexcept { internal::AtomicCounters::Bump(counters_.vendor_errors); }

  internal::DynamicLibrary lib_;
  DhdApi api_;
  Specifications specs_;
  DeviceState last_;
  internal::AtomicCounters counters_;
  std::string system_name_;
  int index_;    // ForceDimensionSettings::id
  char id_ = 0;  // the device ID the open returned, named in every call
  bool open_ = false;
};

}  // namespace

std::unique_ptr<Device> MakeForceDimensionDevice(const ForceDimensionSettings& settings,
                                                 const Specifications& specs) {
  return std::make_unique<ForceDimensionDevice>(settings, specs);
}

}  // namespace mrh::device
