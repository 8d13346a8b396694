#include "ProgressLine.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <mutex>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace igi {

/// Writes log records to stderr above the progress line: "\r\033[K" clears the line, the record
/// prints, the line is drawn again. One mutex orders records and redraws from any thread.
class ProgressSink : public spdlog::sinks::base_sink<std::mutex> {
  public:
    void setLine(std::string line) {
        std::lock_guard lock(mutex_);
        line_ = std::move(line);
        std::fprintf(stderr, "\r\033[K%s", line_.c_str());
        std::fflush(stderr);
    }
    void endLine() {
        std::lock_guard lock(mutex_);
        if (!line_.empty()) std::fputc('\n', stderr);
        line_.clear();
        std::fflush(stderr);
    }

  protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        spdlog::memory_buf_t text;
        formatter_->format(msg, text);
        std::fputs("\r\033[K", stderr);
        std::fwrite(text.data(), 1, text.size(), stderr);
        std::fputs(line_.c_str(), stderr);
        std::fflush(stderr);
    }
    void flush_() override { std::fflush(stderr); }

  private:
    std::string line_;
};

std::shared_ptr<ProgressLine> ProgressLine::attachIfTerminal(int totalFrames, bool limited) {
    if ((totalFrames <= 0 && !limited) || !isatty(STDERR_FILENO)) return nullptr;
    auto sink = std::make_shared<ProgressSink>();
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.clear();
    sinks.push_back(sink);
    return std::make_shared<ProgressLine>(totalFrames, std::move(sink));
}

ProgressLine::ProgressLine(int totalFrames, std::shared_ptr<ProgressSink> sink)
    : totalFrames_(totalFrames), sink_(std::move(sink)) {}

void ProgressLine::update(int framesDone, double fps, int clients, const std::string& error) {
    const std::string line = format(framesDone, totalFrames_, fps, clients);
    sink_->setLine(error.empty() ? line : line + ", " + error);
}

void ProgressLine::finish() {
    sink_->endLine();
}

std::string ProgressLine::format(int framesDone, int totalFrames, double fps, int clients) {
    if (totalFrames <= 0)  // ended by a target or a time limit: no total to count down
        return fmt::format("frame {} {:.2f} fps, {} client{}", framesDone, fps, clients,
                           clients == 1 ? "" : "s");
    constexpr int kBar = 20;
    const int filled = totalFrames > 0 ? kBar * framesDone / totalFrames : 0;
    std::string bar(std::size_t(filled), '=');
    if (filled < kBar) bar += '>';
    bar.resize(kBar, ' ');
    std::string left = "?";
    if (fps > 0) {
        const double seconds = (totalFrames - framesDone) / fps;
        left = seconds >= 90 ? fmt::format("{:.0f} min", std::ceil(seconds / 60))
                             : fmt::format("{:.0f} s", std::ceil(seconds));
    }
    return fmt::format("frame {}/{} [{}] {:.2f} fps, {} left, {} client{}", framesDone, totalFrames,
                       bar, fps, left, clients, clients == 1 ? "" : "s");
}

}  // namespace igi
