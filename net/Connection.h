#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>

// Codec.h: owners of a connection name message types (typeOf, messageTypeName) and catch the
// ProtocolError that send throws.
#include "Codec.h"
#include "Messages.h"

namespace igi::net {

struct ConnectionOptions {
    /// The connection closes ("read timeout") when no data arrives for this long, whether it
    /// waits for a header or is in the middle of a payload. Keeping an idle connection alive
    /// with heartbeats is the owner's business.
    std::chrono::milliseconds readTimeout{30000};
    /// Messages of these types reach the owner undecoded (RawHandler), so that it can decode
    /// them on other threads: the master decodes tile results on all its cores.
    std::vector<proto::MessageType> undecodedTypes;
    /// Tighter payload limits than the protocol's, by type (the master knows how big a tile
    /// result can be); checked with the header, before anything is allocated.
    std::vector<std::pair<proto::MessageType, std::uint32_t>> payloadLimits;
    /// A message, once its header is in, must be complete within readTimeout plus its size at
    /// this rate: a peer that trickles a byte now and then (each byte restarting the read
    /// timeout) to hold a connection and its buffer is dropped.
    std::size_t minBytesPerSecond = 64 * 1024;
};

/// One framed TCP connection, used by master and client alike (after Boost.Beast's session
/// examples): messages are read header first, the header is checked against the type's limit
/// before the payload is allocated, and each message is handed to the owner decoded. Every
/// handler runs on the connection's strand, so the owner may run the io_context on any number
/// of threads; `send` and `close` may be called from any thread.
///
/// The connection closes at most once, on a protocol error, a socket error, the peer closing,
/// a read timeout or the owner's `close`, and then calls `onClose(reason)` exactly once (only
/// if `start` was called) and drops both handlers, so that handlers capturing their owner do
/// not keep it alive.
class Connection : public std::enable_shared_from_this<Connection> {
  public:
    using MessageHandler = std::function<void(const proto::Header&, proto::Message)>;
    using CloseHandler = std::function<void(const std::string& reason)>;
    using RawHandler = std::function<void(const proto::Header&, std::vector<std::uint8_t> payload)>;

    explicit Connection(boost::asio::ip::tcp::socket socket, ConnectionOptions options = {});
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    /// Starts reading. Call once; the handlers are called on the strand. Messages of the types
    /// in ConnectionOptions::undecodedTypes go to `onRaw` with their payload as received (the
    /// header is checked; the payload is the owner's to decode and validate).
    void start(MessageHandler onMessage, CloseHandler onClose, RawHandler onRaw = nullptr);

    /// Encodes the message on the calling thread (throws ProtocolError if it exceeds its
    /// type's limit) and queues it; one write is in flight at a time, the rest wait in order.
    /// Messages sent after the connection closed are dropped.
    void send(const proto::Message& message, std::uint32_t frame, std::uint32_t epoch);

    /// Queues a message encoded earlier (header and payload), e.g. a recorded result replayed.
    void sendEncoded(std::vector<std::uint8_t> bytes);

    /// Closes now; what is still queued is dropped.
    void close(std::string reason);
    /// Closes once everything queued so far has been written (for a final Error or Shutdown).
    void closeAfterSending(std::string reason);

    /// "address:port" of the peer, for messages.
    const std::string& peer() const { return peer_; }
    bool isOpen() const { return open_.load(); }

    /// Bytes encoded but not yet written to the socket: the owner's measure of back-pressure.
    std::size_t queuedBytes() const { return queuedBytes_.load(); }
    std::uint64_t bytesSent() const { return bytesSent_.load(); }
    std::uint64_t bytesReceived() const { return bytesReceived_.load(); }
    std::uint64_t messagesSent() const { return messagesSent_.load(); }
    std::uint64_t messagesReceived() const { return messagesReceived_.load(); }

  private:
    enum class CloseKind { Owner, PeerClosed, Problem };

    void readHeader();
    void onHeader(const boost::system::error_code& ec, std::size_t n);
    void readPayload(std::size_t offset);
    void onPayloadChunk(const boost::system::error_code& ec, std::size_t n, std::size_t offset);
    void deliver();
    void onReadError(const boost::system::error_code& ec, bool atMessageStart, const char* where);

    void restartReadDeadline();
    void waitForReadDeadline();

    void enqueue(std::vector<std::uint8_t> bytes);
    void writeNext();
    void onWrite(const boost::system::error_code& ec, std::size_t n);

    void closeNow(const std::string& reason, CloseKind kind);

    boost::asio::ip::tcp::socket socket_;
    boost::asio::strand<boost::asio::any_io_executor> strand_;
    boost::asio::steady_timer readDeadline_;
    ConnectionOptions options_;
    std::string peer_;

    // Strand-only state.
    MessageHandler onMessage_;
    CloseHandler onClose_;
    RawHandler onRaw_;
    bool started_ = false;
    bool closed_ = false;
    std::array<std::uint8_t, proto::kHeaderSize> headerBytes_{};
    proto::Header header_;
    std::vector<std::uint8_t> payload_;
    /// When the message being read must be complete; none between messages.
    std::optional<std::chrono::steady_clock::time_point> messageDeadline_;
    std::deque<std::vector<std::uint8_t>> writeQueue_;
    /// How many messages at the front of writeQueue_ the write in flight carries (0: none).
    std::size_t inFlight_ = 0;
    bool closeWhenDrained_ = false;
    std::string drainReason_;

    // Readable from any thread.
    std::atomic<bool> open_{true};
    std::atomic<std::size_t> queuedBytes_{0};
    std::atomic<std::uint64_t> bytesSent_{0};
    std::atomic<std::uint64_t> bytesReceived_{0};
    std::atomic<std::uint64_t> messagesSent_{0};
    std::atomic<std::uint64_t> messagesReceived_{0};
};

}  // namespace igi::net
