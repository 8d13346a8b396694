#include "ViewServer.h"

#include <chrono>
#include <deque>
#include <optional>
#include <set>

#include <spdlog/spdlog.h>
#include <boost/asio/ip/address.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace igi {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

namespace {

class Viewer;

// A request's path and its token parameter (the only parameter the view reads).
struct Target {
    std::string path;
    std::string token;
};

Target parseTarget(beast::string_view target) {
    Target t;
    const std::string s(target);
    const std::size_t q = s.find('?');
    t.path = s.substr(0, q);
    if (q == std::string::npos) return t;
    std::size_t start = q + 1;
    while (start <= s.size()) {
        std::size_t end = s.find('&', start);
        if (end == std::string::npos) end = s.size();
        const std::string param = s.substr(start, end - start);
        if (param.rfind("token=", 0) == 0) t.token = param.substr(6);
        start = end + 1;
    }
    return t;
}

// Compares in time that does not depend on where the strings first differ, so that response
// times do not leak the token byte by byte.
bool sameToken(const std::string& given, const std::string& expected) {
    if (given.size() != expected.size()) return false;
    unsigned char diff = 0;
    for (std::size_t i = 0; i < given.size(); ++i)
        diff |= static_cast<unsigned char>(given[i] ^ expected[i]);
    return diff == 0;
}

std::string peerOf(const tcp::socket& socket) {
    boost::system::error_code ec;
    const auto endpoint = socket.remote_endpoint(ec);
    if (ec) return "?";
    return endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

}  // namespace

struct ViewServer::Shared {
    Options options;
    ControlServer::Handler handler;
    std::set<Viewer*> viewers;
    bool closed = false;
};

namespace {

// One browser's WebSocket: commands in, replies and frames out, one write at a time (Beast's
// rule), replies first and then the newest frame.
class Viewer : public std::enable_shared_from_this<Viewer> {
  public:
    Viewer(beast::tcp_stream stream, std::shared_ptr<ViewServer::Shared> shared, std::string peer)
        : ws_(std::move(stream)), shared_(std::move(shared)), peer_(std::move(peer)) {}
    ~Viewer() { shared_->viewers.erase(this); }

    void start(http::request<http::string_body> request) {
        ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
        ws_.read_message_max(ViewServer::kMaxMessage);
        ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
            if (ec)
                return spdlog::info("view: WebSocket from {} failed: {}", self->peer_,
                                    ec.message());
            self->open_ = true;
            self->shared_->viewers.insert(self.get());
            spdlog::info("view: viewer {} connected ({} now)", self->peer_,
                         self->shared_->viewers.size());
            self->read();
        });
    }

    void sendFrame(std::shared_ptr<const std::string> frame) {
        frame_ = std::move(frame);
        write();
    }

    void shutDown() {
        if (!open_) return;
        open_ = false;
        ws_.async_close(websocket::close_code::going_away,
                        [self = shared_from_this()](beast::error_code) {});
    }

  private:
    void read() {
        ws_.async_read(in_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
            self->onRead(ec);
        });
    }

    void onRead(beast::error_code ec) {
        if (ec) {
            open_ = false;
            shared_->viewers.erase(this);
            if (ec == websocket::error::message_too_big)
                spdlog::warn("view: closing viewer {}: a message over {} bytes", peer_,
                             ViewServer::kMaxMessage);
            else if (ec == websocket::error::closed || ec == boost::asio::error::eof ||
                     ec == boost::asio::error::connection_reset)
                spdlog::info("view: viewer {} left ({})", peer_, ec.message());
            else
                spdlog::warn("view: closing viewer {}: {}", peer_, ec.message());
            return;
        }
        if (!ws_.got_text()) return refuse("a binary message (commands are JSON text)");
        const std::string line = beast::buffers_to_string(in_.data());
        in_.consume(in_.size());
        // The page sends only JSON objects: anything else is not a browser running it. A command
        // that is JSON but wrong (an unknown name, a value out of range) gets its error reply
        // from the handler instead, as on the control port.
        const nlohmann::json parsed = nlohmann::json::parse(line, nullptr, false);
        if (parsed.is_discarded() || !parsed.is_object())
            return refuse("a message that is not a JSON object");
        const std::uint64_t id = nextId_++;
        shared_->handler(line, [weak = weak_from_this(), id](std::string reply) {
            auto self = weak.lock();
            if (!self) return;
            self->replies_.push_back(std::make_shared<const std::string>(
                R"({"type":"reply","id":)" + std::to_string(id) + R"(,"reply":)" + reply + "}"));
            self->write();
        });
        read();
    }

    void refuse(const std::string& why) {
        spdlog::warn("view: closing viewer {}: {}", peer_, why);
        open_ = false;
        shared_->viewers.erase(this);
        ws_.async_close(websocket::close_code::policy_error,
                        [self = shared_from_this()](beast::error_code) {});
    }

    void write() {
        if (writing_ || !open_) return;
        std::shared_ptr<const std::string> message;
        bool text = true;
        if (!replies_.empty()) {
            message = std::move(replies_.front());
            replies_.pop_front();
        } else if (frame_) {
            message = std::move(frame_);
            frame_.reset();
            text = false;
        } else {
            return;
        }
        writing_ = true;
        ws_.text(text);
        ws_.async_write(boost::asio::buffer(*message),
                        [self = shared_from_this(), message](beast::error_code ec, std::size_t) {
                            self->writing_ = false;
                            if (ec) {
                                self->open_ = false;
                                self->shared_->viewers.erase(self.get());
                                return;
                            }
                            self->write();
                        });
    }

    websocket::stream<beast::tcp_stream> ws_;
    std::shared_ptr<ViewServer::Shared> shared_;
    std::string peer_;
    beast::flat_buffer in_;
    std::deque<std::shared_ptr<const std::string>> replies_;
    std::shared_ptr<const std::string> frame_;  ///< the newest frame not yet sent
    std::uint64_t nextId_ = 0;
    bool open_ = false;
    bool writing_ = false;
};

