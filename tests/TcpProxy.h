#pragma once
// A TCP relay between clients and a master, for tests that cut connections: everything a peer
// sends is forwarded unchanged until `cut` closes every connection open at that moment (both
// ends, as a broken link or a rebooted switch would). New connections are still relayed.

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

namespace igi::testing {

class TcpProxy {
  public:
    explicit TcpProxy(std::uint16_t targetPort)
        : acceptor_(io_, {boost::asio::ip::address_v4::loopback(), 0}),
          target_(boost::asio::ip::address_v4::loopback(), targetPort) {
        accept();
        thread_ = std::thread([this] { io_.run(); });
    }
    ~TcpProxy() {
        io_.stop();
        thread_.join();
    }
    TcpProxy(const TcpProxy&) = delete;
    TcpProxy& operator=(const TcpProxy&) = delete;

    std::uint16_t port() const { return acceptor_.local_endpoint().port(); }
    int connectionsAccepted() const { return accepted_.load(); }

    /// Closes every relayed connection open now.
    void cut() {
        boost::asio::post(io_, [this] {
            for (auto& link : links_) link->close();
            links_.clear();
        });
    }

  private:
    using tcp = boost::asio::ip::tcp;

    /// Both sockets of one relayed connection and the two pumps between them.
    struct Link : std::enable_shared_from_this<Link> {
        explicit Link(boost::asio::io_context& io) : near(io), far(io) {}
        tcp::socket near, far;  // the client's side, the master's side
        std::array<char, 65536> up{}, down{};

        void start() {
            pump(near, far, up);
            pump(far, near, down);
        }
        void pump(tcp::socket& from, tcp::socket& to, std::array<char, 65536>& buffer) {
            from.async_read_some(
                boost::asio::buffer(buffer),
                [self = shared_from_this(), &from, &to, &buffer](auto ec, std::size_t n) {
                    if (ec) return self->close();
                    boost::asio::async_write(to, boost::asio::buffer(buffer.data(), n),
                                             [self, &from, &to, &buffer](auto ec2, std::size_t) {
                                                 if (ec2) return self->close();
                                                 self->pump(from, to, buffer);
                                             });
                });
        }
        void close() {
            boost::system::error_code ignored;
            near.shutdown(tcp::socket::shutdown_both, ignored);
            far.shutdown(tcp::socket::shutdown_both, ignored);
            near.close(ignored);
            far.close(ignored);
        }
    };

    void accept() {
        auto link = std::make_shared<Link>(io_);
        acceptor_.async_accept(link->near, [this, link](boost::system::error_code ec) {
            if (ec) return;
            ++accepted_;
            boost::system::error_code connectError;
            link->far.connect(target_, connectError);
            if (connectError) {
                link->close();
            } else {
                links_.push_back(link);
                link->start();
            }
            accept();
        });
    }

    boost::asio::io_context io_;
    tcp::acceptor acceptor_;
    tcp::endpoint target_;
    std::vector<std::shared_ptr<Link>> links_;  // io thread only
    std::atomic<int> accepted_{0};
    std::thread thread_;
};

}  // namespace igi::testing
