#include "ControlServer.h"

#include <spdlog/spdlog.h>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>

namespace igi {
namespace {

using boost::asio::ip::tcp;

/// One control connection: read a line, hand it over, write the reply, repeat.
class ControlSession : public std::enable_shared_from_this<ControlSession> {
  public:
    ControlSession(tcp::socket socket, ControlServer::Handler& handler)
        : socket_(std::move(socket)), buffer_(ControlServer::kMaxLine), handler_(handler) {}

    void read() {
        boost::asio::async_read_until(
            socket_, buffer_, '\n',
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                self->onLine(ec, n);
            });
    }

  private:
    void onLine(const boost::system::error_code& ec, std::size_t n) {
        if (ec) {
            // A line longer than the limit fills the buffer without a newline: say so, then drop.
            if (ec == boost::asio::error::not_found)
                write("{\"ok\":false,\"error\":\"command line too long\"}\n", true);
            return;
        }
        std::string line(boost::asio::buffers_begin(buffer_.data()),
                         boost::asio::buffers_begin(buffer_.data()) + n);
        buffer_.consume(n);
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
        if (line.empty()) return read();
        handler_(line, [self = shared_from_this()](std::string reply) {
            self->write(std::move(reply) + "\n", false);
        });
    }

    void write(std::string text, bool last) {
        auto data = std::make_shared<std::string>(std::move(text));
        boost::asio::async_write(socket_, boost::asio::buffer(*data),
                                 [self = shared_from_this(), data, last](
                                     const boost::system::error_code& ec, std::size_t) {
                                     if (!ec && !last) self->read();
                                 });
    }

    tcp::socket socket_;
    boost::asio::streambuf buffer_;
    ControlServer::Handler& handler_;
};

}  // namespace

ControlServer::ControlServer(boost::asio::io_context& io, const std::string& host,
                             std::uint16_t port, Handler handler)
    : acceptor_(io), handler_(std::move(handler)) {
    const tcp::endpoint endpoint(boost::asio::ip::make_address(host), port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen();
    accept();
}

ControlServer::~ControlServer() {
    close();
}

std::uint16_t ControlServer::port() const {
    return acceptor_.local_endpoint().port();
}

void ControlServer::close() {
    boost::system::error_code ignored;
    acceptor_.close(ignored);
}

void ControlServer::accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
        if (ec) return;  // closed
        std::make_shared<ControlSession>(std::move(socket), handler_)->read();
        accept();
    });
}

}  // namespace igi
