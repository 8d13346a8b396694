#include "ViewServer.h"

#include <future>
#include <thread>

#include <gtest/gtest.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace igi {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

// A ViewServer on its own io thread, on real loopback sockets, whose handler answers each
// command with its length (and records it).
struct Served {
    boost::asio::io_context io;
    std::unique_ptr<ViewServer> server;
    std::vector<std::string> commands;
    std::thread thread;
    std::uint16_t port = 0;

    explicit Served(std::string token) {
        ViewServer::Options o;
        o.token = std::move(token);
        o.page = "<html>the page</html>";
        server = std::make_unique<ViewServer>(
            io, o, [this](const std::string& line, ControlServer::Reply reply) {
                commands.push_back(line);
                reply(R"({"ok":true,"length":)" + std::to_string(line.size()) + "}");
            });
        port = server->port();
        thread = std::thread([this] {
            auto guard = boost::asio::make_work_guard(io);
            io.run();
        });
    }
    ~Served() {
        boost::asio::post(io, [this] {
            server->close();
            io.stop();
        });
        thread.join();
    }
    // Runs f on the io thread and waits for it.
    template <typename F>
    auto onIo(F f) {
        std::promise<decltype(f())> done;
        boost::asio::post(io, [&] { done.set_value(f()); });
        return done.get_future().get();
    }
};

http::response<http::string_body> get(std::uint16_t port, const std::string& target) {
    boost::asio::io_context io;
    beast::tcp_stream stream(io);
    stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
    http::request<http::empty_body> request(http::verb::get, target, 11);
    request.set(http::field::host, "127.0.0.1");
    http::write(stream, request);
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(stream, buffer, response);
    return response;
}

struct Client {
    boost::asio::io_context io;
    websocket::stream<tcp::socket> ws{io};
    beast::flat_buffer buffer;

    Client(std::uint16_t port, const std::string& target) {
        ws.next_layer().connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
        ws.handshake("127.0.0.1", target);
    }
    std::string read() {
        buffer.consume(buffer.size());
        ws.read(buffer);
        return beast::buffers_to_string(buffer.data());
    }
};

void waitForViewers(Served& s, std::size_t n) {
    for (int i = 0; i < 500 && s.onIo([&] { return s.server->viewers(); }) < n; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_EQ(s.onIo([&] { return s.server->viewers(); }), n);
}

TEST(ViewServer, ServesThePageAndAnswersCommandsInOrder) {
    Served s("");
    const auto page = get(s.port, "/");
    EXPECT_EQ(page.result(), http::status::ok);
    EXPECT_EQ(page.body(), "<html>the page</html>");
    EXPECT_EQ(get(s.port, "/other").result(), http::status::not_found);

    Client c(s.port, "/ws");
    c.ws.text(true);
    c.ws.write(boost::asio::buffer(std::string(R"({"cmd":"status"})")));
    c.ws.write(boost::asio::buffer(std::string(R"({"cmd":"scene"})")));
    const auto first = nlohmann::json::parse(c.read());
    const auto second = nlohmann::json::parse(c.read());
    EXPECT_EQ(first["type"], "reply");
    EXPECT_EQ(first["id"], 0);
    EXPECT_EQ(first["reply"]["length"], 16);
    EXPECT_EQ(second["id"], 1);
    EXPECT_EQ(second["reply"]["length"], 15);
}

TEST(ViewServer, EveryViewerGetsTheFrameWithItsStatus) {
    Served s("");
    Client a(s.port, "/ws"), b(s.port, "/ws");
    waitForViewers(s, 2);
    const auto frame = ViewServer::frameMessage(R"({"frame":7})", std::string("\xFF\xD8jpeg", 6));
    s.onIo([&] {
        s.server->publish(frame);
        return 0;
    });
    for (Client* c : {&a, &b}) {
        const std::string m = c->read();
        EXPECT_TRUE(c->ws.got_binary());
        ASSERT_EQ(m.size(), 4 + 11 + 6u);
        EXPECT_EQ(m.substr(0, 4), std::string("\x0B\x00\x00\x00", 4));
        EXPECT_EQ(m.substr(4, 11), R"({"frame":7})");
        EXPECT_EQ(m.substr(15), std::string("\xFF\xD8jpeg", 6));
    }
}

TEST(ViewServer, WithATokenNothingIsServedWithoutIt) {
    Served s("s3cret");
    EXPECT_EQ(get(s.port, "/").result(), http::status::forbidden);
    EXPECT_EQ(get(s.port, "/?token=wrong").result(), http::status::forbidden);
    EXPECT_EQ(get(s.port, "/?token=s3cre").result(), http::status::forbidden);
    EXPECT_EQ(get(s.port, "/?token=s3cret").result(), http::status::ok);
    EXPECT_THROW(Client(s.port, "/ws"), beast::system_error);
    EXPECT_THROW(Client(s.port, "/ws?token=nope"), beast::system_error);
    Client ok(s.port, "/ws?a=1&token=s3cret");
    waitForViewers(s, 1);
}

// A message the view does not take closes that viewer only; the server goes on.
TEST(ViewServer, OversizedBinaryOrNonJsonMessagesCloseTheirViewer) {
    Served s("");
    {
        Client big(s.port, "/ws");
        big.ws.text(true);
        big.ws.write(boost::asio::buffer(std::string(ViewServer::kMaxMessage + 1, ' ')));
        EXPECT_THROW(big.read(), beast::system_error);
        EXPECT_EQ(big.ws.reason().code, websocket::close_code::too_big);
    }
    {
        Client binary(s.port, "/ws");
        binary.ws.binary(true);
        binary.ws.write(boost::asio::buffer(std::string("{}")));
        EXPECT_THROW(binary.read(), beast::system_error);
        EXPECT_EQ(binary.ws.reason().code, websocket::close_code::policy_error);
    }
    for (const char* text : {"{not json", "[1,2]", "\"status\""}) {
        Client notAnObject(s.port, "/ws");
        notAnObject.ws.text(true);
        notAnObject.ws.write(boost::asio::buffer(std::string(text)));
        EXPECT_THROW(notAnObject.read(), beast::system_error) << text;
        EXPECT_EQ(notAnObject.ws.reason().code, websocket::close_code::policy_error) << text;
    }
    EXPECT_TRUE(s.commands.empty());
    Client fine(s.port, "/ws");
    fine.ws.text(true);
    fine.ws.write(boost::asio::buffer(std::string(R"({"cmd":"nonsense"})")));
    EXPECT_EQ(nlohmann::json::parse(fine.read())["reply"]["length"], 18);
}

}  // namespace
}  // namespace igi
