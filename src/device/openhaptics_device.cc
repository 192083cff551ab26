// SPDX-License-Identifier: Apache-2.0
// 3D Systems (SensAble) Touch, Touch X and Phantom devices through the OpenHaptics HD API,
// loaded at run time. The vendor's scheduler owns the 1 kHz servo thread.
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

#include "device/dynamic_library.h"
#include "device/hardware_impl.h"
#include "mrh/core/error.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

// The few HD types and constants used, with the values of OpenHaptics' HD/hdDefines.h and the
// signatures of HD/hdDevice.h and HD/hdScheduler.h (C linkage; HDCALLBACK is empty on Linux).
using HHD = unsigned int;
using HDenum = unsigned int;
using HDerror = unsigned int;
using HDCallbackCode = unsigned int;
using HDSchedulerHandle = unsigned long;

struct HDErrorInfo {
  HDerror errorCode;
  int internalErrorCode;
  HHD hHD;
};

using HDSchedulerCallback = HDCallbackCode (*)(void*);
constexpr HHD kHdInvalidHandle = 0xFFFFFFFFu;         // HD_INVALID_HANDLE
constexpr HDerror kHdSuccess = 0x0000;                // HD_SUCCESS
constexpr HDCallbackCode kHdCallbackDone = 0;         // HD_CALLBACK_DONE
constexpr HDCallbackCode kHdCallbackContinue = 1;     // HD_CALLBACK_CONTINUE
constexpr HDenum kHdCurrentButtons = 0x2000;          // HD_CURRENT_BUTTONS
constexpr HDenum kHdCurrentVelocity = 0x2051;         // HD_CURRENT_VELOCITY (mm/s)
constexpr HDenum kHdCurrentTransform = 0x2052;        // HD_CURRENT_TRANSFORM (column-major, mm)
constexpr HDenum kHdCurrentAngularVelocity = 0x2053;  // HD_CURRENT_ANGULAR_VELOCITY (rad/s)
constexpr HDenum kHdCurrentForce = 0x2700;            // HD_CURRENT_FORCE (N)
constexpr HDenum kHdCurrentTorque = 0x2701;           // HD_CURRENT_TORQUE (mN·m)
constexpr HDenum kHdForceOutput = 0x4000;             // HD_FORCE_OUTPUT
constexpr unsigned short kHdMaxSchedulerPriority = 0xFFFF;  // HD_MAX_SCHEDULER_PRIORITY
constexpr double kMetresPerMm = 1e-3;

struct HdApi {
  HHD (*init_device)(const char*) = nullptr;
  void (*disable_device)(HHD) = nullptr;
  void (*enable)(HDenum) = nullptr;
  HDSchedulerHandle (*schedule_asynchronous)(HDSchedulerCallback, void*, unsigned short) = nullptr;
  void (*start_scheduler)() = nullptr;
  void (*stop_scheduler)() = nullptr;
  void (*unschedule)(HDSchedulerHandle) = nullptr;
  void (*begin_frame)(HHD) = nullptr;
  void (*end_frame)(HHD) = nullptr;
  void (*get_doublev)(HDenum, double*) = nullptr;
  void (*set_doublev)(HDenum, const double*) = nullptr;
  HDErrorInfo (*get_error)() = nullptr;
  void (*get_integerv)(HDenum, int*) = nullptr;        // optional: buttons
  const char* (*get_error_string)(HDerror) = nullptr;  // optional: messages
  void (*schedule_synchronous)(HDSchedulerCallback, void*, unsigned short) = nullptr;  // optional
  void (*make_current_device)(HHD) = nullptr;  // optional: needed for several devices
};

// HD runs one scheduler per process for every device. Devices join and leave with it stopped
// (HD initializes and disables devices while no servo callback runs), and it runs while any
// device is open: closing one device must not stop another's servo loop.
struct SharedScheduler {
  std::mutex mutex;
  int open_devices = 0;
};

SharedScheduler& Scheduler() {
  static SharedScheduler scheduler;
  return scheduler;
}

HdApi ResolveHd(const internal::DynamicLibrary& lib) {
  HdApi api;
  lib.Require("hdInitDevice", &api.init_device);
  lib.Require("hdDisableDevice", &api.disable_device);
  lib.Require("hdEnable", &api.enable);
  lib.Require("hdScheduleAsynchronous", &api.schedule_asynchronous);
  lib.Require("hdStartScheduler", &api.start_scheduler);
  lib.Require("hdStopScheduler", &api.stop_scheduler);
  lib.Require("hdUnschedule", &api.unschedule);
  lib.Require("hdBeginFrame", &api.begin_frame);
  lib.Require("hdEndFrame", &api.end_frame);
  lib.Require("hdGetDoublev", &api.get_doublev);
  lib.Require("hdSetDoublev", &api.set_doublev);
  lib.Require("hdGetError", &api.get_error);
  lib.Probe("hdGetIntegerv", &api.get_integerv);
  lib.Probe("hdGetErrorString", &api.get_error_string);
  lib.Probe("hdScheduleSynchronous", &api.schedule_synchronous);
  lib.Probe("hdMakeCurrentDevice", &api.make_current_device);
  return api;
}

