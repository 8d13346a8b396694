#include "scene/GltfPrescan.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

#include "scene/SceneError.h"

namespace igi {

namespace {

using Json = nlohmann::json;

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
    return b > std::numeric_limits<std::uint64_t>::max() - a
               ? std::numeric_limits<std::uint64_t>::max()
               : a + b;
}

// A JSON number as a size, erring high (tinygltf converts doubles too).
std::uint64_t asSize(double v) {
    if (!(v > 0.0)) return 0;
    if (v >= 1.8e19) return std::numeric_limits<std::uint64_t>::max();
    return static_cast<std::uint64_t>(v);
}

// Follows where each value is (only the first four levels matter) and records what
// GltfPrescan wants. Returns false, which stops nlohmann, past the value limit.
class PrescanHandler : public nlohmann::json_sax<Json> {
  public:
    PrescanHandler(GltfPrescan& out, std::uint64_t maxValues, std::size_t maxDepth)
        : out_(out), maxValues_(maxValues), maxDepth_(maxDepth) {}

    bool null() override { return enter(); }
    bool boolean(bool) override { return enter(); }
    bool number_integer(number_integer_t v) override {
        return number(static_cast<double>(v), v < 0 ? 0 : static_cast<std::uint64_t>(v));
    }
    bool number_unsigned(number_unsigned_t v) override { return number(static_cast<double>(v), v); }
    bool number_float(number_float_t v, const string_t&) override { return number(v, asSize(v)); }
    bool string(string_t& v) override {
        if (!enter()) return false;
        if (scalarKey() == "uri") {
            if (topKey() == "buffers" && !out_.buffers.empty()) out_.buffers.back().uri = v;
            if (topKey() == "images" && !out_.images.empty()) out_.images.back().uri = v;
        }
        return true;
    }
    bool binary(binary_t&) override { return enter(); }
    bool start_object(std::size_t) override {
        if (!enter()) return false;
        stack_.push_back({false, {}, 0});
        return deeper();
    }
    bool key(string_t& k) override {
        stack_.back().key = k;
        return true;
    }
    bool end_object() override {
        stack_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        if (!enter()) return false;
        stack_.push_back({true, {}, 0});
        return deeper();
    }
    bool end_array() override {
        stack_.pop_back();
        return true;
    }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& e) override {
        error_ = "JSON syntax error at byte " + std::to_string(position) + ": " + e.what();
        return false;
    }

    const std::string& error() const { return error_; }

  private:
    struct Frame {
        bool array;
        std::string key;      // the current member's key (objects)
        std::uint64_t count;  // elements so far (arrays)
    };

    // The key of the top-level member we are in, or "".
    const std::string& topKey() const {
        static const std::string none;
        return stack_.size() >= 2 && !stack_[0].array && stack_[1].array ? stack_[0].key : none;
    }

    // For a scalar member of a top-level array's element (buffers[i].uri): its key, or "".
    const std::string& scalarKey() const {
        static const std::string none;
        return stack_.size() == 3 && !stack_[2].array ? stack_[2].key : none;
    }

    bool number(double v, std::uint64_t size) {
        if (!enter()) return false;
        const std::string& key = scalarKey();
        if (key.empty()) return true;
        const std::string& top = topKey();
        if (top == "buffers" && key == "byteLength" && !out_.buffers.empty())
            out_.buffers.back().byteLength = size;
        if (top == "bufferViews" && !out_.bufferViews.empty()) {
            auto& view = out_.bufferViews.back();
            if (key == "buffer") view.buffer = index(v);
            if (key == "byteOffset") view.byteOffset = size;
            if (key == "byteLength") view.byteLength = size;
        }
        if (top == "images" && key == "bufferView" && !out_.images.empty())
            out_.images.back().bufferView = index(v);
        return true;
    }

    // An index as written; -1 for none, a huge one for a huge or fractional one (which no
    // array has).
    static long long index(double v) {
        if (v < 0.0) return -1;
        if (v != std::floor(v) || v >= 1e18) return std::numeric_limits<long long>::max();
        return static_cast<long long>(v);
    }

    bool deeper() {
        out_.depth = std::max(out_.depth, stack_.size());
        return out_.depth <= maxDepth_;
    }

    // Called as every value starts, before it is pushed (for objects and arrays).
    bool enter() {
        if (++out_.jsonValues > maxValues_) return false;
        if (stack_.empty()) return true;
        Frame& parent = stack_.back();
        if (parent.array) ++parent.count;
        // An element of a top-level array.
        if (stack_.size() == 2 && !stack_[0].array && parent.array) {
            const std::string& top = stack_[0].key;
            ++out_.arrayElements[top];
            if (top == "buffers") out_.buffers.emplace_back();
            if (top == "images") out_.images.emplace_back();
            if (top == "bufferViews") out_.bufferViews.emplace_back();
        }
        // An element of meshes[i].primitives.
        if (stack_.size() == 4 && parent.array && !stack_[0].array && stack_[1].array &&
            !stack_[2].array && stack_[0].key == "meshes" && stack_[2].key == "primitives") {
            ++out_.primitives;
        }
        return true;
    }

    GltfPrescan& out_;
    std::uint64_t maxValues_;
    std::size_t maxDepth_;
    std::vector<Frame> stack_;
    std::string error_;
};

}  // namespace

std::uint64_t GltfPrescan::objects() const {
    std::uint64_t total = primitives;
    for (const auto& [name, n] : arrayElements) total = saturatingAdd(total, n);
    return total;
}

std::uint64_t GltfPrescan::count(const std::string& array) const {
    auto it = arrayElements.find(array);
    return it == arrayElements.end() ? 0 : it->second;
}

GltfPrescan prescanGltfJson(const std::string& json, const std::string& file,
                            std::uint64_t maxJsonValues, std::size_t maxDepth) {
    GltfPrescan out;
    PrescanHandler handler(out, maxJsonValues, maxDepth);
    const bool ok = Json::sax_parse(json, &handler);
    if (!ok && !handler.error().empty())
        throw SceneError::inFile(file, "cannot load glTF: " + handler.error());
    return out;
}

std::string glbJsonChunk(const std::string& bytes, const std::string& file) {
    // The header (magic, version, length), then the JSON chunk (length, "JSON", data).
    if (bytes.size() < 20) throw SceneError::inFile(file, "invalid glTF binary: too short");
    std::uint32_t chunkLength = 0, chunkType = 0;
    std::memcpy(&chunkLength, bytes.data() + 12, 4);
    std::memcpy(&chunkType, bytes.data() + 16, 4);
    if (chunkType != 0x4E4F534A || chunkLength < 1 || chunkLength > bytes.size() - 20) {
        throw SceneError::inFile(file, "invalid glTF binary: bad JSON chunk header");
    }
    return bytes.substr(20, chunkLength);
}

std::string decodeUri(const std::string& uri) {
    // tinygltf's dlib::urldecode, which is not part of its interface.
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace igi
