#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "ControlServer.h"

namespace igi {

/// The web view (docs/VIEW.md): serves one page over HTTP and pushes every composited frame
/// to each browser connected to its WebSocket, with the session's status. What a browser sends
/// on the WebSocket are control commands, one JSON object per message, handled by the same
/// handler as the control port's lines (one code path, one set of validations); each reply
/// comes back as {"type":"reply","id":N,"reply":{...}}, N counting that connection's commands
/// from 0.
///
/// With a token, the page and the WebSocket need ?token=... in their URL (the master makes
/// one whenever the view listens off loopback: whoever holds it can do what the control port
/// can). Runs on the master's io thread, like everything else of the session.
class ViewServer {
  public:
    struct Options {
        std::string host = "127.0.0.1";
        std::uint16_t port = 0;  ///< 0: any free port
        std::string token;       ///< empty: none asked for
        std::string page;        ///< the HTML served at /
    };

    ViewServer(boost::asio::io_context& io, Options options, ControlServer::Handler handler);
    ~ViewServer();

    std::uint16_t port() const;
    /// Browsers connected to the WebSocket now.
    std::size_t viewers() const;
    /// Sends one frame (a frameMessage) to every viewer. A viewer still sending an earlier
    /// frame gets only the newest one when it is done: a slow browser skips frames, it never
    /// makes them queue up in the master.
    void publish(std::shared_ptr<const std::string> frame);
    /// Stops accepting and closes every viewer.
    void close();

    /// A frame as sent: the status JSON's length (4 bytes, little-endian), the status JSON,
    /// then the JPEG file.
    static std::shared_ptr<const std::string> frameMessage(const std::string& statusJson,
                                                           const std::string& jpeg);

    /// Largest message a browser may send (as a control-port line); a bigger one closes it.
    static constexpr std::size_t kMaxMessage = ControlServer::kMaxLine;

    struct Shared;

  private:
    void accept();

    boost::asio::ip::tcp::acceptor acceptor_;
    std::shared_ptr<Shared> shared_;
};

}  // namespace igi
