// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/mesh_loader.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace hcd
{
static_assert(kMaxFaceVertices == AI_MAX_FACE_INDICES, "the PLY list bound is assimp's face bound");

namespace
{
// Depth-first over the node graph in the order OMPL.app walks it, transform = parent * node.
template <typename Visit>
void visitNodes(const aiScene *scene, const aiNode *node, aiMatrix4x4 transform, const Visit &visit)
{
    transform *= node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
        visit(scene->mMeshes[node->mMeshes[i]], transform);
    for (unsigned c = 0; c < node->mNumChildren; ++c)
        visitNodes(scene, node->mChildren[c], transform, visit);
}

// What the loader takes from one assimp import: triangle corners in single precision, as
// OMPL.app has them, and the sum and count of all instanced vertices for the robot's centring.
struct Imported
{
    std::vector<aiVector3D> corners;  // three per triangle
    aiVector3D vertexSum{0.0f, 0.0f, 0.0f};
    Vec3 vertexSumInDouble = Vec3::Zero();  // for when the float sum overflows
    std::size_t vertexCount = 0;
    std::size_t skippedNonTriangles = 0;
};

// Where the mesh comes from: a file, or a buffer (with a format hint) named `name` in errors.
struct Source
{
    const std::string &name;
    bool inMemory = false;
    std::string_view data;
    const std::string *formatHint = nullptr;
};

// Finishes an import made with aiProcess_ValidateDataStructure only. Three guards against
// malformed files that otherwise reach a failed assertion in assimp's triangulation, which aborts
// the process: validation rejects e.g. an OFF file whose last face lost its line; a face without
// any vertex index (a PLY face list cut short reads "0 0 0" as empty faces, which assimp's
// validation lets through when the reader left the primitive types unset) is an error here; and
// the primitive-type flags are recomputed from the faces, since triangulation asserts that a mesh
// flagged as holding polygons holds one. None of this changes a valid scene; the post-processing
// that follows is OMPL.app's, as ReadFile would have applied it. Before it, the triangulation's
// work is bounded: about n^2 steps for a face of n vertices (eight 32,000-vertex faces of a 2.8 MB
// OBJ file took over a minute), at most kPolygonWorkPerTriangle per triangle allowed.
const aiScene *postProcess(Assimp::Importer &importer, const aiScene *scene, unsigned flags, const std::string &name,
                           const MeshLimits &limits)
{
    if (scene == nullptr)
        return nullptr;
    std::uintmax_t polygonWork = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i)
        for (unsigned f = 0; f < scene->mMeshes[i]->mNumFaces; ++f)
            if (const std::uintmax_t n = scene->mMeshes[i]->mFaces[f].mNumIndices; n > 3)
                polygonWork += n * n;
    const std::uintmax_t maxPolygonWork = std::uintmax_t(limits.maxTriangles) * kPolygonWorkPerTriangle;
    if (polygonWork > maxPolygonWork)
        throw InputError(name, 0,
                         "the mesh's polygons are too large to triangulate: the sum over its faces of more than "
                         "three vertices of (vertices per face)^2 is " +
                             std::to_string(polygonWork) + ", above the limit of " + std::to_string(maxPolygonWork) +
                             " (" + std::to_string(kPolygonWorkPerTriangle) + " for each of the " +
                             std::to_string(limits.maxTriangles) +
                             " triangles allowed per mesh; the command line's --max-triangles raises it)");
    for (unsigned i = 0; i < scene->mNumMeshes; ++i)
    {
        aiMesh *m = scene->mMeshes[i];
        unsigned types = 0;
        for (unsigned f = 0; f < m->mNumFaces; ++f)
        {
            const unsigned n = m->mFaces[f].mNumIndices;
            if (n == 0 || m->mFaces[f].mIndices == nullptr)
                throw InputError(name, 0,
                                 "malformed mesh: face " + std::to_string(f) + " of mesh " + std::to_string(i) +
                                     " has no vertex index");
            types |= n == 1   ? aiPrimitiveType_POINT
                     : n == 2 ? aiPrimitiveType_LINE
                     : n == 3 ? aiPrimitiveType_TRIANGLE
                              : aiPrimitiveType_POLYGON;
        }
        m->mPrimitiveTypes = types;
    }
    return importer.ApplyPostProcessing(flags);
}

std::string lowercase(std::string_view text)
{
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

// Whitespace-separated tokens of `data`, at most `count` of them; with `comments`, '#' comments
// (to the end of the line) are skipped.
std::vector<std::string_view> leadingTokens(std::string_view data, std::size_t count, bool comments = true)
{
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (tokens.size() < count && i < data.size())
    {
        const unsigned char c = static_cast<unsigned char>(data[i]);
        if (std::isspace(c))
            ++i;
        else if (comments && c == '#')
            i = std::min(data.size(), data.find('\n', i));
        else
        {
            std::size_t j = i;
            while (j < data.size() && !std::isspace(static_cast<unsigned char>(data[j])))
                ++j;
            tokens.push_back(data.substr(i, j - i));
            i = j;
        }
    }
    return tokens;
}

// The leading decimal digits of `token` as a number, saturated at the largest value.
std::uintmax_t leadingCount(std::string_view token)
{
    std::uintmax_t value = 0;
    for (char c : token)
    {
        if (c < '0' || c > '9')
            break;
        const std::uintmax_t digit = std::uintmax_t(c - '0');
        if (value > (std::numeric_limits<std::uintmax_t>::max() - digit) / 10)
            return std::numeric_limits<std::uintmax_t>::max();
        value = value * 10 + digit;
    }
    return value;
}

// Why one PLY header line (trimmed) is not one the format defines (empty when it is one): a
// garbled line makes assimp misread what follows, e.g. an ASCII body read as binary, with
// gigabytes allocated for the counts it then finds (found by fuzzing,
// tests/fuzz_corpus/mesh/regression_ply_garbled_format_line.ply). Element counts above the data's
// size are refused as well: every element takes at least one byte.
std::string plyHeaderLineProblem(std::string_view line, bool first, std::size_t dataSize)
{
    const auto isType = [](std::string_view t) {
        for (const char *known : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                                  "int16", "uint16", "int32", "uint32", "float32", "float64"})
            if (t == known)
                return true;
        return false;
    };
    const auto isCount = [&](std::string_view t) {
        return !t.empty() && t.find_first_not_of("0123456789") == std::string_view::npos && leadingCount(t) <= dataSize;
    };
    const std::string quoted = "its header line '" + std::string(line.substr(0, 60)) + "' ";
    if (first)
        return line == "ply" ? std::string() : "its first line is not 'ply'";
    // PLY has no '#' comments: a word starting with '#' is an unknown word.
    const std::vector<std::string_view> words = leadingTokens(line, line.size(), false);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info")
        return {};
    if (words[0] == "format")
        return words.size() == 3 &&
                       (words[1] == "ascii" || words[1] == "binary_little_endian" || words[1] == "binary_big_endian") &&
                       words[2] == "1.0"
                   ? std::string()
                   : quoted + "is not a format line (format ascii|binary_little_endian|binary_big_endian 1.0)";
    if (words[0] == "element")
        return words.size() == 3 && isCount(words[2])
                   ? std::string()
                   : quoted + "is not an element line with a count the data can hold";
    if (words[0] == "property")
        return (words.size() == 3 && isType(words[1])) ||
                       (words.size() == 5 && words[1] == "list" && isType(words[2]) && isType(words[3]))
                   ? std::string()
                   : quoted + "is not a property line (property TYPE NAME, or property list TYPE TYPE NAME)";
    return quoted + "is not a PLY header line";
}

// Why the PLY header of `data` cannot be read safely (empty when it can). assimp 5.2's PLY reader
// only stops on a line that is exactly "end_header", and loops without end or reads past the data
// on headers it does not expect: so the header must be lines of printable text ending in such a
// line (found by fuzzing: tests/fuzz_corpus/mesh/regression_ply_*).
std::string plyHeaderProblem(std::string_view data)
{
    constexpr std::string_view word = "end_header";
    for (std::size_t start = 0; start < data.size();)
    {
        std::size_t end = data.find('\n', start);
        if (end == std::string_view::npos)
            end = data.size();
        std::string_view line = data.substr(start, end - start);
        for (char c : line)
        {
            const auto u = static_cast<unsigned char>(c);
            if ((u < 0x20 && c != '\t' && c != '\r') || u > 0x7e)
                return "its header holds a byte that is not printable text (code " + std::to_string(int(u)) + ")";
        }
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
            line.remove_suffix(1);
        if (line == word)
            return {};
        if (const std::string problem = plyHeaderLineProblem(line, start == 0, data.size()); !problem.empty())
            return problem;
        start = end + 1;
    }
    return "its header has no end_header line";
}

// The attributes of every "<..._array" element of COLLADA data (float_array, int_array, ...),
// passed to `visit(attributes)`; false when a tag is not closed.
template <typename Visit>
bool forEachColladaArray(std::string_view data, const Visit &visit)
{
    for (std::size_t at = data.find('<'); at != std::string_view::npos; at = data.find('<', at + 1))
    {
        std::size_t nameEnd = at + 1;
        while (nameEnd < data.size() &&
               (std::isalnum(static_cast<unsigned char>(data[nameEnd])) || data[nameEnd] == '_'))
            ++nameEnd;
        const std::string_view name = data.substr(at + 1, nameEnd - at - 1);
        if (name.size() <= 6 || name.substr(name.size() - 6) != "_array")
            continue;
        const std::size_t close = data.find('>', nameEnd);
        if (close == std::string_view::npos)
            return false;
        visit(data.substr(nameEnd, close - nameEnd));
        at = close;  // on from the tag's end: a search per tag to the same far '>' would be quadratic
    }
    return true;
}

// The text content of every <tag> or <tag ...> element of `data` (up to the next '<'), passed to
// `visit(content)`.
template <typename Visit>
void forEachElementText(std::string_view data, std::string_view tag, const Visit &visit)
{
    const std::string open = "<" + std::string(tag);
    for (std::size_t at = data.find(open); at != std::string_view::npos; at = data.find(open, at + 1))
    {
        const std::size_t after = at + open.size();
        if (after >= data.size() || (data[after] != '>' && !std::isspace(static_cast<unsigned char>(data[after]))))
            continue;  // another tag that starts with the same letters
        const std::size_t close = data.find('>', after);
        if (close == std::string_view::npos)
            return;  // no later tag closes either
        // On from the tag's end: a search per tag to the same far '>' would be quadratic.
        at = close;
        if (data[close - 1] == '/')
            continue;
        const std::size_t end = data.find('<', close + 1);
        visit(data.substr(close + 1, (end == std::string_view::npos ? data.size() : end) - close - 1));
    }
}

// The value of attribute `key` in an element's attribute text, if present.
std::optional<std::string_view> attributeValue(std::string_view attributes, std::string_view key)
{
    for (std::size_t at = attributes.find(key); at != std::string_view::npos; at = attributes.find(key, at + 1))
    {
        const bool wordStart = at == 0 || std::isspace(static_cast<unsigned char>(attributes[at - 1]));
        std::size_t i = at + key.size();
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        if (!wordStart || i >= attributes.size() || attributes[i] != '=')
            continue;
        ++i;
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        if (i >= attributes.size() || (attributes[i] != '"' && attributes[i] != '\''))
            return std::string_view();
        const std::size_t end = attributes.find(attributes[i], i + 1);
        return end == std::string_view::npos ? std::string_view() : attributes.substr(i + 1, end - i - 1);
    }
    return std::nullopt;
}

// Whether text data starts with a UTF-8 byte order mark.
bool startsWithByteOrderMark(std::string_view data) { return data.substr(0, 3) == "\xEF\xBB\xBF"; }

// The first `l` (line) statement of OBJ data that assimp 5.2's OBJ reader could read with fewer
// than two vertices, as its line number and why (line 0 when there is none). The reader counts
// such a statement as no segment yet stores its vertex, so the mesh's vertex array is one vertex
// short for each; after two of them, the middle vertex of a longer `l` statement is copied one
// element past the array's end (a heap overflow of 12 bytes, and as many in the normal and texture
// coordinate arrays; fixed upstream after 5.2.5). glibc noticed only later, on some other free():
// found by fuzzing (tests/fuzz_corpus/mesh/regression_obj_line_with_one_index.obj).
// The check reads lines as the reader does: any line starting with 'l' is a line statement
// whatever its first word, lines end at \n, \r, \f or a zero byte, and a backslash before a line end
// joins the text after the next \n. It accepts a statement only when each word after the first is
// made of digits, '-' and '/' with no number over 9 digits (so the reader's atoi() never
// overflows and its steps stay within the word), and at least two words start with a vertex index
// (a digit, or '-' and a digit): the reader then takes a vertex from each or fails cleanly.
std::pair<int, std::string> objLineStatementProblem(std::string_view data)
{
    const auto lineEnd = [](char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; };
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };
    int line = 1;
    for (std::size_t start = 0; start < data.size(); ++start)
    {
        // Every byte after a line end starts a line; leading blanks are skipped, to be safe.
        std::size_t i = start;
        while (i < data.size() && (data[i] == ' ' || data[i] == '\t'))
            ++i;
        const int statementLine = line;
        std::size_t end = i;  // the line end of the statement (past continuations)
        std::string text;
        while (end < data.size() && !lineEnd(data[end]))
        {
            if (data[end] == '\\' && end + 1 < data.size() && lineEnd(data[end + 1]))
            {
                const std::size_t next = data.find('\n', end + 1);
                line += next != std::string_view::npos;
                end = next == std::string_view::npos ? data.size() : next + 1;
                continue;
            }
            text += data[end++];
        }
        line += end < data.size() && data[end] == '\n';
        start = end;
        if (text.empty() || text[0] != 'l')
            continue;
        // Words after the statement's first, split where the reader splits them.
        int indices = 0;
        for (std::size_t w = text.find_first_of(" \t"); w < text.size() && indices < 2;)
        {
            w = text.find_first_not_of(" \t", w);
            if (w == std::string::npos)
                break;
            const std::string_view word = std::string_view(text).substr(w, text.find_first_of(" \t", w) - w);
            w += word.size();
            std::size_t run = 0;
            for (char c : word)
            {
                run = digit(c) ? run + 1 : 0;
                if ((!digit(c) && c != '-' && c != '/') || run > 9)
                    return {statementLine, "its line statement ('l') holds '" + std::string(word.substr(0, 20)) +
                                               "', not a vertex index"};
            }
            indices += digit(word[0]) || (word.size() > 1 && word[0] == '-' && digit(word[1]));
        }
        if (indices < 2)
            return {statementLine, "its line statement ('l') has " + std::to_string(indices) + " vertex index" +
                                       (indices == 1 ? "" : "es") + " (a line needs two or more)"};
    }
    return {0, {}};
}

