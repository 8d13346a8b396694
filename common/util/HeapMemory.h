#pragma once

#include <cstddef>

namespace igi {

/// The C heap as the allocator sees it (glibc's mallinfo2).
struct HeapFigures {
    std::size_t inUse = 0;  ///< bytes in live allocations
    std::size_t held = 0;   ///< bytes the allocator has from the system, free chunks included
};
HeapFigures heapFigures();

/// Gives the free pages the allocator keeps back to the system (malloc_trim), and returns how
/// many bytes of resident memory that released. Why it is needed: glibc returns an arena's free
/// memory only from its top, so threads that allocate in bursts (a client when its queue of
/// tiles deepens) leave it resident at the burst's high water, and a long session's resident
/// memory climbs in steps although nothing leaks (docs/SECURITY.md).
std::size_t releaseFreeHeap();

/// This process's resident memory in bytes (/proc/self/statm), or 0 where that cannot be read.
std::size_t residentBytes();

}  // namespace igi
