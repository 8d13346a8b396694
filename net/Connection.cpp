#include "net/Connection.h"

#include <algorithm>
#include <utility>

#include <spdlog/spdlog.h>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "Codec.h"

namespace igi::net {
namespace {

// Payloads are read in pieces so that every piece restarts the read deadline: a big SceneData
// on a slow link is progress, not a stall.
constexpr std::size_t kReadChunk = std::size_t{1} << 20;

std::string describePeer(const boost::asio::ip::tcp::socket& socket) {
    boost::system::error_code ec;
    const auto endpoint = socket.remote_endpoint(ec);
    if (ec) return "unknown peer";
    return endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

std::string seconds(std::chrono::milliseconds d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g s", d.count() / 1000.0);
    return buf;
}

}  // namespace

Connection::Connection(boost::asio::ip::tcp::socket socket, ConnectionOptions options)
    : socket_(std::move(socket)),
      strand_(boost::asio::make_strand(socket_.get_executor())),
      readDeadline_(strand_),
      options_(options),
      peer_(describePeer(socket_)) {}

void Connection::start(MessageHandler onMessage, CloseHandler onClose, RawHandler onRaw) {
    boost::asio::dispatch(strand_,
                          [self = shared_from_this(), onMessage = std::move(onMessage),
                           onClose = std::move(onClose), onRaw = std::move(onRaw)]() mutable {
                              if (self->started_ || self->closed_) return;
                              self->started_ = true;
                              self->onMessage_ = std::move(onMessage);
                              self->onClose_ = std::move(onClose);
                              self->onRaw_ = std::move(onRaw);
                              self->restartReadDeadline();
                              self->waitForReadDeadline();
                              self->readHeader();
                          });
}

// ---- reading ----

void Connection::readHeader() {
    boost::asio::async_read(
        socket_, boost::asio::buffer(headerBytes_),
        boost::asio::bind_executor(
            strand_, [self = shared_from_this()](const boost::system::error_code& ec,
                                                 std::size_t n) { self->onHeader(ec, n); }));
}

void Connection::onHeader(const boost::system::error_code& ec, std::size_t n) {
    if (closed_) return;
    bytesReceived_ += n;
    if (ec) return onReadError(ec, n == 0, "header");
    try {
        header_ = proto::decodeHeader(headerBytes_);
    } catch (const proto::ProtocolError& e) {
        return closeNow(std::string("protocol error: ") + e.what(), CloseKind::Problem);
    }
    for (const auto& [type, limit] : options_.payloadLimits)
        if (header_.type == type && header_.payloadSize > limit)
            return closeNow("protocol error: a " + std::to_string(header_.payloadSize) + "-byte " +
                                proto::messageTypeName(type) +
                                " exceeds this connection's limit of " + std::to_string(limit) +
                                " bytes",
                            CloseKind::Problem);
    const double allowed =
        std::chrono::duration<double>(options_.readTimeout).count() +
        double(header_.payloadSize) / double(std::max<std::size_t>(1, options_.minBytesPerSecond));
    messageDeadline_ = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(allowed));
    restartReadDeadline();
    // Only now, with the size checked against the type's limit, is memory taken for it.
    try {
        payload_.resize(header_.payloadSize);
    } catch (const std::bad_alloc&) {
        return closeNow("out of memory for a " + std::to_string(header_.payloadSize) + "-byte " +
                            proto::messageTypeName(header_.type) + " payload",
                        CloseKind::Problem);
    }
    readPayload(0);
}

void Connection::readPayload(std::size_t offset) {
    if (offset == payload_.size()) return deliver();
    const std::size_t n = std::min(kReadChunk, payload_.size() - offset);
    socket_.async_read_some(boost::asio::buffer(payload_.data() + offset, n),
                            boost::asio::bind_executor(
                                strand_, [self = shared_from_this(), offset](
                                             const boost::system::error_code& ec, std::size_t got) {
                                    self->onPayloadChunk(ec, got, offset);
                                }));
}

void Connection::onPayloadChunk(const boost::system::error_code& ec, std::size_t n,
                                std::size_t offset) {
    if (closed_) return;
    bytesReceived_ += n;
    if (ec) return onReadError(ec, false, "payload");
    restartReadDeadline();
    readPayload(offset + n);
}

void Connection::deliver() {
    messageDeadline_.reset();
    const auto& raw = options_.undecodedTypes;
    if (onRaw_ && std::find(raw.begin(), raw.end(), header_.type) != raw.end()) {
        ++messagesReceived_;
        try {
            onRaw_(header_, std::exchange(payload_, {}));
        } catch (const std::exception& e) {
            return closeNow(std::string("message handler failed: ") + e.what(), CloseKind::Problem);
        }
        if (!closed_) readHeader();
        return;
    }
    proto::Message message;
    try {
        message = proto::decodeMessage(header_, payload_);
    } catch (const proto::ProtocolError& e) {
        return closeNow(std::string("protocol error: ") + e.what(), CloseKind::Problem);
    }
    // A large payload's memory is not kept for the next, most likely small, message.
    if (payload_.capacity() > kReadChunk) std::vector<std::uint8_t>().swap(payload_);
    ++messagesReceived_;
    try {
        if (onMessage_) onMessage_(header_, std::move(message));
    } catch (const std::exception& e) {
        return closeNow(std::string("message handler failed: ") + e.what(), CloseKind::Problem);
    }
    if (!closed_) readHeader();
}

void Connection::onReadError(const boost::system::error_code& ec, bool atMessageStart,
                             const char* where) {
    if (ec == boost::asio::error::eof) {
        if (atMessageStart) return closeNow("peer closed the connection", CloseKind::PeerClosed);
        return closeNow(
            std::string("peer closed the connection in the middle of a message ") + where,
            CloseKind::Problem);
    }
    closeNow("socket error while reading a message " + std::string(where) + ": " + ec.message(),
             CloseKind::Problem);
}

// ---- read deadline ----

void Connection::restartReadDeadline() {
    readDeadline_.expires_after(options_.readTimeout);
    if (messageDeadline_ && *messageDeadline_ < readDeadline_.expiry())
        readDeadline_.expires_at(*messageDeadline_);
}

void Connection::waitForReadDeadline() {
    // Restarting the deadline cancels this wait; the handler then finds the deadline in the
    // future and waits again (the deadline pattern of Asio's timeout examples).
    readDeadline_.async_wait(boost::asio::bind_executor(
        strand_, [self = shared_from_this()](const boost::system::error_code&) {
            if (self->closed_) return;
            const auto now = boost::asio::steady_timer::clock_type::now();
            if (self->messageDeadline_ && *self->messageDeadline_ <= now)
                return self->closeNow(
                    "too slow: a " + std::to_string(self->header_.payloadSize) + "-byte " +
                        proto::messageTypeName(self->header_.type) +
                        " payload still incomplete at its deadline (the peer trickles bytes)",
                    CloseKind::Problem);
            if (self->readDeadline_.expiry() <= now)
                return self->closeNow(
                    "read timeout: nothing received for " + seconds(self->options_.readTimeout),
                    CloseKind::Problem);
            self->waitForReadDeadline();
        }));
}

// ---- writing ----

void Connection::send(const proto::Message& message, std::uint32_t frame, std::uint32_t epoch) {
    if (!open_) return;  // it would be dropped anyway: spare the encoding
    std::vector<std::uint8_t> bytes = proto::encodeMessage(message, frame, epoch);
    queuedBytes_ += bytes.size();
    boost::asio::post(strand_, [self = shared_from_this(), bytes = std::move(bytes)]() mutable {
        self->enqueue(std::move(bytes));
    });
}

void Connection::sendEncoded(std::vector<std::uint8_t> bytes) {
    if (!open_) return;
    queuedBytes_ += bytes.size();
    boost::asio::post(strand_, [self = shared_from_this(), bytes = std::move(bytes)]() mutable {
        self->enqueue(std::move(bytes));
    });
}

void Connection::enqueue(std::vector<std::uint8_t> bytes) {
    if (closed_) {
        queuedBytes_ -= bytes.size();
        return;
    }
    writeQueue_.push_back(std::move(bytes));
    if (inFlight_ == 0) writeNext();
}

void Connection::writeNext() {
    // Every message queued so far goes in one write (up to kMaxGather): the master sends its
    // tile assignments several at a time, and a system call for each cost it more than the
    // compositing of their tiles with fast clients on loopback (where the kernel delivers to
    // the receiver within the sender's call).
    constexpr std::size_t kMaxGather = 64;
    inFlight_ = std::min(writeQueue_.size(), kMaxGather);
    std::vector<boost::asio::const_buffer> buffers;
    buffers.reserve(inFlight_);
    for (std::size_t i = 0; i < inFlight_; ++i)
        buffers.push_back(boost::asio::buffer(writeQueue_[i]));
    boost::asio::async_write(
        socket_, buffers,
        boost::asio::bind_executor(
            strand_, [self = shared_from_this()](const boost::system::error_code& ec,
                                                 std::size_t n) { self->onWrite(ec, n); }));
}

void Connection::onWrite(const boost::system::error_code& ec, std::size_t n) {
    const std::size_t written = inFlight_;
    inFlight_ = 0;
    bytesSent_ += n;
    if (closed_) return;
    if (ec) return closeNow("socket error while writing: " + ec.message(), CloseKind::Problem);
    messagesSent_ += written;
    for (std::size_t i = 0; i < written; ++i) {
        queuedBytes_ -= writeQueue_.front().size();
        writeQueue_.pop_front();
    }
    if (!writeQueue_.empty()) return writeNext();
    if (closeWhenDrained_) closeNow(drainReason_, CloseKind::Owner);
}

// ---- closing ----

void Connection::close(std::string reason) {
    boost::asio::post(strand_, [self = shared_from_this(), reason = std::move(reason)] {
        self->closeNow(reason, CloseKind::Owner);
    });
}

void Connection::closeAfterSending(std::string reason) {
    boost::asio::post(strand_, [self = shared_from_this(), reason = std::move(reason)] {
        if (self->closed_) return;
        if (self->writeQueue_.empty()) return self->closeNow(reason, CloseKind::Owner);
        self->closeWhenDrained_ = true;
        self->drainReason_ = reason;
    });
}

void Connection::closeNow(const std::string& reason, CloseKind kind) {
    if (closed_) return;
    closed_ = true;
    open_ = false;
    if (kind == CloseKind::Problem)
        spdlog::warn("connection with {} closed: {}", peer_, reason);
    else
        spdlog::info("connection with {} closed: {}", peer_, reason);
    boost::system::error_code ignored;
    readDeadline_.cancel();
    socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
    // The buffer of a write still in flight (and the payload being read into) must outlive the
    // cancelled operation: they are freed with the connection, not here.
    while (writeQueue_.size() > inFlight_) {
        queuedBytes_ -= writeQueue_.back().size();
        writeQueue_.pop_back();
    }
    for (const auto& bytes : writeQueue_) queuedBytes_ -= bytes.size();
    // Handlers often capture their owner, which holds this connection: drop them to break the
    // cycle, and call onClose last, from a local, in case it drops the owner's last reference.
    CloseHandler onClose = std::move(onClose_);
    onClose_ = nullptr;
    onMessage_ = nullptr;
    onRaw_ = nullptr;
    if (onClose) onClose(reason);
}

}  // namespace igi::net