// Calls visit(line, text) for each line of OBJ data, from line 1, with `text` its content without
// the line end (\n, \r\n or a lone \r, as the reader's lines end), until visit returns false.
template <class Visit>
void forEachObjLine(std::string_view data, Visit &&visit)
{
    int line = 0;
    for (std::size_t start = 0; start < data.size();)
    {
        std::size_t end = data.find_first_of("\r\n", start);
        if (end == std::string_view::npos)
            end = data.size();
        const std::string_view text = data.substr(start, end - start);
        start = end + (data.substr(end, 2) == "\r\n" ? 2 : 1);
        if (!visit(++line, text))
            return;
    }
}

// The statement keyword `keyword` ("v" or "f") that begins `text` after blanks, as the position of
// its first letter, or npos when text holds another statement.
std::size_t objStatementAt(std::string_view text, char keyword)
{
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string_view::npos || text[first] != keyword || first + 1 >= text.size() ||
        (text[first + 1] != ' ' && text[first + 1] != '\t'))
        return std::string_view::npos;
    return first;
}

// Whether an OBJ statement's text ends in a backslash, which joins the next line to it.
bool continuedOnNextLine(std::string_view text)
{
    const std::size_t last = text.find_last_not_of(" \t");
    return last != std::string_view::npos && text[last] == '\\';
}

// Calls word(w) for each blank-separated word of text after position `from`.
template <class Word>
bool forEachWord(std::string_view text, std::size_t from, Word &&word)
{
    for (std::size_t w = from; (w = text.find_first_not_of(" \t", w)) != std::string_view::npos;)
    {
        const std::size_t wordEnd = std::min(text.find_first_of(" \t", w), text.size());
        if (!word(text.substr(w, wordEnd - w)))
            return false;
        w = wordEnd;
    }
    return true;
}

