// The OpenMP team of the calling thread, with the serial answers when OpenMP is off: for code
// that splits work by thread number inside a parallel region.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace craterkit {

inline int threadCount() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

inline int threadNumber() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

} // namespace craterkit
