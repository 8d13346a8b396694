#include "scene/ObjText.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>

namespace igi {

namespace {

bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
    return s;
}

std::vector<std::string> words(std::string_view s) {
    std::vector<std::string> out;
    while (true) {
        s = trim(s);
        if (s.empty()) return out;
        std::size_t end = 0;
        while (end < s.size() && !isBlank(s[end])) ++end;
        out.emplace_back(s.substr(0, end));
        s.remove_prefix(end);
    }
}

// Number of the current v, vn and vt statements, to resolve relative (negative) indices.
struct VertexCounts {
    long long v = 0, vn = 0, vt = 0;
};

// Checks one "v/vt/vn" reference of a face against the counts so far.
std::optional<std::string> checkReference(std::string_view ref, const VertexCounts& counts) {
    const long long limits[3] = {counts.v, counts.vt, counts.vn};
    const char* names[3] = {"vertex", "texture coordinate", "normal"};
    for (int part = 0; part < 3 && !ref.empty(); ++part) {
        const std::size_t slash = ref.find('/');
        const std::string_view field = ref.substr(0, slash);
        ref = slash == std::string_view::npos ? std::string_view() : ref.substr(slash + 1);
        if (field.empty()) continue;  // "1//3"
        long long index = 0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), index);
        if (ec != std::errc() || end != field.data() + field.size()) {
            return "malformed face index '" + std::string(field) + "'";
        }
        const long long resolved = index < 0 ? limits[part] + index + 1 : index;
        if (index == 0 || resolved < 1 || resolved > limits[part]) {
            return std::string(names[part]) + " index " + std::to_string(index) +
                   " is out of range (" + std::to_string(limits[part]) + " defined so far)";
        }
    }
    return std::nullopt;
}

}  // namespace

void forEachLine(std::string_view text, const std::function<bool(int, std::string_view)>& visit) {
    int number = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        const void* nl = std::memchr(text.data() + pos, '\n', text.size() - pos);
        const std::size_t end = nl ? static_cast<const char*>(nl) - text.data() : text.size();
        std::string_view line = text.substr(pos, end - pos);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t'))
            line.remove_prefix(1);
        if (!visit(++number, line)) return;
        pos = end + 1;
    }
}

std::pair<std::string_view, std::string_view> splitKeyword(std::string_view line) {
    line = trim(line);
    std::size_t end = 0;
    while (end < line.size() && !isBlank(line[end])) ++end;
    return {line.substr(0, end), trim(line.substr(end))};
}

std::vector<ObjMaterialStatement> scanMaterialStatements(std::string_view objText) {
    std::vector<ObjMaterialStatement> out;
    forEachLine(objText, [&](int number, std::string_view line) {
        // Cheap reject first: this runs over every line of a 13 MB bunny.
        if (line.empty() || (line[0] != 'u' && line[0] != 'm')) return true;
        const auto [keyword, rest] = splitKeyword(line);
        if (keyword == "mtllib") out.push_back({number, true, words(rest)});
        if (keyword == "usemtl") {
            // tinyobjloader names the material by the first word after usemtl.
            auto w = words(rest);
            out.push_back({number, false, {w.empty() ? std::string() : w.front()}});
        }
        return true;
    });
    return out;
}

std::optional<int> findNonNumericVertexLine(std::string_view objText) {
    std::optional<int> found;
    forEachLine(objText, [&](int number, std::string_view line) {
        if (line.size() < 2 || line[0] != 'v') return true;
        std::size_t start = 1;
        if (line[1] == 'n' || line[1] == 't') start = 2;
        if (start >= line.size() || !isBlank(line[start])) return true;
        for (std::size_t i = start; i < line.size(); ++i) {
            const char c = line[i];
            if (c == '#') break;
            if (std::isalpha(static_cast<unsigned char>(c)) && c != 'e' && c != 'E') {
                found = number;
                return false;
            }
        }
        return true;
    });
    return found;
}

int lineOfStatement(std::string_view objText, std::string_view keyword, std::size_t index) {
    int result = 0;
    std::size_t seen = 0;
    forEachLine(objText, [&](int number, std::string_view line) {
        if (splitKeyword(line).first != keyword) return true;
        if (seen++ != index) return true;
        result = number;
        return false;
    });
    return result;
}

std::optional<BadFaceIndex> findBadFaceIndex(std::string_view objText) {
    std::optional<BadFaceIndex> found;
    VertexCounts counts;
    forEachLine(objText, [&](int number, std::string_view line) {
        const auto [keyword, rest] = splitKeyword(line);
        if (keyword == "v") ++counts.v;
        if (keyword == "vn") ++counts.vn;
        if (keyword == "vt") ++counts.vt;
        if (keyword != "f" && keyword != "l" && keyword != "p") return true;
        for (const std::string& ref : words(rest)) {
            if (ref[0] == '#') break;
            if (auto problem = checkReference(ref, counts)) {
                found = BadFaceIndex{number, *problem};
                return false;
            }
        }
        return true;
    });
    return found;
}