// The first vertex (`v`) or face (`f`) statement of OBJ data that assimp 5.2's OBJ reader would
// take wrongly or refuse without a line, as its line number and why (line 0 when there is none):
// - the reader reads "nan" and other words that are not numbers as some number (a face through
//   such a vertex was then dropped as degenerate, with no error), and a statement of 5 or 7
//   numbers shifts the vertices after it (a face index then lies out of range, or names the wrong
//   vertex); a vertex statement is accepted with 3 (x y z), 4 (x y z w) or 6 (x y z r g b) finite
//   numbers, up to a comment ('#');
// - it skips an indented statement, which shifts the vertices after it or drops a face silently;
// - a face's vertex index (before any '/') must be a whole number naming a vertex of the file: 1
//   to the number of vertex statements, or -1 to minus the number before the face.
// Statements continued with a backslash are left to the reader.
std::pair<int, std::string> objStatementProblem(std::string_view data)
{
    std::size_t vertices = 0;
    std::pair<int, std::string> problem{0, {}};
    forEachObjLine(data, [&](int line, std::string_view text) {
        const std::size_t at = objStatementAt(text, 'v');
        if (at == std::string_view::npos)
            return true;
        if (at > 0)
        {
            problem = {line, "its vertex statement ('v') is indented, and the OBJ reader reads only a 'v' that "
                             "starts its line as one (the vertices after it would shift)"};
            return false;
        }
        ++vertices;
        if (continuedOnNextLine(text))
            return true;
        // The reader counts the coordinates as the words that start with a digit, '+' or '-' (or
        // spell nan or inf), comments included, and reads that many from the start: the numbers
        // must come first, decimal and finite, and only a comment may follow them.
        int numbers = 0;
        bool comment = false;
        forEachWord(text, 1, [&](std::string_view w) {
            const std::string word(w);
            const char c = word[0];
            const bool counted = (c >= '0' && c <= '9') || c == '+' || c == '-' ||
                                 lowercase(word.substr(0, 3)) == "nan" || lowercase(word.substr(0, 3)) == "inf";
            if (!counted)
            {
                comment = comment || c == '#';
                if (comment)
                    return true;
                problem = {line, "its vertex statement ('v') holds '" + word.substr(0, 20) +
                                     "', which the OBJ reader does not read as a number"};
                return false;
            }
            if (comment)
            {
                problem = {line, "its vertex statement ('v') has a number in its comment, which the OBJ reader "
                                 "counts as a coordinate"};
                return false;
            }
            char *parsed = nullptr;
            const double value = std::strtod(word.c_str(), &parsed);
            if (parsed != word.c_str() + word.size() || !std::isfinite(value) ||
                word.find_first_not_of("0123456789+-.eE") != std::string::npos)
            {
                problem = {line, "its vertex statement ('v') holds '" + word.substr(0, 20) + "', not a finite number"};
                return false;
            }
            if (std::fabs(value) > double(std::numeric_limits<float>::max()))
            {
                // The reader keeps single precision: it would read infinity.
                problem = {line, "its vertex statement ('v') holds '" + word.substr(0, 20) +
                                     "', beyond the OBJ reader's single precision (at most about 3.4e38)"};
                return false;
            }
            ++numbers;
            return true;
        });
        if (problem.second.empty() && numbers != 3 && numbers != 4 && numbers != 6)
            problem = {line, "its vertex statement ('v') holds " + std::to_string(numbers) +
                                 " numbers; the OBJ reader takes 3 (x y z), 4 (x y z w) or 6 (x y z r g b)"};
        return problem.second.empty();
    });
    if (!problem.second.empty())
        return problem;
    std::size_t verticesBefore = 0;
    forEachObjLine(data, [&](int line, std::string_view text) {
        verticesBefore += objStatementAt(text, 'v') != std::string_view::npos;
        const std::size_t at = objStatementAt(text, 'f');
        if (at == std::string_view::npos)
            return true;
        if (at > 0)
        {
            problem = {line, "its face statement ('f') is indented, and the OBJ reader reads only an 'f' that "
                             "starts its line as one (the face would be dropped)"};
            return false;
        }
        if (continuedOnNextLine(text))
            return true;
        forEachWord(text, 1, [&](std::string_view word) {
            const std::string_view index = word.substr(0, word.find('/'));
            const bool negative = !index.empty() && index[0] == '-';
            const std::string_view digits = index.substr(negative ? 1 : 0);
            const bool whole = !digits.empty() && digits.size() <= 9 &&
                               std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
            const std::size_t value = whole ? std::size_t(std::stoul(std::string(digits))) : 0;
            if (!whole || value == 0 || value > (negative ? verticesBefore : vertices))
            {
                problem = {line, "its face statement ('f') holds '" + std::string(word.substr(0, 20)) +
                                     "', not the index of one of the file's " + std::to_string(vertices) + " vertices" +
                                     (negative ? " (counted back from the face)" : "")};
                return false;
            }
            return true;
        });
        return problem.second.empty();
    });
    return problem;
}

// Line number (from 1) of byte `offset` of `data`, for errors.
int lineAt(std::string_view data, std::size_t offset)
{
    return 1 + int(std::count(data.begin(), data.begin() + std::min(offset, data.size()), '\n'));
}

// Saturating arithmetic for counts read from files.
std::uintmax_t saturatingAdd(std::uintmax_t a, std::uintmax_t b)
{
    return a > std::numeric_limits<std::uintmax_t>::max() - b ? std::numeric_limits<std::uintmax_t>::max() : a + b;
}
std::uintmax_t saturatingMul(std::uintmax_t a, std::uintmax_t b)
{
    return b != 0 && a > std::numeric_limits<std::uintmax_t>::max() / b ? std::numeric_limits<std::uintmax_t>::max()
                                                                        : a * b;
}

bool isWholeNumber(std::string_view text)
{
    return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
}

// One element tag of XML data.
struct XmlTag
{
    std::string_view name;
    std::string_view attributes;   // the text between the name and '>' (or "/>")
    bool closing = false;          // </name>
    bool selfClosing = false;      // <name/>
    std::size_t offset = 0;        // of its '<'
    std::size_t contentStart = 0;  // one past its '>'
};

// Where the DOCTYPE declaration starting at `at` ends (one past its '>'), npos when it does not:
// pugixml's reading (assimp's XML parser), so that the tags seen here are the ones it sees.
std::size_t doctypeEnd(std::string_view data, std::size_t at)
{
    const auto startsAt = [&](std::size_t i, std::string_view text) { return data.compare(i, text.size(), text) == 0; };
    std::size_t depth = 0;
    for (std::size_t i = at + 2; i < data.size();)
    {
        if (startsAt(i, "<!["))  // an ignore section, which nests
        {
            std::size_t nested = 0;
            for (i += 3; i < data.size() && !(startsAt(i, "]]>") && nested == 0);)
                if (startsAt(i, "<!["))
                    ++nested, i += 3;
                else if (startsAt(i, "]]>"))
                    --nested, i += 3;
                else
                    ++i;
            if (i >= data.size())
                return std::string_view::npos;
            i += 3;
        }
        else if (startsAt(i, "<!") && !startsAt(i, "<!-"))
            ++depth, i += 2;
        else if (data[i] == '"' || data[i] == '\'')
        {
            i = data.find(data[i], i + 1);
            if (i == std::string_view::npos)
                return i;
            ++i;
        }
        else if (startsAt(i, "<?") || startsAt(i, "<!--"))
        {
            const bool comment = data[i + 1] == '!';
            i = data.find(comment ? "-->" : "?>", i + 2);
            if (i == std::string_view::npos)
                return i;
            i += comment ? 3 : 2;
        }
        else if (data[i] == '<')
            return std::string_view::npos;  // pugixml refuses it
        else if (data[i] == '>' && depth-- == 0)
            return i + 1;
        else
            ++i;
    }
    return std::string_view::npos;
}

// Passes every element tag of XML `data` to `visit(tag)`, skipping comments, CDATA sections,
// processing instructions and the DOCTYPE as pugixml does. Returns why the data is not XML
// pugixml reads (empty when it may be), with the offset of the construct at fault.
template <typename Visit>
std::pair<std::size_t, std::string> forEachXmlTag(std::string_view data, const Visit &visit)
{
    const auto startsAt = [&](std::size_t i, std::string_view text) { return data.compare(i, text.size(), text) == 0; };
    const auto skipTo = [&](std::size_t from, std::string_view end) {
        const std::size_t found = data.find(end, from);
        return found == std::string_view::npos ? found : found + end.size();
    };
    for (std::size_t at = data.find('<'); at != std::string_view::npos; at = data.find('<', at))
    {
        std::size_t next = 0;
        if (startsAt(at, "<!--"))
            next = skipTo(at + 4, "-->");
        else if (startsAt(at, "<![CDATA["))
            next = skipTo(at + 9, "]]>");
        else if (startsAt(at, "<?"))
            next = skipTo(at + 2, "?>");
        else if (startsAt(at, "<!DOCTYPE"))
            next = doctypeEnd(data, at);
        else if (startsAt(at, "<!"))
            return {at, "a declaration '" + std::string(data.substr(at, 12)) + "' XML does not define"};
        else
        {
            XmlTag tag;
            tag.offset = at;
            tag.closing = at + 1 < data.size() && data[at + 1] == '/';
            std::size_t i = at + 1 + tag.closing;
            const std::size_t nameStart = i;
            while (i < data.size() && !std::isspace(static_cast<unsigned char>(data[i])) && data[i] != '>' &&
                   data[i] != '/')
                ++i;
            tag.name = data.substr(nameStart, i - nameStart);
            const std::size_t attributesStart = i;
            for (char quote = 0; i < data.size() && (quote != 0 || data[i] != '>'); ++i)
                if (quote != 0 ? data[i] == quote : data[i] == '"' || data[i] == '\'')
                    quote = quote != 0 ? 0 : data[i];
            if (i >= data.size())
                return {at, "an element tag that is never closed"};
            tag.selfClosing = !tag.closing && i > attributesStart && data[i - 1] == '/';
            tag.attributes = data.substr(attributesStart, i - attributesStart - tag.selfClosing);
            tag.contentStart = i + 1;
            visit(tag);
            next = i + 1;
        }
        if (next == std::string_view::npos)
            return {at, "a comment, CDATA section, processing instruction or DOCTYPE that is never closed"};
        at = next;
    }
    return {0, {}};
}

