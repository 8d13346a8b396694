#include "ProgressLine.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <mutex>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace igi {

/// Writes log records to `out` above the progress line: "\r\033[K" clears the line, the record
/// prints, the line is drawn again. One mutex orders records and redraws from any thread.
class ProgressSink : public spdlog::sinks::base_sink<std::mutex> {
  public:
    explicit ProgressSink(std::FILE* out) : out_(out) {}

    void setLine(std::string line) {
        std::lock_guard lock(mutex_);
        line_ = std::move(line);
        std::fprintf(out_, "\r\033[K%s", line_.c_str());
        std::fflush(out_);
    }
    void endLine() {
        std::lock_guard lock(mutex_);
        if (!line_.empty()) std::fputc('\n', out_);
        line_.clear();
        std::fflush(out_);
    }
    void printAbove(const std::string& text) {
        std::lock_guard lock(mutex_);
        writeAbove(text.data(), text.size(), true);
    }

  protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        spdlog::memory_buf_t text;
        formatter_->format(msg, text);
        writeAbove(text.data(), text.size(), false);
    }
    void flush_() override { std::fflush(out_); }

  private:
    // The caller holds mutex_.
    void writeAbove(const char* text, std::size_t size, bool addNewline) {
        std::fputs("\r\033[K", out_);
        std::fwrite(text, 1, size, out_);
        if (addNewline) std::fputc('\n', out_);
        std::fputs(line_.c_str(), out_);
        std::fflush(out_);
    }

    std::FILE* out_;
    std::string line_;
};

std::shared_ptr<ProgressLine> ProgressLine::attachIfTerminal(int totalFrames, bool limited) {
    if ((totalFrames <= 0 && !limited) || !isatty(STDERR_FILENO)) return nullptr;
    auto line = std::make_shared<ProgressLine>(totalFrames, stderr);
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.clear();
    sinks.push_back(line->sink_);
    return line;
}

ProgressLine::ProgressLine(int totalFrames, std::FILE* out)
    : totalFrames_(totalFrames), sink_(std::make_shared<ProgressSink>(out)) {}

void ProgressLine::update(int framesDone, double fps, int clients, const std::string& error) {
    const std::string line = format(framesDone, totalFrames_, fps, clients);
    sink_->setLine(error.empty() ? line : line + ", " + error);
}

void ProgressLine::printAbove(const std::string& line) {
    sink_->printAbove(line);
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
