#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace igi {

struct HostPort {
    std::string host;
    std::uint16_t port = 0;
};

/// Parses "HOST:PORT" (the port may be 0: any free one). Throws std::invalid_argument naming
/// the option and what is wrong.
inline HostPort parseHostPort(const std::string& text, const std::string& option) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0)
        throw std::invalid_argument(option + " needs HOST:PORT, got '" + text + "'");
    HostPort hp;
    hp.host = text.substr(0, colon);
    const std::string port = text.substr(colon + 1);
    std::size_t used = 0;
    int value = -1;
    try {
        value = std::stoi(port, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != port.size() || port.empty() || value < 0 || value > 65535)
        throw std::invalid_argument(option + ": '" + port + "' is not a port number");
    hp.port = static_cast<std::uint16_t>(value);
    return hp;
}

}  // namespace igi