// One HTTP connection: serves the page, or hands the connection to a Viewer when it asks for
// the WebSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
  public:
    HttpSession(tcp::socket socket, std::shared_ptr<ViewServer::Shared> shared)
        : peer_(peerOf(socket)), stream_(std::move(socket)), shared_(std::move(shared)) {}

    void read() {
        parser_.emplace();
        parser_->header_limit(16 * 1024);
        parser_->body_limit(1024);  // the view takes no request bodies
        stream_.expires_after(std::chrono::seconds(30));
        http::async_read(
            stream_, buffer_, *parser_,
            [self = shared_from_this()](beast::error_code ec, std::size_t) { self->onRead(ec); });
    }

  private:
    void onRead(beast::error_code ec) {
        if (ec == http::error::end_of_stream) return shutDown();
        if (ec) {
            if (ec != beast::error::timeout)
                spdlog::info("view: HTTP request from {} refused: {}", peer_, ec.message());
            return;
        }
        http::request<http::string_body> request = parser_->release();
        const Target target = parseTarget(request.target());
        const bool authorized = sameToken(target.token, shared_->options.token);
        if (websocket::is_upgrade(request)) {
            if (target.path != "/ws")
                return respond(request, http::status::not_found, "no such WebSocket\n");
            if (!authorized) {
                spdlog::warn("view: WebSocket from {} refused: {} token", peer_,
                             target.token.empty() ? "no" : "a wrong");
                return respond(request, http::status::forbidden, "a token is needed\n");
            }
            stream_.expires_never();
            std::make_shared<Viewer>(std::move(stream_), shared_, peer_)->start(std::move(request));
            return;
        }
        if (request.method() != http::verb::get && request.method() != http::verb::head)
            return respond(request, http::status::method_not_allowed, "GET only\n");
        if (target.path != "/" && target.path != "/index.html")
            return respond(request, http::status::not_found, "not found\n");
        if (!authorized) {
            spdlog::warn("view: page request from {} refused: {} token", peer_,
                         target.token.empty() ? "no" : "a wrong");
            return respond(request, http::status::forbidden,
                           "This view needs its token: open the URL the master printed.\n");
        }
        respond(request, http::status::ok, shared_->options.page, "text/html; charset=utf-8");
    }

    void respond(const http::request<http::string_body>& request, http::status status,
                 std::string body, const char* type = "text/plain; charset=utf-8") {
        auto response =
            std::make_shared<http::response<http::string_body>>(status, request.version());
        response->set(http::field::content_type, type);
        response->set(http::field::cache_control, "no-store");
        response->keep_alive(request.keep_alive() && status == http::status::ok);
        response->body() = std::move(body);
        response->prepare_payload();
        if (request.method() == http::verb::head) response->body().clear();
        http::async_write(stream_, *response,
                          [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
                              if (!ec && response->keep_alive()) return self->read();
                              self->shutDown();
                          });
    }

    void shutDown() {
        beast::error_code ignored;
        stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    }

    std::string peer_;
    beast::tcp_stream stream_;
    beast::flat_buffer buffer_;
    std::optional<http::request_parser<http::string_body>> parser_;
    std::shared_ptr<ViewServer::Shared> shared_;
};

}  // namespace

ViewServer::ViewServer(boost::asio::io_context& io, Options options, ControlServer::Handler handler)
    : acceptor_(io), shared_(std::make_shared<Shared>()) {
    shared_->options = std::move(options);
    shared_->handler = std::move(handler);
    const tcp::endpoint endpoint(boost::asio::ip::make_address(shared_->options.host),
                                 shared_->options.port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen();
    accept();
}

ViewServer::~ViewServer() {
    close();
}

std::uint16_t ViewServer::port() const {
    return acceptor_.local_endpoint().port();
}

std::size_t ViewServer::viewers() const {
    return shared_->viewers.size();
}

void ViewServer::accept() {
    acceptor_.async_accept([this](beast::error_code ec, tcp::socket socket) {
        if (ec) {
            if (ec == boost::asio::error::operation_aborted || shared_->closed) return;
            spdlog::warn("view: accept failed: {}", ec.message());
        } else {
            std::make_shared<HttpSession>(std::move(socket), shared_)->read();
        }
        if (!shared_->closed) accept();
    });
}

void ViewServer::publish(std::shared_ptr<const std::string> frame) {
    // A copy of the set: a viewer whose write fails at once leaves it.
    const std::set<Viewer*> viewers = shared_->viewers;
    for (Viewer* v : viewers) v->sendFrame(frame);
}

void ViewServer::close() {
    if (shared_->closed) return;
    shared_->closed = true;
    beast::error_code ignored;
    acceptor_.close(ignored);
    const std::set<Viewer*> viewers = shared_->viewers;
    for (Viewer* v : viewers) v->shutDown();
}

std::shared_ptr<const std::string> ViewServer::frameMessage(const std::string& statusJson,
                                                            const std::string& jpeg) {
    std::string m;
    m.reserve(4 + statusJson.size() + jpeg.size());
    const auto n = std::uint32_t(statusJson.size());
    for (int i = 0; i < 4; ++i) m.push_back(char((n >> (8 * i)) & 0xff));
    m += statusJson;
    m += jpeg;
    return std::make_shared<const std::string>(std::move(m));
}

}  // namespace igi
