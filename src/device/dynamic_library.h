// SPDX-License-Identifier: Apache-2.0
// A vendor library opened with dlopen() and its C symbols resolved with dlsym(): nothing linked.
#pragma once

#include <string>

namespace mrh::device::internal {

/// Owns one dlopen() handle (RTLD_NOW | RTLD_LOCAL). Move-only. Not RT-safe (setup only).
class DynamicLibrary {
 public:
  /// @param what  for messages, e.g. "Force Dimension DHD library (device.library)"
  /// @throws mrh::InvalidArgument naming `what`, the path and dlerror() if it cannot be loaded.
  DynamicLibrary(const std::string& path, const std::string& what);
  ~DynamicLibrary();
  DynamicLibrary(DynamicLibrary&& other) noexcept;
  DynamicLibrary(const DynamicLibrary&) = delete;
  DynamicLibrary& operator=(const DynamicLibrary&) = delete;
  DynamicLibrary& operator=(DynamicLibrary&&) = delete;

  /// A required C symbol. @throws mrh::InvalidArgument naming the symbol, path and dlerror().
  template <typename Fn>
  void Require(const char* name, Fn** out) const {
    *out = reinterpret_cast<Fn*>(Find(name, true));
  }

  /// An optional C symbol: nullptr if absent.
  template <typename Fn>
  void Probe(const char* name, Fn** out) const {
    *out = reinterpret_cast<Fn*>(Find(name, false));
  }

  const std::string& path() const { return path_; }

 private:
  void* Find(const char* name, bool required) const;

  std::string path_;
  std::string what_;
  void* handle_ = nullptr;
};

}  // namespace mrh::device::internal
