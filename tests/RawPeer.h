#pragma once
// One end of a TCP connection that speaks the protocol by hand, for tests that play a hostile
// client or an impostor master: it sends whatever bytes it is given and reads messages with a
// deadline, so that a peer that never answers fails the test instead of hanging it.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "Codec.h"
#include "Messages.h"

namespace igi::testing {

class RawPeer {
  public:
    explicit RawPeer(int fd = -1) : fd_(fd) {}
    RawPeer(RawPeer&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}
    RawPeer& operator=(RawPeer&& o) noexcept {
        std::swap(fd_, o.fd_);
        return *this;
    }
    ~RawPeer() {
        if (fd_ >= 0) ::close(fd_);
    }

    /// Connects to a loopback port.
    static RawPeer connectTo(int port) {
        const int fd = socket(AF_INET, SOCK_STREAM, 0);
        const sockaddr_in address = loopback(port);
        if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
            ::close(fd);
            return RawPeer();
        }
        return RawPeer(fd);
    }

    bool valid() const { return fd_ >= 0; }

    bool send(const std::vector<std::uint8_t>& bytes) {
        std::size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
            if (n <= 0) return false;
            done += std::size_t(n);
        }
        return true;
    }
    bool send(const proto::Message& message) { return send(proto::encodeMessage(message, 0, 0)); }

    /// The next message, or nothing if the peer closed, sent garbage or said nothing in time.
    std::optional<proto::Message> receive(double seconds = 20) {
        std::array<std::uint8_t, proto::kHeaderSize> header{};
        if (!read(header.data(), header.size(), seconds)) return std::nullopt;
        try {
            const proto::Header h = proto::decodeHeader(header);
            std::vector<std::uint8_t> payload(h.payloadSize);
            if (!read(payload.data(), payload.size(), seconds)) return std::nullopt;
            return proto::decodeMessage(h, payload);
        } catch (const proto::ProtocolError&) {
            return std::nullopt;
        }
    }

    /// Reads and discards until the peer closes (true) or `seconds` pass (false).
    bool closedByPeer(double seconds = 20) {
        std::uint8_t sink[4096];
        const auto deadline = deadlineIn(seconds);
        for (;;) {
            if (!wait(deadline)) return false;
            const ssize_t n = ::recv(fd_, sink, sizeof sink, 0);
            if (n <= 0) return true;
        }
    }

  private:
    using Clock = std::chrono::steady_clock;

    static sockaddr_in loopback(int port) {
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        address.sin_port = htons(std::uint16_t(port));
        return address;
    }
    static Clock::time_point deadlineIn(double seconds) {
        return Clock::now() +
               std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    }
    bool wait(Clock::time_point deadline) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return false;
        pollfd p{fd_, POLLIN, 0};
        return poll(&p, 1, int(left)) > 0;
    }
    bool read(std::uint8_t* out, std::size_t size, double seconds) {
        const auto deadline = deadlineIn(seconds);
        std::size_t done = 0;
        while (done < size) {
            if (!wait(deadline)) return false;
            const ssize_t n = ::recv(fd_, out + done, size - done, 0);
            if (n <= 0) return false;
            done += std::size_t(n);
        }
        return true;
    }

    int fd_;
};

/// A listening loopback socket on any free port, for a test that plays the master.
class RawListener {
  public:
    RawListener() : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t size = sizeof address;
        bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address);
        listen(fd_, 4);
        getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &size);
        port_ = ntohs(address.sin_port);
    }
    ~RawListener() { ::close(fd_); }
    RawListener(const RawListener&) = delete;
    RawListener& operator=(const RawListener&) = delete;

    int port() const { return port_; }

    /// The next connection, or an invalid peer after `seconds`.
    RawPeer accept(double seconds = 20) {
        pollfd p{fd_, POLLIN, 0};
        if (poll(&p, 1, int(seconds * 1000)) <= 0) return RawPeer();
        return RawPeer(::accept(fd_, nullptr, nullptr));
    }

  private:
    int fd_;
    int port_ = 0;
};

}  // namespace igi::testing