// The value of attribute `key` of an element's attribute text as an XML parser reads it (the five
// named entities and character references replaced, tabs and line ends read as blanks); nullopt
// when absent. Names are matched whole, so that a value holding "id=" is not taken for one.
std::optional<std::string> xmlAttribute(std::string_view attributes, std::string_view key)
{
    for (std::size_t i = 0; i < attributes.size();)
    {
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        const std::size_t nameStart = i;
        while (i < attributes.size() && attributes[i] != '=' &&
               !std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        const std::string_view name = attributes.substr(nameStart, i - nameStart);
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        if (name.empty() || i >= attributes.size() || attributes[i] != '=')
            return std::nullopt;  // not XML; the parser refuses it
        ++i;
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])))
            ++i;
        if (i >= attributes.size() || (attributes[i] != '"' && attributes[i] != '\''))
            return std::nullopt;
        const std::size_t end = attributes.find(attributes[i], i + 1);
        if (end == std::string_view::npos)
            return std::nullopt;
        const std::string_view raw = attributes.substr(i + 1, end - i - 1);
        i = end + 1;
        if (name != key)
            continue;
        std::string value;
        for (std::size_t k = 0; k < raw.size(); ++k)
        {
            const char c = raw[k];
            // A reference read below is at most 10 characters ("#x" and 7 digits, or "quot"): the
            // search for its ';' stops there, or a run of '&' would make it quadratic.
            const std::size_t window = c == '&' ? raw.substr(k, 12).find(';') : std::string_view::npos;
            const std::size_t semicolon = window == std::string_view::npos ? window : k + window;
            const bool entity = semicolon != std::string_view::npos && semicolon > k + 1;
            if (c == '\r' && k + 1 < raw.size() && raw[k + 1] == '\n')
                continue;  // one blank for the pair
            if (c == '\t' || c == '\n' || c == '\r')
                value += ' ';
            else if (!entity)
                value += c;
            else
            {
                const std::string_view reference = raw.substr(k + 1, semicolon - k - 1);
                const bool hex = reference.size() > 2 && reference[1] == 'x';
                const std::string_view digits =
                    reference.size() > 1 ? reference.substr(hex ? 2 : 1) : std::string_view();
                unsigned long code = 0;
                const bool numeric =
                    reference[0] == '#' && !digits.empty() && digits.size() < 8 &&
                    digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") == std::string_view::npos;
                if (numeric)
                    code = std::stoul(std::string(digits), nullptr, hex ? 16 : 10);
                const std::pair<std::string_view, char> named[] = {
                    {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
                const auto known = std::find_if(std::begin(named), std::end(named),
                                                [&](const auto &n) { return n.first == reference; });
                if (known != std::end(named))
                    value += known->second;
                else if (numeric && code < 0x80)
                    value += char(code);
                else if (numeric && code < 0x800)
                    value += {char(0xc0 | (code >> 6)), char(0x80 | (code & 0x3f))};
                else if (numeric && code < 0x10000)
                    value += {char(0xe0 | (code >> 12)), char(0x80 | ((code >> 6) & 0x3f)), char(0x80 | (code & 0x3f))};
                else if (numeric)
                    value += {char(0xf0 | (code >> 18)), char(0x80 | ((code >> 12) & 0x3f)),
                              char(0x80 | ((code >> 6) & 0x3f)), char(0x80 | (code & 0x3f))};
                else
                {
                    value += c;
                    continue;
                }
                k = semicolon;
            }
        }
        return value;
    }
    return std::nullopt;
}

// Why the structure of COLLADA data would make assimp 5.2 crash or read past its buffers, as the
// line at fault and why (line 0 and empty when it would not):
// - XML elements nested deeper than kMaxColladaDepth: assimp collects them recursively, and
//   overflows the stack (a million nested elements; 10,000 nested <node>s).
// - A node that contains itself through <instance_node> references (a node instancing itself, or
//   L1 -> L2 -> L1): assimp expands instances recursively without end. A hierarchy deeper than
//   kMaxColladaDepth once instances are expanded is refused as well, and one of more than
//   kMaxColladaNodes nodes (assimp copies every instance: 24 nested doublings took 4 GB).
// - An array holding fewer values than its count, or an accessor reading past its array's count
//   (offset + count * stride, and the last element's parameters): assimp keeps `count` values and
//   trusts the accessor, so it read garbage past them, or crashed for an accessor of 4 million
//   vertices over 3 values.
// Instances resolve as assimp resolves them: to a node directly in <library_nodes> or a
// <visual_scene> with that id, else to any node of a visual scene with that id or name.
std::pair<int, std::string> colladaStructureProblem(std::string_view data)
{
    constexpr auto none = std::numeric_limits<std::size_t>::max();
    struct Frame
    {
        std::string_view name;
        std::size_t node;      // the innermost <node> or <visual_scene> open, or none
        std::size_t accessor;  // the innermost <accessor> open, or none
        bool inScene;          // inside a <visual_scene>
    };
    struct Node
    {
        std::string id, name;
        std::size_t offset, parent;
        bool libraryLevel, inScene;
    };
    struct Instance
    {
        std::size_t from;
        std::string target;
        std::size_t offset;
    };
    struct Array
    {
        std::string id;
        std::uintmax_t count, values;
        std::size_t offset;
        bool strings;  // Name_array, IDREF_array, SIDREF_array: assimp keeps no numbers for them
    };
    struct Accessor
    {
        std::string source;
        std::uintmax_t count = 0, offset = 0, stride = 1, params = 0, paramValues = 0, stringParams = 0;
        std::size_t tagOffset = 0;
    };
    std::vector<Frame> open;
    std::vector<Node> nodes;
    std::vector<Instance> instances;
    std::vector<Array> arrays;
    std::vector<Accessor> accessors;
    std::size_t problemOffset = 0;
    std::string problem;
    const auto fail = [&](std::size_t offset, std::string why) {
        if (problem.empty())
            problemOffset = offset, problem = std::move(why);
    };
    const auto [xmlOffset, xmlProblem] = forEachXmlTag(data, [&](const XmlTag &tag) {
        if (!problem.empty())
            return;
        if (tag.closing)
        {
            if (!open.empty())
                open.pop_back();
            return;
        }
        if (open.size() >= kMaxColladaDepth)
            return fail(tag.offset,
                        "its elements nest deeper than " + std::to_string(kMaxColladaDepth) + " levels (the limit)");
        Frame frame = open.empty() ? Frame{tag.name, none, none, false} : open.back();
        frame.name = tag.name;
        const std::string_view parent = open.empty() ? std::string_view() : open.back().name;
        if (tag.name == "node" || tag.name == "visual_scene")
        {
            const bool scene = tag.name == "visual_scene";
            nodes.push_back({xmlAttribute(tag.attributes, "id").value_or(""),
                             xmlAttribute(tag.attributes, "name").value_or(""), tag.offset, frame.node,
                             scene || parent == "library_nodes", scene || frame.inScene});
            frame.node = nodes.size() - 1;
            frame.inScene = nodes.back().inScene;
        }
        else if (tag.name == "instance_node" && frame.node != none)
        {
            const std::string url = xmlAttribute(tag.attributes, "url").value_or("");
            if (!url.empty() && url[0] == '#')
                instances.push_back({frame.node, url.substr(1), tag.offset});
        }
        else if (tag.name.size() > 6 && tag.name.substr(tag.name.size() - 6) == "_array")
        {
            // The count is a whole number here: rejectBeforeImport checked it first.
            const std::uintmax_t count = leadingCount(xmlAttribute(tag.attributes, "count").value_or(""));
            std::uintmax_t values = 0;
            if (!tag.selfClosing)
            {
                const std::size_t end = std::min(data.size(), data.find('<', tag.contentStart));
                bool inValue = false;
                for (std::size_t i = tag.contentStart; i < end; ++i)
                {
                    const bool blank = std::isspace(static_cast<unsigned char>(data[i])) != 0;
                    values += !blank && !inValue;
                    inValue = !blank;
                }
            }
            const bool strings = tag.name == "Name_array" || tag.name == "IDREF_array" || tag.name == "SIDREF_array";
            arrays.push_back({xmlAttribute(tag.attributes, "id").value_or(""), count, values, tag.offset, strings});
        }
        else if (tag.name == "accessor")
        {
            Accessor accessor;
            accessor.tagOffset = tag.offset;
            accessor.source = xmlAttribute(tag.attributes, "source").value_or("");
            for (auto [key, value] : {std::pair<const char *, std::uintmax_t *>{"count", &accessor.count},
                                      {"offset", &accessor.offset},
                                      {"stride", &accessor.stride}})
                if (const std::optional<std::string> text = xmlAttribute(tag.attributes, key))
                {
                    if (!isWholeNumber(*text))
                        return fail(tag.offset, std::string("an accessor whose ") + key + " '" + text->substr(0, 20) +
                                                    "' is not a whole number");
                    *value = leadingCount(*text);
                }
            accessors.push_back(accessor);
            frame.accessor = accessors.size() - 1;
        }
        else if (tag.name == "param" && frame.accessor != none)
        {
            // assimp reads one value per parameter (sixteen for a float4x4) from each element.
            Accessor &accessor = accessors[frame.accessor];
            ++accessor.params;
            if (const std::optional<std::string> type = xmlAttribute(tag.attributes, "type"))
            {
                accessor.paramValues += *type == "float4x4" ? 16 : 1;
                const std::string kind = lowercase(*type);
                accessor.stringParams += kind == "name" || kind == "idref" || kind == "sidref" ? 1 : 0;
            }
        }
        if (!tag.selfClosing)
            open.push_back(frame);
    });
    if (!xmlProblem.empty())
        fail(xmlOffset, xmlProblem);
    if (!problem.empty())
        return {lineAt(data, problemOffset), problem};

    // Arrays and their accessors. assimp keeps the array last read of an id; the smallest is used.
    std::unordered_map<std::string_view, std::uintmax_t> arrayCounts;
    std::unordered_set<std::string_view> stringArrays;
    for (const Array &array : arrays)
    {
        if (array.strings)
            stringArrays.insert(array.id);
        if (array.values < array.count)
            return {lineAt(data, array.offset), "an array '" + array.id + "' holding " + std::to_string(array.values) +
                                                    " values, fewer than its count of " + std::to_string(array.count)};
        const auto [it, added] = arrayCounts.emplace(array.id, array.count);
        if (!added)
            it->second = std::min(it->second, array.count);
    }
    for (const Accessor &accessor : accessors)
    {
        const auto array = !accessor.source.empty() && accessor.source[0] == '#'
                               ? arrayCounts.find(std::string_view(accessor.source).substr(1))
                               : arrayCounts.end();
        if (array == arrayCounts.end() || accessor.count == 0)
            continue;  // assimp refuses an accessor of an unknown array when it uses one
        // Numbers read from an array of names index assimp's empty number vector (a crash).
        if (stringArrays.count(array->first) != 0 && (accessor.params == 0 || accessor.stringParams < accessor.params))
            return {lineAt(data, accessor.tagOffset),
                    "an accessor of '" + accessor.source + "' reading numbers from an array of names"};
        const std::uintmax_t elementValues = std::max({std::uintmax_t(1), accessor.params, accessor.paramValues});
        const std::uintmax_t read =
            std::max(saturatingAdd(accessor.offset, saturatingMul(accessor.count, accessor.stride)),
                     saturatingAdd(saturatingAdd(accessor.offset, saturatingMul(accessor.count - 1, accessor.stride)),
                                   elementValues));
        if (read > array->second)
            return {lineAt(data, accessor.tagOffset),
                    "an accessor of '" + accessor.source + "' reading " + std::to_string(accessor.count) +
                        " elements of stride " + std::to_string(accessor.stride) + " from offset " +
                        std::to_string(accessor.offset) + ", " + std::to_string(read) +
                        " values, past the array's count of " + std::to_string(array->second)};
    }

    // The node graph: each node's children and the nodes it instances.
    const auto tooManyNodes = [&](std::size_t offset) {
        return std::pair<int, std::string>{lineAt(data, offset),
                                           "its scene has more than " + std::to_string(kMaxColladaNodes) +
                                               " nodes with instanced nodes expanded (the limit)"};
    };
    if (nodes.size() > kMaxColladaNodes)
        return tooManyNodes(nodes[kMaxColladaNodes].offset);
    if (instances.empty())
        return {0, {}};  // nesting alone is bounded by the element depth
    std::unordered_map<std::string_view, std::vector<std::size_t>> libraryById, sceneByIdOrName;
    for (std::size_t n = 0; n < nodes.size(); ++n)
    {
        // assimp stores a library node without an id under "", finds scene nodes by name (a node
        // without one matches "", a visual scene without one is named "Scene"), so those count too.
        if (nodes[n].libraryLevel)
            libraryById[nodes[n].id].push_back(n);
        if (nodes[n].inScene)
        {
            sceneByIdOrName[nodes[n].id].push_back(n);
            if (nodes[n].name != nodes[n].id)
                sceneByIdOrName[nodes[n].name].push_back(n);
            if (nodes[n].name.empty() && nodes[n].parent == none && nodes[n].id != "Scene")
                sceneByIdOrName["Scene"].push_back(n);
        }
    }
    struct Edge
    {
        std::size_t to, offset;
    };
    std::vector<std::vector<Edge>> edges(nodes.size());
    for (std::size_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].parent != none)
            edges[nodes[n].parent].push_back({n, nodes[n].offset});
    for (const Instance &instance : instances)
    {
        const auto library = libraryById.find(instance.target);
        const auto scene = sceneByIdOrName.find(instance.target);
        const std::vector<std::size_t> *targets = library != libraryById.end()     ? &library->second
                                                  : scene != sceneByIdOrName.end() ? &scene->second
                                                                                   : nullptr;
        for (std::size_t k = 0; targets != nullptr && k < targets->size(); ++k)
            edges[instance.from].push_back({(*targets)[k], instance.offset});
    }
    // Depth-first without recursion (the graph may be a chain of millions): depth in levels.
    enum : char
    {
        unseen,
        onPath,
        done
    };
    std::vector<char> state(nodes.size(), unseen);
    std::vector<std::size_t> depth(nodes.size(), 1), expanded(nodes.size(), 1);
    std::vector<std::pair<std::size_t, std::size_t>> path;  // node, next edge
    for (std::size_t root = 0; root < nodes.size(); ++root)
    {
        if (state[root] != unseen)
            continue;
        path.push_back({root, 0});
        state[root] = onPath;
        while (!path.empty())
        {
            auto &[n, next] = path.back();
            if (next < edges[n].size())
            {
                const Edge edge = edges[n][next++];
                if (state[edge.to] == onPath)
                {
                    const Node &looped = nodes[edge.to];
                    const std::string label = !looped.id.empty() ? looped.id : looped.name;
                    return {lineAt(data, edge.offset),
                            "its node '" + label +
                                "' contains itself through <instance_node> references (a cycle), which assimp "
                                "would expand without end"};
                }
                if (state[edge.to] == unseen)
                {
                    state[edge.to] = onPath;
                    path.push_back({edge.to, 0});
                }
                continue;
            }
            for (const Edge &edge : edges[n])
            {
                depth[n] = std::max(depth[n], depth[edge.to] + 1);
                expanded[n] = std::min(expanded[n] + expanded[edge.to], kMaxColladaNodes + 1);
            }
            if (expanded[n] > kMaxColladaNodes)
                return tooManyNodes(nodes[n].offset);
            if (depth[n] > kMaxColladaDepth)
                return {lineAt(data, nodes[n].offset),
                        "its node hierarchy, with instanced nodes expanded, is deeper than " +
                            std::to_string(kMaxColladaDepth) + " levels (the limit)"};
            state[n] = done;
            path.pop_back();
        }
    }
    return {0, {}};
}