class OpenHapticsDevice final : public ServoDevice {
 public:
  OpenHapticsDevice(const OpenHapticsSettings& settings, const Specifications& specs)
      : lib_(settings.library, "OpenHaptics HD library (device.library)"),
        api_(ResolveHd(lib_)),
        specs_(specs),
        name_(settings.name) {}

  ~OpenHapticsDevice() override { Close(); }

  const Specifications& specifications() const override { return specs_; }

  void SetServoClient(ServoClient* client) override { client_.store(client); }

  void Open() override;
  void Close() override;

  DeviceState Read(double t) noexcept override {
    states_.Update();
    DeviceState s = states_.read_slot();
    s.t = t;
    return s;
  }

  void SetWrench(const Wrench& w_D) noexcept override {
    wrenches_.write_slot() = w_D;
    wrenches_.Publish();
  }

  DeviceCounters counters() const override { return counters_.Load(); }

  std::string last_error() const override {
    const HDerror code = last_error_code_.load();
    if (code == kHdSuccess) return {};
    const char* text = api_.get_error_string != nullptr ? api_.get_error_string(code) : nullptr;
    return "HD error 0x" + Hex(code) + (text != nullptr ? std::string(" (") + text + ")" : "");
  }

 private:
  static HDCallbackCode ServoCallback(void* self) {
    return static_cast<OpenHapticsDevice*>(self)->ServoTick();
  }

  static HDCallbackCode ReadOnceCallback(void* self) {
    auto* device = static_cast<OpenHapticsDevice*>(self);
    device->MakeCurrent();
    device->api_.begin_frame(device->hhd_);
    device->PublishReading(0.0);
    device->api_.end_frame(device->hhd_);
    return kHdCallbackDone;
  }

  HDCallbackCode ServoTick() noexcept;

  // HD's get/set calls act on the current device; with several, each callback selects its own.
  void MakeCurrent() noexcept {
    if (api_.make_current_device != nullptr) api_.make_current_device(hhd_);
  }

  DeviceState PublishReading(double t) noexcept;
  void WriteWrench(const Wrench& w_D) noexcept;
  bool CheckHd() noexcept;
  std::string OpenError(const std::string& step);

  static std::string Hex(unsigned int value) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string text(4, '0');
    for (int i = 3; i >= 0; --i, value >>= 4)
      text[static_cast<std::size_t>(i)] = kDigits[value & 0xF];
    return text;
  }

  internal::DynamicLibrary lib_;
  HdApi api_;
  Specifications specs_;
  std::string name_;
  HHD hhd_ = kHdInvalidHandle;
  HDSchedulerHandle callback_ = 0;
  bool scheduled_ = false;
  std::atomic<ServoClient*> client_{nullptr};
  std::atomic<bool> zero_output_{false};
  std::atomic<HDerror> last_error_code_{kHdSuccess};
  std::chrono::steady_clock::time_point t0_;
  TripleBuffer<DeviceState> states_;  // servo callback → Read()
  TripleBuffer<Wrench> wrenches_;     // SetWrench() → servo callback
  Wrench commanded_;                  // servo thread only
  internal::AtomicCounters counters_;
};

std::string OpenHapticsDevice::OpenError(const std::string& step) {
  const HDErrorInfo error = api_.get_error();
  last_error_code_.store(error.errorCode);
  return "openhaptics device" + (name_.empty() ? std::string() : " \"" + name_ + "\"") + ": " +
         step + " failed: " + last_error() + ", internal code " +
         std::to_string(error.internalErrorCode) +
         " (is the device configured with Touch Setup and allowed by udev?)";
}

void OpenHapticsDevice::Open() {
  if (scheduled_) return;
  SharedScheduler& scheduler = Scheduler();
  const std::lock_guard<std::mutex> lock(scheduler.mutex);
  const bool others = scheduler.open_devices > 0;
  if (others) api_.stop_scheduler();
  hhd_ = api_.init_device(name_.empty() ? nullptr : name_.c_str());  // nullptr = HD_DEFAULT_DEVICE
  if (hhd_ == kHdInvalidHandle || api_.get_error().errorCode != kHdSuccess) {
    hhd_ = kHdInvalidHandle;
    const std::string message = OpenError("hdInitDevice");
    if (others) api_.start_scheduler();
    throw RuntimeError(message);
  }
  MakeCurrent();
  api_.enable(kHdForceOutput);
  callback_ = api_.schedule_asynchronous(&ServoCallback, this, kHdMaxSchedulerPriority);
  api_.start_scheduler();
  if (api_.get_error().errorCode != kHdSuccess) {
    const std::string message = OpenError("hdEnable(HD_FORCE_OUTPUT) / hdStartScheduler");
    api_.stop_scheduler();
    api_.unschedule(callback_);
    api_.disable_device(hhd_);
    hhd_ = kHdInvalidHandle;
    if (others) api_.start_scheduler();
    throw RuntimeError(message);
  }
  ++scheduler.open_devices;
  scheduled_ = true;
  zero_output_.store(false);
  t0_ = std::chrono::steady_clock::now();
  // The first reading, so that Read() right after Open() sees the real tool pose, not the
  // origin (the engine builds its first snapshot around it).
  if (api_.schedule_synchronous != nullptr) {
    api_.schedule_synchronous(&ReadOnceCallback, this, kHdMaxSchedulerPriority);
  }
}