namespace {

// Calls visit(lineNumber, line) for each line ended by "\n", "\r\n" or a lone "\r",
// leading blanks removed.
template <typename Visit>
void forEachObjLine(std::string_view text, Visit visit) {
    // The next '\n' and '\r' at or after pos, each searched for again only once passed, so
    // that a file with one kind of line end only is still read in linear time.
    auto find = [&](char c, std::size_t from) {
        const void* p = std::memchr(text.data() + from, c, text.size() - from);
        return p ? static_cast<std::size_t>(static_cast<const char*>(p) - text.data())
                 : text.size();
    };
    std::size_t nextNl = find('\n', 0), nextCr = find('\r', 0);
    int number = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        if (nextNl < pos) nextNl = find('\n', pos);
        if (nextCr < pos) nextCr = find('\r', pos);
        std::size_t end = std::min(nextNl, nextCr);
        std::string_view line = text.substr(pos, end - pos);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t'))
            line.remove_prefix(1);
        visit(++number, line);
        if (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ++end;
        pos = end + 1;
    }
}

// The words of an index statement's arguments, and whether one of its numbers is outside the
// range of an int; one pass, since this runs over every face of a large mesh.
struct IndexWords {
    std::size_t words = 0;
    bool beyondInt = false;
};

IndexWords scanIndexWords(std::string_view args) {
    IndexWords out;
    bool inWord = false;
    std::size_t digits = 0, longest = 0;
    for (char c : args) {
        const bool blank = c == ' ' || c == '\t';
        if (!blank && !inWord) ++out.words;
        inWord = !blank;
        digits = c >= '0' && c <= '9' ? digits + 1 : 0;
        longest = std::max(longest, digits);
    }
    // 2147483647 has 10 digits: only longer runs need a closer look (leading zeros).
    if (longest < 10) return out;
    for (std::size_t pos = 0; pos < args.size();) {
        const std::size_t start = args.find_first_of("0123456789", pos);
        if (start == std::string_view::npos) break;
        std::size_t end = args.find_first_not_of("0123456789", start);
        if (end == std::string_view::npos) end = args.size();
        long long value = 0;
        const auto [ptr, ec] = std::from_chars(args.data() + start, args.data() + end, value);
        if (ec != std::errc() || value > 2147483647LL) out.beyondInt = true;
        pos = end;
    }
    return out;
}

// tinyobjloader's test for a statement: the keyword, then a space or a tab.
bool isStatement(std::string_view line, std::string_view keyword) {
    return line.size() > keyword.size() && line.substr(0, keyword.size()) == keyword &&
           (line[keyword.size()] == ' ' || line[keyword.size()] == '\t');
}

}  // namespace

ObjStatementCounts countObjStatements(std::string_view objText) {
    ObjStatementCounts counts;
    forEachObjLine(objText, [&](int number, std::string_view line) {
        if (line.size() < 2) return;
        switch (line[0]) {
            case 'v':
                if (isStatement(line, "v")) ++counts.positions;
                if (isStatement(line, "vn")) ++counts.normals;
                if (isStatement(line, "vt")) ++counts.texcoords;
                return;
            case 'f':
                if (isStatement(line, "f")) {
                    const IndexWords scan = scanIndexWords(line.substr(2));
                    counts.indexBeyondInt = counts.indexBeyondInt || scan.beyondInt;
                    const std::size_t corners = scan.words;
                    if (corners >= 3) counts.triangles += corners - 2;
                    if (corners > counts.mostFaceCorners) {
                        counts.mostFaceCorners = corners;
                        counts.mostFaceCornersLine = number;
                    }
                }
                return;
            case 'l':
            case 'p':
                if (line[1] == ' ' || line[1] == '\t') {
                    const IndexWords scan = scanIndexWords(line.substr(2));
                    counts.indexBeyondInt = counts.indexBeyondInt || scan.beyondInt;
                    counts.triangles += scan.words;
                }
                return;
            case 'o':
            case 'g':
                if (line[1] == ' ' || line[1] == '\t') ++counts.groups;
                return;
            default:
                return;
        }
    });
    return counts;
}

std::size_t countNewmtl(std::string_view mtlText) {
    std::size_t count = 0;
    forEachObjLine(mtlText, [&](int, std::string_view line) {
        if (line.rfind("newmtl", 0) == 0) ++count;
    });
    return count;
}

int mtlLine(std::string_view mtlText, const std::string& material, std::string_view keyword) {
    int newmtlLine = 0;
    int keywordLine = 0;
    bool inside = false;
    forEachLine(mtlText, [&](int number, std::string_view line) {
        const auto [key, rest] = splitKeyword(line);
        if (key == "newmtl") {
            if (inside) return false;  // left the material without finding the keyword
            inside = rest == material;
            if (inside) newmtlLine = number;
            return true;
        }
        if (inside && key == keyword) {
            keywordLine = number;
            return false;
        }
        return true;
    });
    return keywordLine > 0 ? keywordLine : newmtlLine;
}

}  // namespace igi
