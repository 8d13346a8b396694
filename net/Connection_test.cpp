#include "net/Connection.h"

#include <gtest/gtest.h>

#include <future>
#include <mutex>
#include <thread>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "Codec.h"

namespace igi::net {
namespace {

using boost::asio::ip::tcp;
using namespace std::chrono_literals;
constexpr auto kPatience = 20s;  // a hang fails the test instead of blocking the suite

/// An io_context run by `threads` threads for the lifetime of the object.
struct Loop {
    explicit Loop(int threads = 1) : guard(boost::asio::make_work_guard(io)) {
        for (int i = 0; i < threads; ++i) runners.emplace_back([this] { io.run(); });
    }
    ~Loop() {
        guard.reset();
        io.stop();
        for (auto& t : runners) t.join();
    }
    boost::asio::io_context io;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard;
    std::vector<std::thread> runners;
};

/// Two connected loopback sockets: {accepted, connecting}.
std::pair<tcp::socket, tcp::socket> socketPair(boost::asio::io_context& io) {
    tcp::acceptor acceptor(io, tcp::endpoint(boost::asio::ip::address_v4::loopback(), 0));
    tcp::socket client(io);
    client.connect(acceptor.local_endpoint());
    tcp::socket server = acceptor.accept();
    return {std::move(server), std::move(client)};
}

/// Collects what a connection reports, for the test thread to wait on.
struct Inbox {
    std::mutex mutex;
    std::vector<std::pair<proto::Header, proto::Message>> messages;
    std::promise<std::string> closed;
    std::atomic<int> closeCalls{0};
    std::atomic<std::size_t> expected{1};
    std::promise<void> enough;

    void start(Connection& c) {
        c.start(
            [this](const proto::Header& h, proto::Message m) {
                std::lock_guard lock(mutex);
                messages.emplace_back(h, std::move(m));
                if (messages.size() == expected) enough.set_value();
            },
            [this](const std::string& reason) {
                if (closeCalls++ == 0) closed.set_value(reason);
            });
    }
};

template <class T>
bool ready(std::future<T>& f) {
    return f.wait_for(kPatience) == std::future_status::ready;
}

/// Routes spdlog's default logger into memory while alive.
struct CapturedLog {
    CapturedLog()
        : sink(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(100)),
          previous(spdlog::default_logger()) {
        spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink));
    }
    ~CapturedLog() { spdlog::set_default_logger(previous); }
    std::string text() const {
        std::string all;
        for (const auto& line : sink->last_formatted()) all += line;
        return all;
    }
    std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> sink;
    std::shared_ptr<spdlog::logger> previous;
};

std::string localAddress(const tcp::socket& s) {
    const auto e = s.local_endpoint();
    return e.address().to_string() + ":" + std::to_string(e.port());
}

TEST(Connection, MessagesRoundTripBothWays) {
    Loop loop(2);
    auto [s, c] = socketPair(loop.io);
    auto server = std::make_shared<Connection>(std::move(s));
    auto client = std::make_shared<Connection>(std::move(c));
    Inbox serverInbox, clientInbox;
    serverInbox.expected = 2;
    clientInbox.expected = 2;
    auto serverGot = serverInbox.enough.get_future();
    auto clientGot = clientInbox.enough.get_future();
    serverInbox.start(*server);
    clientInbox.start(*client);

    proto::Hello hello{proto::kVersion, "build-1", 8, "host-a", {}, std::nullopt};
    // A scene bigger than one read chunk, incompressible, so the payload arrives in pieces.
    proto::SceneData scene;
    scene.bundle.sceneName = "big.json";
    std::string noise(3u << 20, '\0');
    std::uint32_t x = 12345;
    for (char& ch : noise) ch = static_cast<char>((x = x * 1664525u + 1013904223u) >> 24);
    scene.bundle.files["big.bin"] = noise;
    client->send(hello, 3, 4);
    server->send(proto::Welcome{7, 99, std::nullopt}, 5, 6);
    server->send(scene, 8, 9);
    client->send(proto::Heartbeat{}, 10, 11);

    ASSERT_TRUE(ready(serverGot));
    ASSERT_TRUE(ready(clientGot));
    {
        std::lock_guard lock(serverInbox.mutex);
        const auto& [h, m] = serverInbox.messages.at(0);
        EXPECT_EQ(h.type, proto::MessageType::Hello);
        EXPECT_EQ(h.frame, 3u);
        EXPECT_EQ(h.epoch, 4u);
        const auto& got = std::get<proto::Hello>(m);
        EXPECT_EQ(got.buildId, "build-1");
        EXPECT_EQ(got.threads, 8u);
        EXPECT_EQ(got.hostname, "host-a");
        EXPECT_EQ(serverInbox.messages.at(1).first.type, proto::MessageType::Heartbeat);
        EXPECT_EQ(serverInbox.messages.at(1).first.frame, 10u);
    }
    {
        std::lock_guard lock(clientInbox.mutex);
        const auto& [h, m] = clientInbox.messages.at(0);
        EXPECT_EQ(h.frame, 5u);
        EXPECT_EQ(h.epoch, 6u);
        EXPECT_EQ(std::get<proto::Welcome>(m).clientId, 7u);
        EXPECT_EQ(std::get<proto::Welcome>(m).sessionSeed, 99u);
        const auto& [h2, m2] = clientInbox.messages.at(1);
        EXPECT_EQ(h2.epoch, 9u);
        EXPECT_EQ(std::get<proto::SceneData>(m2).bundle.files.at("big.bin"), noise);
    }
    EXPECT_EQ(client->messagesReceived(), 2u);
    EXPECT_EQ(server->messagesReceived(), 2u);
    EXPECT_GT(client->bytesReceived(), 3u << 20);  // the scene is incompressible
    // A sender counts its bytes when its write completes, which may be after the peer has
    // read them: wait for the counters to settle.
    for (auto waited = 0ms; waited < kPatience && (client->bytesReceived() != server->bytesSent() ||
                                                   server->bytesReceived() != client->bytesSent());
         waited += 10ms)
        std::this_thread::sleep_for(10ms);
    EXPECT_EQ(client->bytesReceived(), server->bytesSent());
    EXPECT_EQ(server->bytesReceived(), client->bytesSent());
    EXPECT_TRUE(server->isOpen());
    EXPECT_EQ(serverInbox.closeCalls, 0);
    server->close("test over");
    client->close("test over");
}

