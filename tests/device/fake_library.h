// SPDX-License-Identifier: Apache-2.0
// Opens a fake vendor library (built by the tests) a second time to reach its fakexx_*
// controls: dlopen of the same path returns the same handle, so the device and the test share
// the fake's state.
#pragma once

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <string>

namespace mrh::device::testing {

class FakeLibrary {
 public:
  explicit FakeLibrary(const std::string& path)
      : handle_(::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
    if (handle_ == nullptr) ADD_FAILURE() << "cannot load " << path << ": " << ::dlerror();
  }

  ~FakeLibrary() {
    if (handle_ != nullptr) (void)::dlclose(handle_);
  }

  FakeLibrary(const FakeLibrary&) = delete;
  FakeLibrary& operator=(const FakeLibrary&) = delete;

  /// The control or query symbol `name` as a function of type Fn.
  template <typename Fn>
  Fn* Get(const char* name) const {
    void* symbol = handle_ != nullptr ? ::dlsym(handle_, name) : nullptr;
    if (symbol == nullptr) ADD_FAILURE() << "fake lacks " << name;
    return reinterpret_cast<Fn*>(symbol);
  }

 private:
  void* handle_;
};

}  // namespace mrh::device::testing
