// SPDX-License-Identifier: Apache-2.0
// A stand-in for OpenHaptics' libHD.so: the HD symbols mrhaptics uses, a servo "scheduler" the
// test drives by hand (fakehd_RunServoTicks), a scripted transform and recorded forces.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace {

using HDCallback = unsigned int (*)(void*);

struct HDErrorInfo {
  unsigned int errorCode;
  int internalErrorCode;
  unsigned int hHD;
};

constexpr int kMaxRecords = 20000;
constexpr unsigned int kInvalidHandle = 0xFFFFFFFFu;
constexpr unsigned int kFakeError = 0x0100;  // any nonzero HDerror

struct State {
  bool fail_init = false;
  int fail_frames = 0;  // the next n servo ticks push an error
  unsigned int pending_error = 0;
  char name[64] = "";
  bool initialized = false, force_output = false, scheduler = false, disabled = false;
  HDCallback callback = nullptr;
  void* data = nullptr;
  bool scheduled = false;
  // A second scheduled callback (a second device), run after the first on each servo tick.
  HDCallback callback2 = nullptr;
  void* data2 = nullptr;
  bool scheduled2 = false;
  unsigned long next_schedule_handle = 7;
  unsigned int next_device = 1;  // hdInitDevice's handles: 1, 2, ...
  unsigned int current = 0;      // the current device (hdInitDevice, hdMakeCurrentDevice)
  int start_calls = 0, stop_calls = 0;
  unsigned int force_devices[kMaxRecords] = {};  // the current device at each force write
  int in_frame = 0;
  int frames = 0;
  double transform[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double velocity[3] = {0, 0, 0};
  int buttons = 0;
  int records = 0;
  double forces[kMaxRecords][3] = {};
  int torque_writes = 0;
};

State state;

// With FAKEHD_THREAD=1 in the environment the "scheduler" is a real thread ticking at ~1 kHz
// (for smoke runs of `mrh run` / `mrh view`); otherwise tests tick it by hand.
std::thread scheduler_thread;
std::atomic<bool> scheduler_quit{false};
std::atomic<HDCallback> sync_callback{nullptr};  // run once on the scheduler thread, as in HD
void* sync_data = nullptr;

void SchedulerLoop() {
  while (!scheduler_quit.load()) {
    if (HDCallback cb = sync_callback.load()) {
      (void)cb(sync_data);
      sync_callback.store(nullptr);
    }
    if (state.scheduled && state.callback(state.data) == 0) state.scheduled = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

extern "C" {

// HD API (signatures of OpenHaptics' HD/hdDevice.h and HD/hdScheduler.h).
unsigned int hdInitDevice(const char* name) {
  std::strncpy(state.name, name != nullptr ? name : "(default)", sizeof(state.name) - 1);
  if (state.fail_init) {
    state.pending_error = kFakeError;
    return kInvalidHandle;
  }
  state.initialized = true;
  state.current = state.next_device++;
  return state.current;
}

void hdMakeCurrentDevice(unsigned int hhd) {
  state.current = hhd;
}

void hdDisableDevice(unsigned int) {
  state.disabled = true;
}

void hdEnable(unsigned int cap) {
  state.force_output = state.force_output || cap == 0x4000;
}

// The first callback takes handle 7, a second one while the first is scheduled handle 8.
unsigned long hdScheduleAsynchronous(HDCallback cb, void* data, unsigned short) {
  if (state.scheduled) {
    state.callback2 = cb;
    state.data2 = data;
    state.scheduled2 = true;
    return 8;
  }
  state.callback = cb;
  state.data = data;
  state.scheduled = true;
  return 7;
}

void hdScheduleSynchronous(HDCallback cb, void* data, unsigned short) {
  if (!scheduler_thread.joinable()) {
    (void)cb(data);
    return;
  }
  sync_data = data;
  sync_callback.store(cb);
  while (sync_callback.load() != nullptr)
    std::this_thread::sleep_for(std::chrono::microseconds(100));
}

void hdStartScheduler() {
  ++state.start_calls;
  state.scheduler = true;
  const char* threaded = std::getenv("FAKEHD_THREAD");
  if (threaded != nullptr && threaded[0] == '1' && !scheduler_thread.joinable()) {
    scheduler_quit.store(false);
    scheduler_thread = std::thread(SchedulerLoop);
  }
}

void hdStopScheduler() {
  ++state.stop_calls;
  scheduler_quit.store(true);
  if (scheduler_thread.joinable()) scheduler_thread.join();
  state.scheduler = false;
}

void hdUnschedule(unsigned long handle) {
  if (handle == 8) {
    state.scheduled2 = false;
  } else {
    state.scheduled = false;
  }
}

void hdBeginFrame(unsigned int) {
  ++state.in_frame;
}

void hdEndFrame(unsigned int) {
  --state.in_frame;
  ++state.frames;
}

void hdGetDoublev(unsigned int what, double* out) {
  if (what == 0x2052) std::memcpy(out, state.transform, sizeof(state.transform));
  if (what == 0x2051) std::memcpy(out, state.velocity, sizeof(state.velocity));
  if (what == 0x2053) out[0] = out[1] = out[2] = 0.0;
}

void hdGetIntegerv(unsigned int what, int* out) {
  if (what == 0x2000) *out = state.buttons;
}

void hdSetDoublev(unsigned int what, const double* v) {
  if (what == 0x2701) ++state.torque_writes;
  if (what != 0x2700 || state.records >= kMaxRecords) return;
  state.force_devices[state.records] = state.current;
  std::memcpy(state.forces[state.records++], v, 3 * sizeof(double));
}

HDErrorInfo hdGetError() {
  HDErrorInfo info{state.pending_error, state.pending_error != 0 ? 42 : 0, 1};
  state.pending_error = 0;
  return info;
}

const char* hdGetErrorString(unsigned int) {
  return "fake HD error";
}

// Test controls and queries.
void fakehd_Reset() {
  state = State{};
}

void fakehd_FailInit(int on) {
  state.fail_init = on != 0;
}

void fakehd_FailFrames(int n) {
  state.fail_frames = n;
}

void fakehd_SetTransform(const double m[16]) {
  std::memcpy(state.transform, m, sizeof(state.transform));
}

void fakehd_SetVelocity(const double v[3]) {
  std::memcpy(state.velocity, v, sizeof(state.velocity));
}

void fakehd_SetButtons(int b) {
  state.buttons = b;
}

// Runs n servo ticks of the scheduled callback on the calling thread; returns how many ran
// (a callback that returns HD_CALLBACK_DONE is unscheduled, as in HD).
int fakehd_RunServoTicks(int n) {
  int ran = 0;
  for (; ran < n && state.scheduler && (state.scheduled || state.scheduled2); ++ran) {
    if (state.fail_frames > 0) {
      --state.fail_frames;
      state.pending_error = kFakeError;
    }
    if (state.scheduled && state.callback(state.data) == 0) state.scheduled = false;
    if (state.scheduled2 && state.callback2(state.data2) == 0) state.scheduled2 = false;
  }
  return ran;
}

int fakehd_ForceCount() {
  return state.records;
}

void fakehd_Force(int i, double out[3]) {
  std::memcpy(out, state.forces[i], 3 * sizeof(double));
}

unsigned int fakehd_ForceDevice(int i) {
  return state.force_devices[i];
}

int fakehd_StartCalls() {
  return state.start_calls;
}

int fakehd_StopCalls() {
  return state.stop_calls;
}

int fakehd_TorqueWrites() {
  return state.torque_writes;
}

int fakehd_ForceOutputEnabled() {
  return state.force_output ? 1 : 0;
}

int fakehd_SchedulerRunning() {
  return state.scheduler ? 1 : 0;
}

int fakehd_Disabled() {
  return state.disabled ? 1 : 0;
}

int fakehd_Unbalanced() {
  return state.in_frame;
}

const char* fakehd_DeviceName() {
  return state.name;
}

}  // extern "C"