TEST(Connection, GarbageHeaderClosesWithALoggedReasonAndThePeerSeesIt) {
    CapturedLog log;
    Loop loop;
    auto [s, c] = socketPair(loop.io);
    const std::string clientAddress = localAddress(c);
    auto server = std::make_shared<Connection>(std::move(s));
    Inbox serverInbox;
    auto serverClosed = serverInbox.closed.get_future();
    serverInbox.start(*server);

    const std::string garbage = "GET / HTTP/1.1\r\nHost: x\r\n";  // a confused web client
    boost::asio::write(c, boost::asio::buffer(garbage.data(), proto::kHeaderSize));
    auto client = std::make_shared<Connection>(std::move(c));
    Inbox clientInbox;
    auto clientClosed = clientInbox.closed.get_future();
    clientInbox.start(*client);

    ASSERT_TRUE(ready(serverClosed));
    const std::string reason = serverClosed.get();
    EXPECT_NE(reason.find("bad magic"), std::string::npos) << reason;
    EXPECT_NE(log.text().find("bad magic"), std::string::npos) << log.text();
    EXPECT_NE(log.text().find(clientAddress), std::string::npos) << log.text();
    EXPECT_NE(log.text().find("warning"), std::string::npos) << log.text();
    ASSERT_TRUE(ready(clientClosed));
    EXPECT_EQ(clientClosed.get(), "peer closed the connection");
    EXPECT_FALSE(server->isOpen());
    EXPECT_EQ(serverInbox.messages.size(), 0u);
}

TEST(Connection, OversizedLengthClosesBeforeReadingThePayload) {
    Loop loop;
    auto [s, c] = socketPair(loop.io);
    auto server = std::make_shared<Connection>(std::move(s));
    Inbox serverInbox;
    auto serverClosed = serverInbox.closed.get_future();
    serverInbox.start(*server);

    proto::Header h;
    h.type = proto::MessageType::TileResult;
    h.payloadSize = 3u << 30;  // 3 GiB
    const auto header = proto::encodeHeader(h);
    boost::asio::write(c, boost::asio::buffer(header));
    boost::asio::write(c, boost::asio::buffer(std::string(1000, 'x')));  // the "payload" starts

    ASSERT_TRUE(ready(serverClosed));
    const std::string reason = serverClosed.get();
    EXPECT_NE(reason.find("exceeds the 67108864-byte limit for TileResult"), std::string::npos)
        << reason;
    // Closed on the header alone: not a byte of the payload was read (or allocated for).
    EXPECT_EQ(server->bytesReceived(), proto::kHeaderSize);
    // And the peer sees the close.
    boost::system::error_code ec;
    char byte;
    boost::asio::read(c, boost::asio::buffer(&byte, 1), ec);
    EXPECT_TRUE(ec == boost::asio::error::eof || ec == boost::asio::error::connection_reset)
        << ec.message();
}

