#include "SequencePath.h"

#include <cctype>
#include <stdexcept>

namespace igi {
namespace {

// Finds the one conversion "%[0][width]d": its start and end (one past the 'd').
std::pair<std::size_t, std::size_t> findConversion(const std::string& p, int& width) {
    std::size_t start = std::string::npos, end = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p[i] != '%') continue;
        if (i + 1 < p.size() && p[i + 1] == '%') {
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        while (j < p.size() && std::isdigit(static_cast<unsigned char>(p[j]))) ++j;
        if (j >= p.size() || p[j] != 'd' || j - i - 1 > 2)
            throw std::invalid_argument("output sequence '" + p +
                                        "': only %d or %0Nd (N < 100) may follow a '%'");
        if (start != std::string::npos)
            throw std::invalid_argument("output sequence '" + p +
                                        "' has more than one frame number");
        width = j > i + 1 ? std::stoi(p.substr(i + 1, j - i - 1)) : 0;
        start = i;
        end = j + 1;
        i = j;
    }
    if (start == std::string::npos)
        throw std::invalid_argument("output sequence '" + p + "' has no frame number (%04d, say)");
    return {start, end};
}

std::string unescape(const std::string& s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        out += s[i];
        if (s[i] == '%' && i + 1 < s.size() && s[i + 1] == '%') ++i;
    }
    return out;
}

}  // namespace

void checkSequencePattern(const std::string& pattern) {
    int width = 0;
    findConversion(pattern, width);
    const auto dot = pattern.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : pattern.substr(dot);
    if (ext != ".png" && ext != ".exr")
        throw std::invalid_argument("output sequence '" + pattern + "' must end in .png or .exr");
}

std::string sequencePath(const std::string& pattern, std::uint32_t frame) {
    int width = 0;
    const auto [start, end] = findConversion(pattern, width);
    std::string number = std::to_string(frame);
    if (int(number.size()) < width) number.insert(0, std::size_t(width) - number.size(), '0');
    return unescape(pattern.substr(0, start)) + number + unescape(pattern.substr(end));
}

}  // namespace igi