void OpenHapticsDevice::Close() {
  if (!scheduled_) return;
  SharedScheduler& scheduler = Scheduler();
  const std::lock_guard<std::mutex> lock(scheduler.mutex);
  zero_output_.store(true);  // the callbacks still to come display zero
  api_.stop_scheduler();
  api_.unschedule(callback_);
  MakeCurrent();
  api_.disable_device(hhd_);
  hhd_ = kHdInvalidHandle;
  scheduled_ = false;
  if (--scheduler.open_devices > 0) api_.start_scheduler();
}

// One servo tick on the vendor's thread: read, get the wrench (from the client or the
// mailbox), write, and count any HD error (the tick goes on: the scheduler must keep running).
HDCallbackCode OpenHapticsDevice::ServoTick() noexcept {
  MakeCurrent();
  api_.begin_frame(hhd_);
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  const DeviceState reading = PublishReading(t);
  Wrench w;
  if (ServoClient* client = client_.load(std::memory_order_acquire)) {
    w = client->OnServoTick(t, reading);
  } else {
    wrenches_.Update();
    w = wrenches_.read_slot();
  }
  if (zero_output_.load(std::memory_order_acquire)) w = Wrench{};
  WriteWrench(w);
  api_.end_frame(hhd_);
  CheckHd();
  return kHdCallbackContinue;
}

DeviceState OpenHapticsDevice::PublishReading(double t) noexcept {
  double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double v[3] = {0, 0, 0};
  double w[3] = {0, 0, 0};
  api_.get_doublev(kHdCurrentTransform, m);
  api_.get_doublev(kHdCurrentVelocity, v);
  api_.get_doublev(kHdCurrentAngularVelocity, w);
  DeviceState& s = states_.write_slot();
  s.t = t;
  Mat3 R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R(i, j) = m[4 * j + i];  // column-major: column j at m[4j]
  }
  s.X_DT = Pose{kMetresPerMm * Vec3(m[12], m[13], m[14]), Quat(R).normalized()};
  s.V_DT = Twist{kMetresPerMm * Vec3(v[0], v[1], v[2]), Vec3(w[0], w[1], w[2])};
  int buttons = 0;
  if (api_.get_integerv != nullptr) api_.get_integerv(kHdCurrentButtons, &buttons);
  s.buttons = static_cast<std::uint32_t>(buttons);
  const DeviceState copy = s;
  states_.Publish();
  return copy;
}

void OpenHapticsDevice::WriteWrench(const Wrench& w_D) noexcept {
  const Wrench w = internal::DropTorqueIfNoTorque(specs_, w_D, &counters_);
  commanded_ = w;
  const double f[3] = {w.f.x(), w.f.y(), w.f.z()};
  api_.set_doublev(kHdCurrentForce, f);
  if (specs_.has_torque) {
    constexpr double kMilliNewtonMetresPerNm = 1e3;
    const double tau[3] = {kMilliNewtonMetresPerNm * w.tau.x(), kMilliNewtonMetresPerNm * w.tau.y(),
                           kMilliNewtonMetresPerNm * w.tau.z()};
    api_.set_doublev(kHdCurrentTorque, tau);
  }
}

bool OpenHapticsDevice::CheckHd() noexcept {
  // hdGetError pops one error off HD's stack: drain a few so one bad tick is not reported on
  // every later tick (bounded: the stack is small).
  constexpr int kMaxErrorsPerTick = 8;
  bool ok = true;
  for (int i = 0; i < kMaxErrorsPerTick; ++i) {
    const HDErrorInfo error = api_.get_error();
    if (error.errorCode == kHdSuccess) break;
    ok = false;
    last_error_code_.store(error.errorCode, std::memory_order_relaxed);
    internal::AtomicCounters::Bump(counters_.vendor_errors);
  }
  return ok;
}

}  // namespace

std::unique_ptr<Device> MakeOpenHapticsDevice(const OpenHapticsSettings& settings,
                                              const Specifications& specs) {
  return std::make_unique<OpenHapticsDevice>(settings, specs);
}

}  // namespace mrh::device
