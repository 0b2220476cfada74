// disco — fresh heap memory with the same bytes in every process (deterministic_heap.h).
#include "core/util/deterministic_heap.h"

#include <cstdlib>
#include <new>

// The replacement of the global operator new is in this file so that a program that calls
// make_heap_deterministic() links it (a static library's object file is linked when one of its
// symbols is used). It is the one needed: the standard's default array and nothrow forms call
// it, and the default array deletes call the deletes below (the sized one too, as GCC asks). Not under a
// sanitizer, which replaces them itself and fills fresh memory with a fixed byte.
#if !defined(__SANITIZE_ADDRESS__)
void* operator new(std::size_t n) {
  for (;;) {
    if (void* p = std::calloc(1, n == 0 ? 1 : n)) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
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