// A PLY header's elements (the header checked by plyHeaderProblem first) and where its data starts.
struct PlyProperty
{
    std::string_view name, type, countType;  // countType is empty for a single value
};
struct PlyElement
{
    std::string_view name;
    std::uintmax_t count = 0;
    int line = 0;
    std::vector<PlyProperty> properties;
};
struct PlyLayout
{
    std::string_view format;
    std::vector<PlyElement> elements;
    std::size_t headerEnd = 0;  // the byte ending the end_header line, as assimp reads it
};

PlyLayout plyLayout(std::string_view data)
{
    PlyLayout layout;
    int line = 1;
    for (std::size_t start = 0; start < data.size(); ++line)
    {
        const std::size_t end = std::min(data.size(), data.find('\n', start));
        const std::vector<std::string_view> words = leadingTokens(data.substr(start, end - start), end - start, false);
        if (!words.empty() && words[0] == "end_header")
        {
            layout.headerEnd = std::min(end, data.find('\r', start));
            break;
        }
        if (words.size() == 3 && words[0] == "format")
            layout.format = words[1];
        else if (words.size() == 3 && words[0] == "element")
            layout.elements.push_back({words[1], leadingCount(words[2]), line, {}});
        else if (!words.empty() && words[0] == "property" && !layout.elements.empty())
            layout.elements.back().properties.push_back(words.size() == 5 ? PlyProperty{words[4], words[3], words[2]}
                                                                          : PlyProperty{words[2], words[1], {}});
        start = end + 1;
    }
    return layout;
}

std::size_t plyTypeSize(std::string_view type)
{
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
        return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
        return 2;
    return type == "double" || type == "float64" ? 8 : 4;
}

bool plyTypeIsFloat(std::string_view type)
{
    return type == "float" || type == "double" || type == "float32" || type == "float64";
}

bool plyTypeIsSigned(std::string_view type)
{
    return type == "char" || type == "short" || type == "int" || type == "int8" || type == "int16" || type == "int32";
}

// Whether assimp's number readers consume the whole of `token` as a value of PLY type `type`:
// otherwise they stop inside it and read the next values from the wrong place.
bool isPlyValue(std::string_view token, std::string_view type)
{
    std::size_t i = 0;
    const auto digits = [&] {
        const std::size_t from = i;
        while (i < token.size() && token[i] >= '0' && token[i] <= '9')
            ++i;
        return i > from;
    };
    if (!plyTypeIsFloat(type))
    {
        if (plyTypeIsSigned(type) && !token.empty() && (token[0] == '-' || token[0] == '+'))
            ++i;
        return digits() && i == token.size();
    }
    if (!token.empty() && (token[0] == '-' || token[0] == '+'))
        ++i;
    const std::string word = lowercase(token.substr(i));
    if (word == "nan" || word == "inf" || word == "infinity")
        return true;
    const bool whole = digits();
    if (i < token.size() && (token[i] == '.' || token[i] == ','))
    {
        ++i;
        if (!digits() && (!whole || token[i - 1] == ','))
            return false;
    }
    else if (!whole)
        return false;
    if (i < token.size() && (token[i] == 'e' || token[i] == 'E'))
    {
        ++i;
        if (i < token.size() && (token[i] == '-' || token[i] == '+'))
            ++i;
        digits();
    }
    return i == token.size();
}