TEST(Connection, ThousandMessagesFromTwoThreadsArriveCompleteAndInOrder) {
    Loop loop(2);
    auto [s, c] = socketPair(loop.io);
    auto server = std::make_shared<Connection>(std::move(s));
    auto client = std::make_shared<Connection>(std::move(c));
    Inbox serverInbox, clientInbox;
    constexpr int kPerThread = 500;
    serverInbox.expected = 2 * kPerThread;
    auto all = serverInbox.enough.get_future();
    serverInbox.start(*server);
    clientInbox.start(*client);

    auto sender = [&](std::uint32_t thread) {
        for (std::uint32_t i = 0; i < kPerThread; ++i) {
            proto::TileAssign t;
            t.tileId = thread << 16 | i;
            t.width = t.height = 32;
            client->send(t, i, thread);
        }
    };
    std::thread a(sender, 1), b(sender, 2);
    a.join();
    b.join();
    ASSERT_TRUE(ready(all));

    std::lock_guard lock(serverInbox.mutex);
    ASSERT_EQ(serverInbox.messages.size(), 2u * kPerThread);
    std::uint32_t next[3] = {0, 0, 0};
    for (const auto& [h, m] : serverInbox.messages) {
        const auto& t = std::get<proto::TileAssign>(m);
        const std::uint32_t thread = t.tileId >> 16;
        ASSERT_TRUE(thread == 1 || thread == 2);
        EXPECT_EQ(t.tileId & 0xFFFF, next[thread]) << "thread " << thread;
        EXPECT_EQ(h.frame, next[thread]);
        EXPECT_EQ(h.epoch, thread);
        ++next[thread];
    }
    EXPECT_EQ(next[1], std::uint32_t(kPerThread));
    EXPECT_EQ(next[2], std::uint32_t(kPerThread));
    // Every write completes; the queue drains to nothing.
    for (int i = 0; i < 2000 && (client->queuedBytes() != 0 || client->messagesSent() < 1000); ++i)
        std::this_thread::sleep_for(10ms);
    EXPECT_EQ(client->queuedBytes(), 0u);
    EXPECT_EQ(client->messagesSent(), 2u * kPerThread);
    EXPECT_EQ(client->bytesSent(), server->bytesReceived());
}

TEST(Connection, ReadTimeoutCloses) {
    Loop loop;
    auto [s, c] = socketPair(loop.io);
    auto server = std::make_shared<Connection>(std::move(s), ConnectionOptions{100ms, {}, {}});
    Inbox serverInbox;
    auto closed = serverInbox.closed.get_future();
    serverInbox.start(*server);
    // The peer says nothing at all.
    ASSERT_TRUE(ready(closed));
    const std::string reason = closed.get();
    EXPECT_EQ(reason.rfind("read timeout", 0), 0u) << reason;
}

TEST(Connection, CloseAfterSendingDeliversTheLastMessageAndClosesOnce) {
    Loop loop(2);
    auto [s, c] = socketPair(loop.io);
    auto server = std::make_shared<Connection>(std::move(s));
    auto client = std::make_shared<Connection>(std::move(c));
    Inbox serverInbox, clientInbox;
    auto got = clientInbox.enough.get_future();
    auto clientClosed = clientInbox.closed.get_future();
    auto serverClosed = serverInbox.closed.get_future();
    serverInbox.start(*server);
    clientInbox.start(*client);

    server->send(proto::Error{"scene failed to load"}, 0, 0);
    server->closeAfterSending("sent an error");

    ASSERT_TRUE(ready(got));
    ASSERT_TRUE(ready(clientClosed));
    ASSERT_TRUE(ready(serverClosed));
    EXPECT_EQ(std::get<proto::Error>(clientInbox.messages.at(0).second).reason,
              "scene failed to load");
    EXPECT_EQ(clientClosed.get(), "peer closed the connection");
    EXPECT_EQ(serverClosed.get(), "sent an error");
    server->close("and again");              // a second close changes nothing
    client->send(proto::Heartbeat{}, 0, 0);  // dropped, not an error
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(serverInbox.closeCalls, 1);
    EXPECT_EQ(clientInbox.closeCalls, 1);
}

TEST(Connection, EncodingErrorsReachTheCaller) {
    Loop loop;
    auto [s, c] = socketPair(loop.io);
    auto client = std::make_shared<Connection>(std::move(c));
    EXPECT_THROW(client->send(proto::Error{std::string(100000, 'x')}, 0, 0), proto::ProtocolError);
    EXPECT_EQ(client->queuedBytes(), 0u);
}

}  // namespace
}  // namespace igi::net

