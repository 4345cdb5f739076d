#include "server/sessions/heap_trim.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace spinfold::server {

bool return_free_heap() {
#if defined(__GLIBC__)
  return malloc_trim(0) == 1;
#else
  return false;
#endif
}

bool HeapTrimmer::tick(Clock::time_point now) {
  if (now - last_ < interval_) return false;
  last_ = now;
  return_free_heap();
  return true;
}

}  // namespace spinfold::server