// Why the data of a PLY file (its header checked by plyHeaderProblem) is not what its header
// announces, as the line at fault (0 in binary data) and why; empty when it is. assimp 5.2's PLY
// reader sizes each list by the count it reads before reading the values, so a 200-byte file with
// a list count of 500,000,000 made it allocate 4 GB: list counts above kMaxFaceVertices are
// refused, as are lists cut short (`255 0 1 2`, read as a face of 252 more zeros), values assimp
// does not read whole, and data ending early. A vertex element without x, y and z (read as 0) is
// refused too. ASCII data is read as assimp reads it: one element per line, where a line ends at
// \r, \n, \f or a zero byte and the next starts after the following \n when a line end follows.
std::pair<int, std::string> plyDataProblem(std::string_view data)
{
    const PlyLayout layout = plyLayout(data);
    for (const PlyElement &element : layout.elements)
    {
        if (element.name == "vertex")
            for (const char *axis : {"x", "y", "z"})
                if (std::none_of(element.properties.begin(), element.properties.end(),
                                 [&](const PlyProperty &p) { return p.name == axis && p.countType.empty(); }))
                    return {element.line, std::string("its vertex element has no '") + axis + "' property"};
        for (const PlyProperty &property : element.properties)
            if (!property.countType.empty() && plyTypeIsFloat(property.countType))
                return {element.line, "its list property '" + std::string(property.name) + "' has a count of type " +
                                          std::string(property.countType) + ", not a whole-number type"};
    }
    const auto listTooLong = [](std::uintmax_t count) {
        return "a list of " + std::to_string(count) + " values, above the limit of " +
               std::to_string(kMaxFaceVertices) + " (the most vertices a face may have)";
    };
    const auto endsEarly = [](const PlyElement &element, std::uintmax_t read) {
        return "its data ends after " + std::to_string(read) + " of its " + std::to_string(element.count) + " " +
               std::string(element.name) + " elements";
    };
    if (layout.format == "ascii")
    {
        const auto isLineEnd = [&](std::size_t i) {
            return data[i] == '\r' || data[i] == '\n' || data[i] == '\f' || data[i] == '\0';
        };
        // The line after the one ending at byte `end`.
        const auto nextLine = [&](std::size_t end) {
            std::size_t start = std::min(end + 1, data.size());
            if (start < data.size() && isLineEnd(start))
            {
                // The next line starts after the following \n; with none, the data has ended.
                const std::size_t newline = data.find('\n', start);
                start = newline == std::string_view::npos ? data.size() : newline + 1;
            }
            return start;
        };
        std::size_t start = nextLine(layout.headerEnd);
        int line = lineAt(data, start);
        for (const PlyElement &element : layout.elements)
            for (std::uintmax_t i = 0; i < element.count; ++i)
            {
                if (start >= data.size())
                    return {line, endsEarly(element, i)};
                std::size_t end = start;
                while (end < data.size() && !isLineEnd(end))
                    ++end;
                const std::string_view text = data.substr(start, end - start);
                std::size_t at = 0;
                const auto nextValue = [&] {
                    at = std::min(text.size(), text.find_first_not_of(" \t", at));
                    const std::size_t from = at;
                    at = std::min(text.size(), text.find_first_of(" \t", at));
                    return text.substr(from, at - from);
                };
                for (const PlyProperty &property : element.properties)
                {
                    const bool list = !property.countType.empty();
                    const std::string_view first = nextValue();
                    const std::string what = "'" + std::string(property.name) + "' of " + std::string(element.name) +
                                             " element " + std::to_string(i);
                    if (first.empty())
                        return {line, "its line has no value for " + what};
                    if (!isPlyValue(first, list ? property.countType : property.type))
                        return {line, "its value '" + std::string(first.substr(0, 20)) + "' for " + what +
                                          " is not a number of type " +
                                          std::string(list ? property.countType : property.type)};
                    if (!list)
                        continue;
                    if (first[0] == '-' && first.find_first_not_of("-+0") != std::string_view::npos)
                        return {line, "its list " + what + " has a negative count"};
                    const std::uintmax_t count = leadingCount(first.substr(first[0] == '+' || first[0] == '-'));
                    if (count > kMaxFaceVertices)
                        return {line, "its list " + what + " is " + listTooLong(count)};
                    for (std::uintmax_t k = 0; k < count; ++k)
                    {
                        const std::string_view value = nextValue();
                        if (value.empty())
                            return {line, "its list " + what + " announces " + std::to_string(count) +
                                              " values but holds " + std::to_string(k)};
                        if (!isPlyValue(value, property.type))
                            return {line, "its value '" + std::string(value.substr(0, 20)) + "' in the list " + what +
                                              " is not a number of type " + std::string(property.type)};
                    }
                }
                const std::size_t next = nextLine(end);
                line +=
                    int(std::count(data.begin() + std::ptrdiff_t(start), data.begin() + std::ptrdiff_t(next), '\n'));
                start = next;
            }
        return {0, {}};
    }
    // Binary: assimp's data starts after the byte ending the end_header line, and after one more
    // byte when that one is a \n (the \n of "\r\n").
    const bool bigEndian = layout.format == "binary_big_endian";
    std::uintmax_t at = layout.headerEnd + 1;
    if (at < data.size() && data[at] == '\n')
        ++at;
    for (const PlyElement &element : layout.elements)
    {
        std::uintmax_t fixedSize = 0;
        bool lists = false;
        for (const PlyProperty &property : element.properties)
        {
            lists = lists || !property.countType.empty();
            fixedSize += plyTypeSize(property.type);
        }
        if (!lists)
        {
            const std::uintmax_t end = saturatingAdd(at, saturatingMul(element.count, fixedSize));
            if (end > data.size())
                return {0, endsEarly(element, (data.size() - std::min<std::uintmax_t>(at, data.size())) /
                                                  std::max<std::uintmax_t>(fixedSize, 1))};
            at = end;
            continue;
        }
        for (std::uintmax_t i = 0; i < element.count; ++i)
            for (const PlyProperty &property : element.properties)
            {
                if (property.countType.empty())
                {
                    at += plyTypeSize(property.type);
                    continue;
                }
                const std::size_t countSize = plyTypeSize(property.countType);
                if (at + countSize > data.size())
                    return {0, endsEarly(element, i)};
                std::uintmax_t count = 0;
                for (std::size_t b = 0; b < countSize; ++b)
                    count |= std::uintmax_t(static_cast<unsigned char>(data[at + b]))
                             << (8 * (bigEndian ? countSize - 1 - b : b));
                const bool negative = plyTypeIsSigned(property.countType) && (count >> (8 * countSize - 1)) != 0;
                if (negative)
                    return {0, "its list '" + std::string(property.name) + "' of " + std::string(element.name) +
                                   " element " + std::to_string(i) + " has a negative count"};
                if (count > kMaxFaceVertices)
                    return {0, "its list '" + std::string(property.name) + "' of " + std::string(element.name) +
                                   " element " + std::to_string(i) + " is " + listTooLong(count)};
                at += countSize + count * plyTypeSize(property.type);
                if (at > data.size())
                    return {0, endsEarly(element, i)};
            }
        if (at > data.size())
            return {0, endsEarly(element, element.count)};
    }
    return {0, {}};
}

// The first face of OFF data that assimp 5.2's OFF reader would read with a vertex index out of
// range (it clamps the index to the last vertex, silently) or without one where one is due (it
// reads 0), as its line and why; also a line of 4096 or more bytes, which the reader copies into a
// 4096-byte buffer with its terminating zero past the end. The data is read as the reader reads
// it: the header (comments skipped), one line per vertex, then face lines, a face announcing 0 or
// more than 9 vertices skipped without counting (as the reader skips it).
std::pair<int, std::string> offFaceProblem(std::string_view data)
{
    const std::size_t n = data.size();
    std::size_t i = 0;
    const auto at = [&](std::size_t k) { return k < n ? data[k] : '\0'; };
    const auto digit = [&](std::size_t k) { return at(k) >= '0' && at(k) <= '9'; };
    const auto lineEnd = [&](std::size_t k) {
        return at(k) == '\r' || at(k) == '\n' || at(k) == '\0' || at(k) == '\f';
    };
    const auto skipSpacesAndLineEnds = [&] {
        while (at(i) == ' ' || at(i) == '\t' || at(i) == '\r' || at(i) == '\n')
            ++i;
    };
    const auto nextToken = [&] {
        skipSpacesAndLineEnds();
        while (i <= n && (at(i) == '#' || at(i) == '\n' || at(i) == '\r'))
        {
            while (at(i) != '\r' && at(i) != '\n' && at(i) != '\0')
                ++i;
            skipSpacesAndLineEnds();
        }
    };
    // strtoul10: digits, wrapping as the reader's unsigned int does.
    const auto readNumber = [&](std::size_t &k, const auto &charAt) {
        std::uint32_t value = 0;
        for (; charAt(k) >= '0' && charAt(k) <= '9'; ++k)
            value = value * 10 + std::uint32_t(charAt(k) - '0');
        return value;
    };
    nextToken();
    if (i + 1 < n && at(i) == 'S' && at(i + 1) == 'T')
        i += 2;
    for (const char flag : {'C', 'N', '4'})
        if (i < n && at(i) == flag)
            ++i;
    const bool dimension = i < n && at(i) == 'n';
    i += dimension;
    if (i + 2 < n && at(i) == 'O' && at(i + 1) == 'F' && at(i + 2) == 'F')
        i += 3;
    nextToken();
    if (!digit(i))
        return {0, {}};  // the reader refuses the header
    if (dimension)
    {
        if (readNumber(i, at) > 3)
            return {0, {}};  // the reader refuses more than three dimensions
        nextToken();
    }
    nextToken();
    const std::uint32_t vertices = readNumber(i, at);
    nextToken();
    const std::uint32_t faces = readNumber(i, at);
    nextToken();
    readNumber(i, at);
    nextToken();
    // GetNextLine into a 4096-byte buffer; false at the end of the data.
    std::size_t lineStart = 0, lineLength = 0;
    const auto nextLine = [&] {
        if (at(i) == '\0')
            return false;
        lineStart = i;
        while (!lineEnd(i))
            ++i;
        lineLength = i - lineStart;
        while (lineEnd(i) && at(i) != '\0')
            ++i;
        return true;
    };
    const auto tooLong = [&] {
        return std::pair<int, std::string>{lineAt(data, lineStart),
                                           "its line of " + std::to_string(lineLength) +
                                               " bytes is longer than the 4095 the OFF reader holds"};
    };
    for (std::uint32_t v = 0; v < vertices && nextLine(); ++v)
        if (lineLength >= 4096)
            return tooLong();
    for (std::uint32_t f = 0; f < faces && nextLine();)
    {
        if (lineLength >= 4096)
            return tooLong();
        const auto charAt = [&](std::size_t k) { return k < lineLength ? data[lineStart + k] : '\0'; };
        std::size_t k = 0;
        const auto skipSpaces = [&] {
            while (charAt(k) == ' ' || charAt(k) == '\t')
                ++k;
        };
        skipSpaces();
        const std::uint32_t count = readNumber(k, charAt);
        if (count == 0 || count > 9)
            continue;
        for (std::uint32_t m = 0; m < count; ++m)
        {
            skipSpaces();
            if (charAt(k) < '0' || charAt(k) > '9')
                return {lineAt(data, lineStart),
                        "its face of " + std::to_string(count) + " vertices has " +
                            (charAt(k) == '\0' ? std::string("only ") + std::to_string(m) + " vertex indices"
                                               : "'" + std::string(1, charAt(k)) + "' where vertex index " +
                                                     std::to_string(m + 1) + " is due")};
            const std::uint32_t index = readNumber(k, charAt);
            if (index >= vertices)
                return {lineAt(data, lineStart), "its face has the vertex index " + std::to_string(index) +
                                                     ", out of range for its " + std::to_string(vertices) +
                                                     " vertices (numbered from 0)"};
        }
        ++f;
    }
    return {0, {}};
}

