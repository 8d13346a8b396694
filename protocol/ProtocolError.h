#pragma once

#include <stdexcept>
#include <string>

namespace igi::proto {

/// Anything wrong with bytes received from a peer (or with a message too big to send): a bad
/// header, a truncated or oversized payload, an out-of-range field, corrupt compressed data.
/// The message names what is wrong, so that a closed connection's log says why.
class ProtocolError : public std::runtime_error {
  public:
    explicit ProtocolError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace igi::proto
