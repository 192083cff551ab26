// SPDX-License-Identifier: Apache-2.0
// A libdhd.so stand-in that lacks required symbols (only dhdOpen): the missing-symbol error.
extern "C" int dhdOpen() {
  return 0;
}
