#include "util/HeapMemory.h"

#include <malloc.h>
#include <unistd.h>

#include <fstream>

namespace igi {

HeapFigures heapFigures() {
    const struct mallinfo2 info = mallinfo2();
    HeapFigures f;
    // Chunks of the arenas in use, plus the large blocks mmap'd one by one (always in use).
    f.inUse = info.uordblks + info.hblkhd;
    f.held = info.arena + info.hblkhd;
    return f;
}

std::size_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return 0;
    return resident * std::size_t(sysconf(_SC_PAGESIZE));
}

std::size_t releaseFreeHeap() {
    const std::size_t before = residentBytes();
    malloc_trim(0);
    const std::size_t after = residentBytes();
    return before > after ? before - after : 0;
}

}  // namespace igi
