#pragma once

// Typed reads from a parsed JSON scene file that know where they are: every failure throws a
// SceneError naming the file and the JSON path ("/meshes/1/transform/scale") of the value.
// Internal to the scene loaders; it is the one header here that includes nlohmann.

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace igi {

/// An interval of allowed values, each end open or closed, printed in messages as "(0, 180)".
struct NumberRange {
    double lo = -HUGE_VAL;
    double hi = HUGE_VAL;
    bool loOpen = false;
    bool hiOpen = false;

    static NumberRange any() { return {}; }
    static NumberRange closed(double lo, double hi) { return {lo, hi, false, false}; }
    static NumberRange open(double lo, double hi) { return {lo, hi, true, true}; }
    static NumberRange atLeast(double lo) { return {lo, HUGE_VAL, false, false}; }
    static NumberRange above(double lo) { return {lo, HUGE_VAL, true, false}; }
    /// [lo, hi)
    static NumberRange closedOpen(double lo, double hi) { return {lo, hi, false, true}; }
    /// (lo, hi]
    static NumberRange openClosed(double lo, double hi) { return {lo, hi, true, false}; }

    bool contains(double v) const;
    std::string text() const;
};

/// Escapes a key for use in a JSON pointer (RFC 6901: "~" -> "~0", "/" -> "~1").
std::string jsonPointerEscape(const std::string& key);

/// Parses JSON text; a syntax error becomes a SceneError at the line, with the column in the
/// message.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);

/// A JSON value together with the file it came from and its path inside it.
class JsonNode {
  public:
    JsonNode(const nlohmann::json& value, std::string file, std::string path);

    const nlohmann::json& value() const { return *value_; }
    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; }

    [[noreturn]] void fail(const std::string& message) const;

    void requireObject() const;
    /// Requires an object whose keys are all in `allowed`; the error names the unknown key's
    /// path and lists the allowed keys.
    void checkKeys(std::initializer_list<const char*> allowed) const;
    bool has(const std::string& key) const;
    /// A member that must be present.
    JsonNode at(const std::string& key) const;
    std::optional<JsonNode> find(const std::string& key) const;
    /// An object's members, sorted by key (nlohmann::json keeps objects in a std::map).
    std::vector<std::pair<std::string, JsonNode>> members() const;
    /// An array's elements; `expectedSize` < 0 accepts any size.
    std::vector<JsonNode> elements(int expectedSize = -1) const;

    /// A finite number inside `range`.
    double number(NumberRange range = NumberRange::any()) const;
    /// A number that is also finite as a float (1e300 is a finite double but not a float).
    float real(NumberRange range = NumberRange::any()) const;
    /// An integer (no fraction, no exponent) in [lo, hi].
    std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
    std::uint64_t unsignedInteger() const;
    bool boolean() const;
    std::string string() const;
    /// A string that must be one of `choices`.
    std::string choice(std::initializer_list<const char*> choices) const;
    /// [x, y, z], each component in `range`.
    glm::vec3 vec3(NumberRange range = NumberRange::any()) const;
    /// [r, g, b] or one number for grey, each in `range`.
    glm::vec3 rgb(NumberRange range) const;

  private:
    const std::string& typeName() const;

    const nlohmann::json* value_;
    std::string file_;
    std::string path_;
};

}  // namespace igi
