#include "ViewPage.h"

namespace igi {

const std::string& viewPage() {
    static const std::string page =
#include "ViewPage.inc"
        ;
    return page;
}

}  // namespace igi
