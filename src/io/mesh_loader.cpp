// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/mesh_loader.h"

#include "hybridcd/io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>

namespace hcd
{
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
// that follows is OMPL.app's, as ReadFile would have applied it.
const aiScene *postProcess(Assimp::Importer &importer, const aiScene *scene, unsigned flags, const std::string &name)
{
    if (scene == nullptr)
        return nullptr;
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
        if (close == std::string_view::npos || data[close - 1] == '/')
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

// Refuses, before assimp sees them, data that assimp 5.2's readers cannot survive (each found by
// fuzzing; `format` is the file's extension or the buffer's hint):
// - PLY data without an "end_header" line, or with a header that is not printable text (see
//   plyHeaderProblem): the PLY reader then never returns.
// - COLLADA data with array elements that have no count, or a count beyond the data (below).
// - OFF data whose header announces more vertices or faces than its bytes can hold: the OFF reader
//   allocates every announced face before reading one, and billions of them exhaust memory
//   (tests/fuzz_corpus/mesh/regression_off_huge_face_count.off). Every vertex and face takes more
//   than one byte, so a count above the data's size is never valid.
// - OBJ data with a line statement the OBJ reader could read with fewer than two vertices (see
//   objLineStatementProblem): the reader then writes past the end of its vertex array. Checked
//   whenever the OBJ reader may get the data: an "obj" extension or hint, or one no reader claims
//   (assimp then picks a reader by content).
void rejectBeforeImport(std::string_view data, const std::string &format, const std::string &name,
                        const Assimp::Importer &importer)
{
    const std::string kind = lowercase(format);
    if (kind == "obj" || !importer.IsExtensionSupported(kind.c_str()))
        if (const auto [line, problem] = objLineStatementProblem(data); !problem.empty())
            throw InputError(name, line, "malformed OBJ file: " + problem);
    const std::vector<std::string_view> tokens = leadingTokens(data, 5);
    const std::string first = tokens.empty() ? std::string() : lowercase(tokens.front());

    const bool ply = kind == "ply" || first.rfind("ply", 0) == 0;
    if (ply)
        if (const std::string problem = plyHeaderProblem(data); !problem.empty())
            throw InputError(name, 0, "malformed PLY file: " + problem);

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
    const aiScene *scene = postProcess(importer, read, flags, source.name);
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
            out.vertexSum += transform * m->mVertices[v];
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

    aiVector3D shift(0.0f, 0.0f, 0.0f);
    if (role != MeshRole::Environment)
    {
        shift = vertexSum / float(vertexCount);
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
            throw InputError(path, 0, "mesh has a non-finite vertex coordinate");
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
    if (!std::ifstream(path).good())
        throw InputError(path, 0, "cannot open mesh file (missing or unreadable)");
    // Refused before assimp reads it: assimp holds the whole file and more in memory.
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec)
        rejectAboveByteLimit(bytes, "file", path, limits);
    // Read up to one byte past the limit, so that a device or pipe without a size cannot run on.
    const std::uintmax_t maxBytes = std::uintmax_t(limits.maxTriangles) * limits.bytesPerTriangle;
    std::ifstream in(path, std::ios::binary);
    std::string content;
    char block[1 << 16];
    while (in && content.size() <= maxBytes)
    {
        in.read(block, sizeof block);
        content.append(block, std::size_t(in.gcount()));
    }
    rejectAboveByteLimit(content.size(), "file", path, limits);
    rejectBeforeImport(content, extensionOf(path), path, *importer.importer_);
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
