// common/check.h — invariants that must hold whatever the input (programming errors, not bad
// input). SOFTMOL_CHECK is always on; SOFTMOL_DCHECK only in debug builds. Bad input is reported
// with io::InputError instead (io/error.h), never with these.
#pragma once

#include <cstdio>
#include <cstdlib>

#define SOFTMOL_CHECK(cond)                                                           \
  do {                                                                                \
    if (!(cond)) {                                                                    \
      std::fprintf(stderr, "softmol: internal check failed at %s:%d: %s\n", __FILE__, \
                   __LINE__, #cond);                                                  \
      std::abort();                                                                   \
    }                                                                                 \
  } while (0)

#ifdef NDEBUG
#define SOFTMOL_DCHECK(cond) \
  do {                       \
  } while (0)
#else
#define SOFTMOL_DCHECK(cond) SOFTMOL_CHECK(cond)
#endif
