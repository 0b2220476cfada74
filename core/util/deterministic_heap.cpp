// disco — fresh heap memory with the same bytes in every process (deterministic_heap.h).
#include "core/util/deterministic_heap.h"

#include <cstdlib>
#include <new>

// The replacements of the global operator new below are in this file so that a program that
// calls make_heap_deterministic() links them (a static library's object file is linked when one
// of its symbols is used). Not under a sanitizer, which replaces them itself and fills fresh
// memory with a fixed byte.
#if !defined(__SANITIZE_ADDRESS__)
namespace {

void* zeroed(std::size_t n) {
  for (;;) {
    if (void* p = std::calloc(1, n == 0 ? 1 : n)) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

void* operator new(std::size_t n) { return zeroed(n); }
void* operator new[](std::size_t n) { return zeroed(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return zeroed(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return zeroed(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace disco {

bool make_heap_deterministic() {
#if !defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return false;
#endif
}

}  // namespace disco
