#pragma once

// Line-level scans of OBJ and MTL text. tinyobjloader parses the files but reports few
// line numbers, so the OBJ loader scans the text itself to name the line of what is wrong.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace igi {

/// Calls `visit(lineNumber, line)` for every line (1-based, without the end of line), with
/// leading blanks removed; stops early when `visit` returns false.
void forEachLine(std::string_view text, const std::function<bool(int, std::string_view)>& visit);

/// The first word of a line ("usemtl" in "usemtl light") and the rest, trimmed.
std::pair<std::string_view, std::string_view> splitKeyword(std::string_view line);

/// An OBJ statement that refers to a material or a material library.
struct ObjMaterialStatement {
    int line = 0;
    bool isLibrary = false;  ///< mtllib (names are files) or usemtl (one material name)
    std::vector<std::string> names;
};

/// Every mtllib and usemtl statement of an OBJ file, in order.
std::vector<ObjMaterialStatement> scanMaterialStatements(std::string_view objText);

/// The line of the first v/vn/vt statement whose numbers are not plain numbers ("nan",
/// "inf"), which tinyobjloader would silently read as 0.
std::optional<int> findNonNumericVertexLine(std::string_view objText);

/// The line of the `index`-th (0-based) statement with keyword `keyword` ("v", "vn", "vt").
int lineOfStatement(std::string_view objText, std::string_view keyword, std::size_t index);

/// A face (or line/point) index that is zero or outside the vertices defined so far.
struct BadFaceIndex {
    int line = 0;
    std::string message;
};
std::optional<BadFaceIndex> findBadFaceIndex(std::string_view objText);

/// What parsing an OBJ file will cost, counted before tinyobjloader allocates for it.
/// Lines end at "\n", "\r\n" or a lone "\r", as for tinyobjloader; counts err high.
struct ObjStatementCounts {
    std::uint64_t positions = 0;  ///< v
    std::uint64_t normals = 0;    ///< vn
    std::uint64_t texcoords = 0;  ///< vt
    /// Triangles the faces become (corners - 2 each), plus one per `l` and `p` index (not
    /// rendered, but tinyobjloader stores them).
    std::uint64_t triangles = 0;
    std::uint64_t groups = 0;  ///< o and g
    std::size_t mostFaceCorners = 0;
    int mostFaceCornersLine = 0;  ///< the first face with that many
    /// A face, line or point index beyond an int, which tinyobjloader would wrap around
    /// (4294967299 reads as 3).
    bool indexBeyondInt = false;
};
ObjStatementCounts countObjStatements(std::string_view objText);

/// The number of `newmtl` statements of an MTL file.
std::size_t countNewmtl(std::string_view mtlText);

/// The line of `keyword` inside material `material` of an MTL file, or of its `newmtl`
/// statement when the keyword is not found, or 0.
int mtlLine(std::string_view mtlText, const std::string& material, std::string_view keyword);

}  // namespace igi
