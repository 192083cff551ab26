// SPDX-License-Identifier: Apache-2.0
// Replacement global operator new/delete that count calls while an AllocGuard is armed.
#include "support/alloc_guard.h"

#include <cstdlib>
#include <new>

namespace {

// Constant-initialized thread_locals: no dynamic initialization, so they are safe to touch from
// operator new at any point of the program's life.
thread_local int tl_armed_depth = 0;
thread_local std::int64_t tl_allocations = 0;
thread_local std::int64_t tl_deallocations = 0;

void* Allocate(std::size_t size) noexcept {
  if (tl_armed_depth > 0) ++tl_allocations;
  // malloc(0) may return null; operator new must return a unique pointer.
  return std::malloc(size == 0 ? 1 : size);
}

void* AllocateAligned(std::size_t size, std::align_val_t alignment) noexcept {
  if (tl_armed_depth > 0) ++tl_allocations;
  const auto align = static_cast<std::size_t>(alignment);
  // aligned_alloc wants a size that is a non-zero multiple of the alignment.
  const std::size_t rounded = ((size == 0 ? 1 : size) + align - 1) / align * align;
  return std::aligned_alloc(align, rounded);
}

void Free(void* p) noexcept {
  if (p == nullptr) return;
  if (tl_armed_depth > 0) ++tl_deallocations;
  std::free(p);
}

// The throwing forms retry through the new-handler as the standard requires.
void* AllocateOrThrow(std::size_t size) {
  while (true) {
    if (void* p = Allocate(size)) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

void* AllocateAlignedOrThrow(std::size_t size, std::align_val_t alignment) {
  while (true) {
    if (void* p = AllocateAligned(size, alignment)) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

namespace mrh::testing {

AllocGuard::AllocGuard() noexcept
    : start_allocations_(tl_allocations), start_deallocations_(tl_deallocations) {
  ++tl_armed_depth;
}

AllocGuard::~AllocGuard() {
  --tl_armed_depth;
}

std::int64_t AllocGuard::count() const noexcept {
  return tl_allocations - start_allocations_;
}

std::int64_t AllocGuard::deallocations() const noexcept {
  return tl_deallocations - start_deallocations_;
}

}  // namespace mrh::testing

void* operator new(std::size_t size) {
  return AllocateOrThrow(size);
}

void* operator new[](std::size_t size) {
  return AllocateOrThrow(size);
}

void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return Allocate(size);
}

void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return Allocate(size);
}

void* operator new(std::size_t size, std::align_val_t al) {
  return AllocateAlignedOrThrow(size, al);
}

void* operator new[](std::size_t size, std::align_val_t al) {
  return AllocateAlignedOrThrow(size, al);
}

void* operator new(std::size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  return AllocateAligned(size, al);
}

void* operator new[](std::size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  return AllocateAligned(size, al);
}

void operator delete(void* p) noexcept {
  Free(p);
}

void operator delete[](void* p) noexcept {
  Free(p);
}

void operator delete(void* p, std::size_t) noexcept {
  Free(p);
}

void operator delete[](void* p, std::size_t) noexcept {
  Free(p);
}

void operator delete(void* p, const std::nothrow_t&) noexcept {
  Free(p);
}

void operator delete[](void* p, const std::nothrow_t&) noexcept {
  Free(p);
}

void operator delete(void* p, std::align_val_t) noexcept {
  Free(p);
}

void operator delete[](void* p, std::align_val_t) noexcept {
  Free(p);
}

void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  Free(p);
}

void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  Free(p);
}

void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  Free(p);
}

void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  Free(p);
}