// Whether assimp may give data of format `kind` (lowercase) to its OBJ reader: an "obj" extension or
// hint, or one no reader claims (assimp then picks a reader by content).
bool objReaderMayRead(const std::string &kind, const Assimp::Importer &importer)
{
    return kind == "obj" || !importer.IsExtensionSupported(kind.c_str());
}

// The bytes assimp's reader is given: without a UTF-8 byte order mark where the OBJ reader may
// read them (it takes the mark for part of the first statement: a first vertex was lost and every
// face index after it shifted), so that the checks before import see what the reader will.
std::string_view withoutObjByteOrderMark(std::string_view data, const std::string &format,
                                         const Assimp::Importer &importer)
{
    if (startsWithByteOrderMark(data) && objReaderMayRead(lowercase(format), importer))
        data.remove_prefix(3);
    return data;
}

// Refuses, before assimp sees them, data that assimp 5.2's readers cannot survive (each found by
// fuzzing; `format` is the file's extension or the buffer's hint):
// - PLY data without an "end_header" line, or with a header that is not printable text (see
//   plyHeaderProblem): the PLY reader then never returns. Then data that is not what the header
//   announces, or lists longer than kMaxFaceVertices (see plyDataProblem).
// - COLLADA data with array elements that have no count, or a count beyond the data (below), and
//   nesting, instancing cycles or accessors assimp cannot survive (see colladaStructureProblem).
// - OFF data whose header announces more vertices or faces than its bytes can hold: the OFF reader
//   allocates every announced face before reading one, and billions of them exhaust memory
//   (tests/fuzz_corpus/mesh/regression_off_huge_face_count.off). Every vertex and face takes more
//   than one byte, so a count above the data's size is never valid. Then face indices out of range
//   or missing, which the reader replaces silently (see offFaceProblem).
// - OBJ data with a line statement the OBJ reader could read with fewer than two vertices (see
//   objLineStatementProblem): the reader then writes past the end of its vertex array. Checked
//   whenever the OBJ reader may get the data: an "obj" extension or hint, or one no reader claims
//   (assimp then picks a reader by content).
void rejectBeforeImport(std::string_view data, const std::string &format, const std::string &name,
                        const Assimp::Importer &importer)
{
    const std::string kind = lowercase(format);
    // Zip archives (.zae, .3mf, .pk3, ...): assimp unpacks them and reads what is inside, which none
    // of the checks below would see (a .zae holding a COLLADA instance cycle overflowed the stack).
    if (kind == "zae" || data.substr(0, 4) == std::string_view("PK\x03\x04", 4))
        throw InputError(name, 0, "a zip archive (.zae and the like) is not read: unpack the mesh file it holds");
    if (objReaderMayRead(kind, importer))
    {
        if (const auto [line, problem] = objLineStatementProblem(data); !problem.empty())
            throw InputError(name, line, "malformed OBJ file: " + problem);
        if (const auto [line, problem] = objStatementProblem(data); !problem.empty())
            throw InputError(name, line, "malformed OBJ file: " + problem);
    }
    const std::vector<std::string_view> tokens = leadingTokens(data, 5);
    const std::string first = tokens.empty() ? std::string() : lowercase(tokens.front());

    const bool ply = kind == "ply" || first.rfind("ply", 0) == 0;
    if (ply)
    {
        if (const std::string problem = plyHeaderProblem(data); !problem.empty())
            throw InputError(name, 0, "malformed PLY file: " + problem);
        if (const auto [line, problem] = plyDataProblem(data); !problem.empty())
            throw InputError(name, line, "malformed PLY file: " + problem);
    }

    // COLLADA: assimp 5.2's reader dereferences a null pointer on an array element without a
    // count (tests/fuzz_corpus/mesh/regression_collada_array_without_count.dae), and a count is
    // allocated before the values are read, so one above what the data can hold is refused too.
    if (kind == "dae" || kind == "xml" || data.find("<COLLADA") != std::string_view::npos)
    {
        std::string problem;
        const bool closed = forEachColladaArray(data, [&](std::string_view attributes) {
            if (!problem.empty())
                return;
            const std::optional<std::string_view> count = attributeValue(attributes, "count");
            if (!count || count->empty() || count->find_first_not_of("0123456789") != std::string_view::npos)
                problem = "an array element without a whole-number count";
            else if (leadingCount(*count) > data.size())
                problem = "an array element whose count (" + std::string(*count) + ") exceeds what its " +
                          std::to_string(data.size()) + " bytes can hold";
        });
        if (!closed)
            problem = "an array element that is never closed";
        // Index lists: assimp reads a non-digit as a huge index and allocates for it (gigabytes for
        // one '$', found by fuzzing: regression_collada_index_not_a_number.dae). Indices are whole
        // numbers, each below the data's size (every vertex takes more than one byte).
        for (const char *tag : {"p", "v", "vcount", "h"})
            forEachElementText(data, tag, [&](std::string_view text) {
                if (!problem.empty())
                    return;
                const std::size_t bad = text.find_first_not_of("0123456789 \t\r\n");
                if (bad != std::string_view::npos)
                    problem = std::string("an index list <") + tag + "> holding '" + std::string(1, text[bad]) +
                              "', which is not a whole number";
                for (const std::string_view index : leadingTokens(text, text.size()))
                    if (problem.empty() && leadingCount(index) > data.size())
                        problem = std::string("an index list <") + tag + "> with the index " + std::string(index) +
                                  ", beyond what its " + std::to_string(data.size()) + " bytes can hold";
            });
        if (!problem.empty())
            throw InputError(name, 0, "malformed COLLADA file: " + problem);
        // The structure only where the COLLADA reader may get the data (as for OBJ above): other
        // readers' data is not XML.
        if (kind == "dae" || kind == "xml" || !importer.IsExtensionSupported(kind.c_str()))
            if (const auto [line, structure] = colladaStructureProblem(data); !structure.empty())
                throw InputError(name, line, "malformed COLLADA file: " + structure);
    }

    // The OFF header is "[ST][C][N][4][n]OFF", an optional dimension after the 'n' form, then the
    // vertex, face and edge counts; the keyword itself may be left out.
    const bool keyword = first.find("off") != std::string::npos;
    if (kind != "off" && !keyword)
        return;
    // The dimension prefix is a lower-case 'n' right before "OFF" ("NOFF" is the normals flag):
    // then the dimension comes first, and is checked with the counts (it is a small number). The
    // reader takes whatever follows the keyword as the next number, even with no blank between.
    std::vector<std::string_view> counts;
    bool dimension = false;
    if (keyword)
    {
        const std::string_view head = tokens.front();
        dimension = head.find("nOFF") != std::string_view::npos;
        const std::size_t end = first.find("off") + 3;
        if (end < head.size())
            counts.push_back(head.substr(end));
        counts.insert(counts.end(), tokens.begin() + 1, tokens.end());
    }
    else
        counts = tokens;
    const char *names[] = {"dimensions", "vertices", "faces"};
    for (std::size_t k = 0; k < std::min(counts.size(), std::size_t(dimension ? 3 : 2)); ++k)
        if (leadingCount(counts[k]) > data.size())
            throw InputError(name, 0,
                             "malformed OFF file: its header announces " + std::string(counts[k]) + " " +
                                 names[k + (dimension ? 0 : 1)] + ", more than its " + std::to_string(data.size()) +
                                 " bytes can hold");
    if (kind == "off" || !importer.IsExtensionSupported(kind.c_str()))  // where the OFF reader may get it
        if (const auto [line, problem] = offFaceProblem(data); !problem.empty())
            throw InputError(name, line, "malformed OFF file: " + problem);
}

