#pragma once

#include <string>

namespace igi {

/// The web view's page (master/view/index.html, compiled in: the master serves it with no
/// files beside the executable).
const std::string& viewPage();

}  // namespace igi
