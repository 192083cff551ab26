// SPDX-License-Identifier: Apache-2.0
// A stand-in for Force Dimension's libdhd.so: the DHD C symbols mrhaptics requires, a scripted
// tool pose, and every force it receives recorded for the tests (fakedhd_* query symbols).
#include <cstring>

namespace {

constexpr int kMaxRecords = 20000;

struct State {
  bool open = false;
  bool force_enabled = false;
  int open_calls = 0, close_calls = 0;
  bool fail_open = false;
  int fail_reads = 0;   // the next n position reads fail
  int fail_writes = 0;  // the next n force writes fail
  const char* error = "no error";
  double p[3] = {0, 0, 0};
  double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double v[3] = {0, 0, 0};
  int buttons = 0;
  int records = 0;
  double forces[kMaxRecords][6] = {};
  int force_ids[kMaxRecords] = {};  // the device ID each force was sent to
  int last_open_index = -1;         // dhdOpenID's argument
  int enabled_ids = 0;              // bit i: forces enabled on device ID i
  bool has_angular_velocity = true;
};

State state;

}  // namespace

extern "C" {

// DHD API (signatures of Force Dimension's dhdc.h).
int dhdOpen() {
  ++state.open_calls;
  if (state.fail_open) {
    state.error = "fake: no device found";
    return -1;
  }
  state.open = true;
  return 0;
}

// Device IDs differ from enumeration indices (index + 10), so that a caller passing the index
// where the ID belongs is seen.
int dhdOpenID(char index) {
  ++state.open_calls;
  state.last_open_index = index;
  if (state.fail_open || index < 0 || index > 3) {
    state.error = "fake: no such device";
    return -1;
  }
  state.open = true;
  return index + 10;
}

int dhdClose(char) {
  ++state.close_calls;
  state.open = false;
  return 0;
}

int dhdGetPosition(double* x, double* y, double* z, char) {
  if (state.fail_reads > 0) {
    --state.fail_reads;
    state.error = "fake: communication error";
    return -1;
  }
  *x = state.p[0];
  *y = state.p[1];
  *z = state.p[2];
  return 0;
}

int dhdGetOrientationFrame(double m[3][3], char) {
  std::memcpy(m, state.R, sizeof(state.R));
  return 0;
}

int dhdGetLinearVelocity(double* x, double* y, double* z, char) {
  *x = state.v[0];
  *y = state.v[1];
  *z = state.v[2];
  return 0;
}

int dhdSetForceAndTorque(double fx, double fy, double fz, double tx, double ty, double tz,
                         char id) {
  if (state.fail_writes > 0) {
    --state.fail_writes;
    state.error = "fake: force write failed";
    return -1;
  }
  if (state.records < kMaxRecords) {
    double* r = state.forces[state.records++];
    r[0] = fx, r[1] = fy, r[2] = fz, r[3] = tx, r[4] = ty, r[5] = tz;
    state.force_ids[state.records - 1] = id;
  }
  return 0;
}

int dhdEnableForce(unsigned char on, char id) {
  state.force_enabled = on != 0;
  if (id >= 0 && id < 31) {
    state.enabled_ids = on != 0 ? state.enabled_ids | (1 << id) : state.enabled_ids & ~(1 << id);
  }
  return 0;
}

int dhdGetButtonMask(char) {
  return state.buttons;
}

const char* dhdErrorGetLastStr() {
  return state.error;
}

const char* dhdGetSystemName(char) {
  return "fake omega.3";
}

int dhdGetAngularVelocityRad(double* x, double* y, double* z, char) {
  *x = 0.1, *y = 0.2, *z = 0.3;
  return 0;
}

// Test controls and queries.
void fakedhd_Reset() {
  state = State{};
}

void fakedhd_FailOpen(int on) {
  state.fail_open = on != 0;
}

void fakedhd_FailReads(int n) {
  state.fail_reads = n;
}

void fakedhd_FailWrites(int n) {
  state.fail_writes = n;
}

void fakedhd_SetPose(const double p[3], const double R_rowmajor[9], const double v[3],
                     int buttons) {
  std::memcpy(state.p, p, sizeof(state.p));
  std::memcpy(state.R, R_rowmajor, sizeof(state.R));
  std::memcpy(state.v, v, sizeof(state.v));
  state.buttons = buttons;
}

int fakedhd_IsOpen() {
  return state.open ? 1 : 0;
}

int fakedhd_ForceEnabled() {
  return state.force_enabled ? 1 : 0;
}

int fakedhd_OpenCalls() {
  return state.open_calls;
}

int fakedhd_CloseCalls() {
  return state.close_calls;
}

int fakedhd_ForceCount() {
  return state.records;
}

int fakedhd_ForceId(int i) {
  return state.force_ids[i];
}

int fakedhd_LastOpenIndex() {
  return state.last_open_index;
}

int fakedhd_EnabledIds() {
  return state.enabled_ids;
}

void fakedhd_Force(int i, double out[6]) {
  std::memcpy(out, state.forces[i], 6 * sizeof(double));
}

}  // extern "C"
