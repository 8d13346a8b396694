#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <boost/system/system_error.hpp>

namespace igi {

/// Runs `open`, which opens a listening port; a port that cannot be opened ("bind: Address
/// already in use") is the user's to fix, so the error says which flag and which address.
template <typename Open>
auto openPort(const std::string& flag, const std::string& host, int port, Open open) {
    try {
        return open();
    } catch (const boost::system::system_error& e) {
        throw std::runtime_error(
            fmt::format("{} {}:{}: cannot listen there: {}", flag, host, port, e.code().message()));
    }
}

}  // namespace igi