namespace igi::net {
namespace {

TEST(Connection, UndecodedTypesReachTheRawHandlerAndOthersAreDecoded) {
    Loop loop(1);
    auto [s, c] = socketPair(loop.io);
    ConnectionOptions options;
    options.undecodedTypes = {proto::MessageType::TileResult};
    auto server = std::make_shared<Connection>(std::move(s), options);
    auto client = std::make_shared<Connection>(std::move(c));
    std::promise<std::pair<proto::Header, std::vector<std::uint8_t>>> raw;
    std::promise<proto::MessageType> decoded;
    server->start([&](const proto::Header& h, proto::Message) { decoded.set_value(h.type); },
                  [](const std::string&) {},
                  [&](const proto::Header& h, std::vector<std::uint8_t> p) {
                      raw.set_value({h, std::move(p)});
                  });
    client->start([](const proto::Header&, proto::Message) {}, [](const std::string&) {});

    proto::TileResult result;
    result.tileId = 17;
    result.channels.resize(3, kUnfiltered);
    result.channels.unfiltered[1] = glm::vec3(2.0f);
    client->send(result, 4, 0);
    client->sendEncoded(proto::encodeMessage(proto::Heartbeat{}, 5, 0));

    auto rawFuture = raw.get_future();
    auto decodedFuture = decoded.get_future();
    ASSERT_TRUE(ready(rawFuture));
    ASSERT_TRUE(ready(decodedFuture));
    EXPECT_EQ(decodedFuture.get(), proto::MessageType::Heartbeat);
    auto [header, payload] = rawFuture.get();
    EXPECT_EQ(header.frame, 4u);
    const auto back = std::get<proto::TileResult>(proto::decodeMessage(header, payload));
    EXPECT_EQ(back.tileId, 17u);
    EXPECT_FLOAT_EQ(back.channels.unfiltered[1].y, 2.0f);
}

}  // namespace
}  // namespace igi::net

namespace igi::net {
namespace {

TEST(Connection, APerConnectionPayloadLimitClosesBeforeThePayloadIsRead) {
    Loop loop(1);
    auto [s, c] = socketPair(loop.io);
    ConnectionOptions options;
    options.payloadLimits = {{proto::MessageType::TileResult, 64}};
    auto server = std::make_shared<Connection>(std::move(s), options);
    auto client = std::make_shared<Connection>(std::move(c));
    Inbox inbox;
    auto closed = inbox.closed.get_future();
    inbox.start(*server);
    client->start([](const proto::Header&, proto::Message) {}, [](const std::string&) {});
    proto::TileResult big;
    big.channels.resize(1000, kUnfiltered);
    for (std::size_t i = 0; i < big.channels.unfiltered.size(); ++i)
        big.channels.unfiltered[i] = glm::vec3(float(i));
    client->send(big, 0, 0);
    ASSERT_TRUE(ready(closed));
    EXPECT_NE(closed.get().find("exceeds this connection's limit of 64 bytes"), std::string::npos);
}

}  // namespace
}  // namespace igi::net

namespace igi::net {
namespace {

TEST(Connection, APeerThatTricklesAMessageIsDroppedThoughEachByteBeatsTheReadTimeout) {
    Loop loop(1);
    auto [s, c] = socketPair(loop.io);
    ConnectionOptions options;
    options.readTimeout = 200ms;
    options.minBytesPerSecond = 10000;
    auto server = std::make_shared<Connection>(std::move(s), options);
    Inbox inbox;
    auto closed = inbox.closed.get_future();
    inbox.start(*server);

    proto::TileResult result;
    result.channels.resize(1000, kUnfiltered);
    for (std::size_t i = 0; i < result.channels.unfiltered.size(); ++i)
        result.channels.unfiltered[i] = glm::vec3(float(i));
    const std::vector<std::uint8_t> bytes = proto::encodeMessage(result, 0, 0);
    // The whole header at once, then the payload a byte every 20 ms: never silent for 200 ms,
    // but far below 10 kB/s.
    boost::asio::write(c, boost::asio::buffer(bytes.data(), proto::kHeaderSize));
    const auto start = std::chrono::steady_clock::now();
    std::string reason;
    for (std::size_t i = proto::kHeaderSize; i < bytes.size(); ++i) {
        if (closed.wait_for(20ms) == std::future_status::ready) break;
        boost::system::error_code ec;
        boost::asio::write(c, boost::asio::buffer(&bytes[i], 1), ec);
        if (ec || std::chrono::steady_clock::now() - start > kPatience) break;
    }
    ASSERT_TRUE(ready(closed)) << "the trickling peer was never dropped";
    reason = closed.get();
    EXPECT_EQ(reason.rfind("too slow", 0), 0u) << reason;
    EXPECT_TRUE(inbox.messages.empty());
}

}  // namespace
}  // namespace igi::net
