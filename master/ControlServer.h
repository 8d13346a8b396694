#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

namespace igi {

/// The master's control port: newline-delimited JSON commands from other processes (igi-ctl),
/// one JSON reply line per command. Lines are limited in length and the port listens where it
/// is told (loopback by default: whoever reaches it can move the scene and stop the session).
class ControlServer {
  public:
    using Reply = std::function<void(std::string line)>;
    /// Handles one command line; calls `reply` once, now or later, with the reply line.
    using Handler = std::function<void(const std::string& line, Reply reply)>;

    ControlServer(boost::asio::io_context& io, const std::string& host, std::uint16_t port,
                  Handler handler);
    ~ControlServer();

    std::uint16_t port() const;
    void close();

    static constexpr std::size_t kMaxLine = 64 * 1024;

  private:
    void accept();

    boost::asio::ip::tcp::acceptor acceptor_;
    Handler handler_;
};

}  // namespace igi
