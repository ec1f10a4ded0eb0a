// cli/heap_policy.h — how the `softmol` process asks glibc's allocator to treat memory: keep
// what it frees for the next allocation instead of handing it back to the kernel, in a heap
// backed by transparent huge pages.
#pragma once

namespace softmol::cli {

// Call first thing in main(), before the work allocates. Process-wide, so only the executable
// calls it (never the library or the Python module, whose host owns its own heap). A no-op where
// the C library is not glibc.
void KeepFreedMemoryInTheHeap();

}  // namespace softmol::cli