std::string extensionOf(const std::string &path)
{
    const auto dot = path.find_last_of('.');
    const auto slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return {};
    return path.substr(dot + 1);
}

// Imports `source` with post-processing `flags`; throws InputError naming the source when assimp
// fails, when it holds no geometry, or when its instanced triangles exceed the limit (counted
// before any copy).
Imported import(Assimp::Importer &importer, const Source &source, unsigned flags, const MeshLimits &limits)
{
    const aiScene *read = source.inMemory
                              ? importer.ReadFileFromMemory(source.data.data(), source.data.size(),
                                                            aiProcess_ValidateDataStructure, source.formatHint->c_str())
                              : importer.ReadFile(source.name, aiProcess_ValidateDataStructure);
    const aiScene *scene = postProcess(importer, read, flags, source.name, limits);
    const std::string &path = source.name;
    if (scene == nullptr)
        throw InputError(path, 0, std::string("cannot read mesh: ") + importer.GetErrorString());
    if (!scene->HasMeshes() || scene->mRootNode == nullptr)
        throw InputError(path, 0, "mesh file holds no geometry");

    std::size_t triangles = 0;
    visitNodes(scene, scene->mRootNode, aiMatrix4x4(),
               [&](const aiMesh *m, const aiMatrix4x4 &) { triangles += m->mNumFaces; });
    if (triangles > limits.maxTriangles)
        throw InputError(path, 0,
                         "the mesh has " + std::to_string(triangles) + " faces, above the limit of " +
                             std::to_string(limits.maxTriangles) +
                             " triangles per mesh (about 0.7 KB of memory each; the command line's "
                             "--max-triangles raises it)");

    Imported out;
    out.corners.reserve(3 * triangles);
    visitNodes(scene, scene->mRootNode, aiMatrix4x4(), [&](const aiMesh *m, const aiMatrix4x4 &transform) {
        for (unsigned v = 0; v < m->mNumVertices; ++v)
        {
            const aiVector3D p = transform * m->mVertices[v];
            out.vertexSum += p;
            out.vertexSumInDouble += Vec3(p.x, p.y, p.z);
            ++out.vertexCount;
        }
        for (unsigned f = 0; f < m->mNumFaces; ++f)
        {
            const aiFace &face = m->mFaces[f];
            if (face.mNumIndices != 3)
            {
                ++out.skippedNonTriangles;
                continue;
            }
            for (int k = 0; k < 3; ++k)
                out.corners.push_back(transform * m->mVertices[face.mIndices[k]]);
        }
    });
    return out;
}

// Diagonal of the corners' bounding box (in double, so tiny meshes are measured exactly).
double extentOf(const std::vector<aiVector3D> &corners)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const aiVector3D &c : corners)
    {
        const Vec3 p(c.x, c.y, c.z);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    return corners.empty() ? 0.0 : (hi - lo).norm();
}

// Refuses mesh data of `bytes` bytes above the limit: assimp holds the whole of it and more.
void rejectAboveByteLimit(std::uintmax_t bytes, const char *what, const std::string &name, const MeshLimits &limits)
{
    const std::uintmax_t maxBytes = std::uintmax_t(limits.maxTriangles) * limits.bytesPerTriangle;
    if (bytes > maxBytes)
        throw InputError(name, 0,
                         std::string("the mesh ") + what + " has " + std::to_string(bytes) +
                             " bytes, above the limit of " + std::to_string(maxBytes) + " (" +
                             std::to_string(limits.bytesPerTriangle) + " bytes for each of the " +
                             std::to_string(limits.maxTriangles) +
                             " triangles allowed per mesh; the command line's --max-triangles raises it)");
}

// The mesh of `source`, placed for `role`.
LoadedMesh loadFrom(Assimp::Importer &importer, const Source &source, MeshRole role, const MeshLimits &limits)
{
    const std::string &path = source.name;
    const unsigned joined = aiProcess_GenNormals | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                            aiProcess_SortByPType | aiProcess_OptimizeGraph;
    Imported imported = import(importer, source, joined, limits);
    if (!imported.corners.empty() && extentOf(imported.corners) < kTinyMeshExtent)
        imported = import(importer, source, joined & ~unsigned(aiProcess_JoinIdenticalVertices), limits);

    LoadedMesh out;
    out.skippedNonTriangles = imported.skippedNonTriangles;
    const std::vector<aiVector3D> &corners = imported.corners;
    const aiVector3D vertexSum = imported.vertexSum;
    const std::size_t vertexCount = imported.vertexCount;
    out.sourceTriangles = corners.size() / 3;
    if (corners.empty())
        throw InputError(path, 0,
                         "mesh file holds no triangle (" + std::to_string(out.skippedNonTriangles) +
                             " point or line primitives only)");

    for (const aiVector3D &c : corners)
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
            throw InputError(path, 0, "mesh has a non-finite vertex coordinate");
    aiVector3D shift(0.0f, 0.0f, 0.0f);
    if (role != MeshRole::Environment)
    {
        shift = vertexSum / float(vertexCount);
        // A float sum of vertices near the float range's end (3.4e38) overflows: OMPL.app's robot
        // would be at infinity there, so no compatibility is lost by taking the mean in double.
        if (!std::isfinite(shift.x) || !std::isfinite(shift.y) || !std::isfinite(shift.z))
        {
            const Vec3 mean = imported.vertexSumInDouble / double(vertexCount);
            if (!mean.allFinite())  // a vertex outside the triangles is not finite
                throw InputError(path, 0, "mesh has a non-finite vertex coordinate");
            shift = aiVector3D(float(mean.x()), float(mean.y()), float(mean.z()));
        }
        if (role == MeshRole::RobotPlanar)
            shift.z = 0.0f;
    }
    out.centeringShift = Vec3(shift.x, shift.y, shift.z);

    TriangleMesh mesh;
    mesh.vertices.reserve(corners.size());
    for (const aiVector3D &c : corners)
    {
        const aiVector3D p = c - shift;  // subtracted in float, exactly as OMPL.app does
        mesh.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (std::uint32_t t = 0; t < out.sourceTriangles; ++t)
        mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    for (const Vec3 &v : mesh.vertices)
        if (!v.allFinite())
            throw InputError(path, 0,
                             "the robot's vertex coordinates, centred on their mean, exceed single precision "
                             "(about 3.4e38)");
    out.droppedDegenerate = weldAndDropDegenerate(mesh);
    if (mesh.empty())
        throw InputError(path, 0, "every triangle of the mesh is degenerate (zero area)");
    out.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    return out;
}
}  // namespace

MeshImporter::MeshImporter() : importer_(std::make_unique<Assimp::Importer>()) {}

MeshImporter::~MeshImporter() = default;

LoadedMesh loadMesh(MeshImporter &importer, const std::string &path, MeshRole role, const MeshLimits &limits)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, 0, "is a folder, not a mesh file");
    // Refused before assimp reads it: assimp holds the whole file and more in memory.
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec)
        rejectAboveByteLimit(bytes, "file", path, limits);
    // readInputFile refuses a pipe (opening one waits for a writer), a device or a socket before
    // reading, and reads at most one byte past the limit.
    const std::uintmax_t maxBytes = std::uintmax_t(limits.maxTriangles) * limits.bytesPerTriangle;
    const std::string content = readInputFile(path, "mesh file", maxBytes);
    const std::string extension = extensionOf(path);
    const std::string_view data = withoutObjByteOrderMark(content, extension, *importer.importer_);
    rejectBeforeImport(data, extension, path, *importer.importer_);
    // A file whose byte order mark was left out is read from these bytes (an OBJ's .mtl library is
    // then not read: it holds no geometry).
    if (data.size() != content.size())
        return loadFrom(*importer.importer_, Source{path, true, data, &extension}, role, limits);
    // assimp then reads the file again by path, not these bytes: a mesh's own references (an OBJ's
    // .mtl library, a COLLADA file's external parts) resolve only beside the file.
    return loadFrom(*importer.importer_, Source{path, false, {}, nullptr}, role, limits);
}

LoadedMesh loadMeshFromMemory(MeshImporter &importer, std::string_view data, const std::string &formatHint,
                              MeshRole role, const std::string &sourceName, const MeshLimits &limits)
{
    // assimp refuses an empty buffer without saying why.
    if (data.empty())
        throw InputError(sourceName, 0, "mesh data is empty");
    rejectAboveByteLimit(data.size(), "data", sourceName, limits);
    data = withoutObjByteOrderMark(data, formatHint, *importer.importer_);
    rejectBeforeImport(data, formatHint, sourceName, *importer.importer_);
    return loadFrom(*importer.importer_, Source{sourceName, true, data, &formatHint}, role, limits);
}

LoadedMesh loadMesh(const std::string &path, MeshRole role, const MeshLimits &limits)
{
    MeshImporter importer;
    return loadMesh(importer, path, role, limits);
}

LoadedMesh loadMeshFromMemory(std::string_view data, const std::string &formatHint, MeshRole role,
                              const std::string &sourceName, const MeshLimits &limits)
{
    MeshImporter importer;
    return loadMeshFromMemory(importer, data, formatHint, role, sourceName, limits);
}
}  // namespace hcd
