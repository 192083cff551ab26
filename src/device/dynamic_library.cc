// SPDX-License-Identifier: Apache-2.0
// DynamicLibrary: dlopen/dlsym with errors that name the library, the symbol and dlerror().
#include "device/dynamic_library.h"

#include <dlfcn.h>

#include "mrh/core/error.h"

namespace mrh::device::internal {
namespace {

std::string LastDlError() {
  const char* error = ::dlerror();
  return error != nullptr ? std::string(error) : std::string("no reason given");
}

}  // namespace

DynamicLibrary::DynamicLibrary(const std::string& path, const std::string& what)
    : path_(path), what_(what) {
  // RTLD_NOW: a library missing one of its own dependencies fails here, at setup, not on the
  // haptic thread at the first lazy call. RTLD_LOCAL: vendor symbols stay out of our namespace.
  ::dlerror();
  handle_ = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) {
    throw InvalidArgument("cannot load the " + what_ + " \"" + path_ + "\": " + LastDlError() +
                          "; install the vendor's library or set its path");
  }
}

DynamicLibrary::~DynamicLibrary() {
  // dlclose can only fail for an invalid handle, which would be our bug; nothing to do then.
  if (handle_ != nullptr) (void)::dlclose(handle_);
}

DynamicLibrary::DynamicLibrary(DynamicLibrary&& other) noexcept
    : path_(std::move(other.path_)), what_(std::move(other.what_)), handle_(other.handle_) {
  other.handle_ = nullptr;
}

void* DynamicLibrary::Find(const char* name, bool required) const {
  ::dlerror();
  void* symbol = ::dlsym(handle_, name);
  if (symbol == nullptr && required) {
    throw InvalidArgument("the " + what_ + " \"" + path_ + "\" lacks the required symbol " + name +
                          ": " + LastDlError() + "; is it the right library and version?");
  }
  return symbol;
}

}  // namespace mrh::device::internal
