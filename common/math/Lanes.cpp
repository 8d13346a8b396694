#include "math/Lanes.h"

#include <cstdlib>
#include <string_view>

namespace igi::lanes {

bool hasAvx2() {
    // IGI_NO_AVX2=1 runs the baseline code on any machine: the same bits, to compare with.
    static const bool yes = [] {
        const char* off = std::getenv("IGI_NO_AVX2");
        if (off && *off && std::string_view(off) != "0") return false;
#if IGI_HAS_AVX2_TARGET
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0;
#else
        return false;
#endif
    }();
    return yes;
}

}  // namespace igi::lanes
