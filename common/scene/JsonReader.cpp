#include "scene/JsonReader.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "scene/KeySuggestion.h"
#include "scene/SceneError.h"

namespace igi {

namespace {

std::string formatNumber(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

std::string describe(const nlohmann::json& v) {
    std::string text = v.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

// nlohmann reports the byte offset just past the offending character (1-based); editors want
// line and column.
std::pair<int, int> lineAndColumn(const std::string& text, std::size_t byte) {
    const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
    int line = 1;
    std::size_t lineStart = 0;
    for (std::size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    }
    return {line, static_cast<int>(end - lineStart) + 1};
}

// Drops nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: " prefix:
// the SceneError already says where.
std::string parseErrorReason(const std::string& what) {
    const std::size_t column = what.find("column");
    const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
    return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

bool NumberRange::contains(double v) const {
    const bool aboveLo = loOpen ? v > lo : v >= lo;
    const bool belowHi = hiOpen ? v < hi : v <= hi;
    return aboveLo && belowHi;
}

std::string NumberRange::text() const {
    return std::string(loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
           (hiOpen ? ")" : "]");
}

std::string jsonPointerEscape(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~') {
            out += "~0";
        } else if (c == '/') {
            out += "~1";
        } else {
            out += c;
        }
    }
    return out;
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        const auto [line, column] = lineAndColumn(text, e.byte);
        throw SceneError::atLine(
            file, line, "column " + std::to_string(column) + ": " + parseErrorReason(e.what()));
    } catch (const nlohmann::json::out_of_range& e) {
        // A number such as 1e999 overflows while parsing; nlohmann names the literal, not
        // where it is, so look for it.
        const std::string what = e.what();
        const std::size_t open = what.find('\'');
        const std::size_t close = what.rfind('\'');
        const std::string literal = open < close ? what.substr(open + 1, close - open - 1) : "";
        const std::size_t at = literal.empty() ? std::string::npos : text.find(literal);
        if (at == std::string::npos) throw SceneError::inFile(file, "number overflow");
        const auto [line, column] = lineAndColumn(text, at + 1);
        throw SceneError::atLine(
            file, line,
            "column " + std::to_string(column) + ": number " + literal + " overflows (not finite)");
    }
}

JsonNode::JsonNode(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

void JsonNode::fail(const std::string& message) const {
    throw SceneError::atPath(file_, path_, message);
}

const std::string& JsonNode::typeName() const {
    static const std::string names[] = {"null",   "object", "array",  "string", "boolean",
                                        "number", "number", "number", "binary", "nothing"};
    const auto index = static_cast<std::size_t>(value_->type());
    return names[index < std::size(names) ? index : std::size(names) - 1];
}

void JsonNode::requireObject() const {
    if (!value_->is_object()) fail("expected an object, got " + typeName());
}

void JsonNode::checkKeys(std::initializer_list<const char*> allowed) const {
    requireObject();
    for (const auto& [key, v] : value_->items()) {
        bool known = false;
        for (const char* a : allowed) known = known || key == a;
        if (known) continue;
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        throw SceneError::atPath(
            file_, path_ + "/" + jsonPointerEscape(key),
            "unknown key (expected one of: " + list + ")" +
                didYouMean(key, std::vector<std::string>(allowed.begin(), allowed.end())));
    }
}

bool JsonNode::has(const std::string& key) const {
    return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::at(const std::string& key) const {
    requireObject();
    auto it = value_->find(key);
    if (it == value_->end()) fail("missing required key '" + key + "'");
    return JsonNode(*it, file_, path_ + "/" + jsonPointerEscape(key));
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
    requireObject();
    auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return JsonNode(*it, file_, path_ + "/" + jsonPointerEscape(key));
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::members() const {
    requireObject();
    std::vector<std::pair<std::string, JsonNode>> out;
    for (const auto& [key, v] : value_->items()) {
        out.emplace_back(key, JsonNode(v, file_, path_ + "/" + jsonPointerEscape(key)));
    }
    return out;
}

std::vector<JsonNode> JsonNode::elements(int expectedSize) const {
    if (!value_->is_array()) fail("expected an array, got " + typeName());
    if (expectedSize >= 0 && value_->size() != static_cast<std::size_t>(expectedSize)) {
        fail("expected an array of " + std::to_string(expectedSize) + " elements, got " +
             std::to_string(value_->size()));
    }
    std::vector<JsonNode> out;
    out.reserve(value_->size());
    for (std::size_t i = 0; i < value_->size(); ++i) {
        out.emplace_back((*value_)[i], file_, path_ + "/" + std::to_string(i));
    }
    return out;
}

double JsonNode::number(NumberRange range) const {
    if (!value_->is_number()) fail("expected a number, got " + describe(*value_));
    const double v = value_->get<double>();
    // nlohmann turns 1e999 into inf instead of failing.
    if (!std::isfinite(v)) fail("number is not finite (overflow?)");
    if (!range.contains(v)) fail("must be in " + range.text() + ", got " + formatNumber(v));
    return v;
}

float JsonNode::real(NumberRange range) const {
    const double v = number(range);
    if (std::abs(v) > std::numeric_limits<float>::max()) {
        fail("number " + formatNumber(v) + " is too large for single precision");
    }
    return static_cast<float>(v);
}

std::int64_t JsonNode::integer(std::int64_t lo, std::int64_t hi) const {
    if (!value_->is_number_integer()) fail("expected an integer, got " + describe(*value_));
    std::ostringstream range;  // (not string concatenation: GCC 12 warns falsely on it here)
    range << '[' << lo << ", " << hi << ']';
    const std::string rangeText = range.str();
    if (value_->is_number_unsigned()) {
        const auto u = value_->get<std::uint64_t>();
        if (hi < 0 || u > static_cast<std::uint64_t>(hi) ||
            (lo > 0 && u < static_cast<std::uint64_t>(lo))) {
            fail("must be in " + rangeText + ", got " + std::to_string(u));
        }
        return static_cast<std::int64_t>(u);
    }
    const auto v = value_->get<std::int64_t>();
    if (v < lo || v > hi) fail("must be in " + rangeText + ", got " + std::to_string(v));
    return v;
}

std::uint64_t JsonNode::unsignedInteger() const {
    if (!value_->is_number_integer()) fail("expected an integer, got " + describe(*value_));
    if (!value_->is_number_unsigned()) fail("must not be negative, got " + describe(*value_));
    return value_->get<std::uint64_t>();
}

bool JsonNode::boolean() const {
    if (!value_->is_boolean()) fail("expected true or false, got " + describe(*value_));
    return value_->get<bool>();
}

std::string JsonNode::string() const {
    if (!value_->is_string()) fail("expected a string, got " + describe(*value_));
    return value_->get<std::string>();
}

std::string JsonNode::choice(std::initializer_list<const char*> choices) const {
    const std::string s = string();
    std::string list;
    for (const char* c : choices) {
        if (s == c) return s;
        list += (list.empty() ? "" : ", ") + std::string(c);
    }
    fail("unknown value '" + s + "' (expected one of: " + list + ")");
}

glm::vec3 JsonNode::vec3(NumberRange range) const {
    const auto e = elements(3);
    return {e[0].real(range), e[1].real(range), e[2].real(range)};
}

glm::vec3 JsonNode::rgb(NumberRange range) const {
    if (value_->is_number()) return glm::vec3(real(range));
    if (!value_->is_array()) fail("expected [r, g, b] or a number, got " + describe(*value_));
    return vec3(range);
}

}  // namespace igi
