// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/path_file.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

namespace hcd
{
namespace
{
std::string readText(const std::string &path) { return readInputFile(path, "pose file", kMaxPoseFileBytes); }

// A word of the file as a message quotes it: control bytes escaped, and no more than 60 bytes.
std::string quotedWord(const std::string &word)
{
    constexpr std::size_t kShown = 60;
    return "'" + printable(word.substr(0, kShown)) + (word.size() > kShown ? "...'" : "'");
}

// Reads every non-blank, non-comment line as at least `columns` finite numbers.
std::vector<PoseRecord> parseRows(std::string_view text, const std::string &path, std::size_t columns, const char *what)
{
    std::istringstream in{std::string(text)};
    std::vector<PoseRecord> rows;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line))
    {
        ++lineNo;
        if (lineNo == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
            line.erase(0, 3);  // a UTF-8 byte-order mark, as some editors write (the .cfg reader skips it too)
        const auto hash = line.find('#');
        if (hash != std::string::npos)
            line.erase(hash);
        std::istringstream words(line);
        std::string word;
        PoseRecord row;
        row.line = lineNo;
        while (row.values.size() < columns && words >> word)
        {
            // strtod, not stod: stod refuses subnormal numbers (it throws on ERANGE), yet writePoses
            // writes them and a path must read back. Overflow gives infinity, refused below.
            char *end = nullptr;
            const double v = std::strtod(word.c_str(), &end);
            if (end != word.c_str() + word.size())
                throw InputError(path, lineNo, quotedWord(word) + " is not a number");
            if (!std::isfinite(v))
                throw InputError(path, lineNo, quotedWord(word) + " is not a finite number");
            if (std::fabs(v) > kLargestInputMagnitude)
                throw InputError(path, lineNo, quotedWord(word) + " is beyond magnitude 1e100");
            row.values.push_back(v);
        }
        if (row.values.empty())
            continue;
        if (row.values.size() < columns)
            throw InputError(path, lineNo,
                             std::string(what) + " needs " + std::to_string(columns) + " numbers, found " +
                                 std::to_string(row.values.size()));
        rows.push_back(std::move(row));
    }
    return rows;
}

// Checks and normalises the quaternion of the pose row starting at values[first].
void normaliseQuaternion(PoseRecord &row, std::size_t first, const std::string &path)
{
    const QuaternionCheck check = normaliseRowQuaternion(row.values.data() + first);
    if (check.verdict != QuaternionCheck::Verdict::Unit)
        throw InputError(path, row.line, quaternionProblem(check));
}
}  // namespace

std::vector<PoseRecord> readPoses(const std::string &path, bool planar, std::size_t robots)
{
    return parsePoses(readText(path), path, planar, robots);
}

namespace
{
std::string poseWhat(bool planar, std::size_t robots, const char *single, const char *several)
{
    return robots == 1 ? std::string(single) : std::to_string(robots) + " " + several;
}
}  // namespace

std::vector<PoseRecord> parsePoses(std::string_view text, const std::string &sourceName, bool planar,
                                   std::size_t robots)
{
    robots = std::max<std::size_t>(robots, 1);
    const std::size_t n = poseColumns(planar);
    const std::string what =
        planar
            ? poseWhat(planar, robots, "a planar pose (x y theta)", "planar poses (x y theta each, one per robot)")
            : poseWhat(planar, robots, "a pose (x y z qx qy qz qw)", "poses (x y z qx qy qz qw each, one per robot)");
    std::vector<PoseRecord> rows = parseRows(text, sourceName, robots * n, what.c_str());
    if (!planar)
        for (PoseRecord &row : rows)
            for (std::size_t r = 0; r < robots; ++r)
                normaliseQuaternion(row, r * n, sourceName);
    return rows;
}

std::vector<std::pair<PoseRecord, PoseRecord>> readMotions(const std::string &path, bool planar, std::size_t robots)
{
    return parseMotions(readText(path), path, planar, robots);
}

std::vector<std::pair<PoseRecord, PoseRecord>> parseMotions(std::string_view text, const std::string &sourceName,
                                                            bool planar, std::size_t robots)
{
    robots = std::max<std::size_t>(robots, 1);
    const std::size_t n = poseColumns(planar) * robots;
    const std::string what = robots == 1 ? std::string("a motion (two poses)")
                                         : "a motion (two states of " + std::to_string(robots) + " poses each)";
    std::vector<std::pair<PoseRecord, PoseRecord>> motions;
    for (PoseRecord &row : parseRows(text, sourceName, 2 * n, what.c_str()))
    {
        if (!planar)
            for (std::size_t r = 0; r < 2 * robots; ++r)
                normaliseQuaternion(row, r * poseColumns(planar), sourceName);
        PoseRecord a{{row.values.begin(), row.values.begin() + long(n)}, row.line};
        PoseRecord b{{row.values.begin() + long(n), row.values.begin() + long(2 * n)}, row.line};
        motions.emplace_back(std::move(a), std::move(b));
    }
    return motions;
}

namespace
{
/// Whether every non-blank line of `text` (comments removed) holds exactly `count` words.
bool everyLineHolds(std::string_view text, std::size_t count)
{
    std::istringstream in{std::string(text)};
    std::string line;
    bool any = false;
    while (std::getline(in, line))
    {
        line.erase(std::min(line.size(), line.find('#')));
        std::istringstream words(line);
        std::size_t n = 0;
        for (std::string word; words >> word;)
            ++n;
        if (n == 0)
            continue;
        if (n != count)
            return false;
        any = true;
    }
    return any;
}
}  // namespace

std::vector<std::pair<PoseRecord, PoseRecord>> readPathMotions(const std::string &path, bool planar, std::size_t robots)
{
    const std::string text = readText(path);
    std::vector<PoseRecord> states = parsePoses(text, path, planar, robots);
    // Columns after a state are ignored, so a motions file would read as the first state of each
    // line, silently: a file whose every line holds two states' worth of numbers is refused.
    const std::size_t stateColumns = poseColumns(planar) * std::max<std::size_t>(robots, 1);
    if (!states.empty() && everyLineHolds(text, 2 * stateColumns))
        throw InputError(path, states.front().line,
                         "every line holds two states (" + std::to_string(2 * stateColumns) +
                             " numbers), as a motions file does: a path holds one state per line "
                             "(check-motion --motions reads start-end pairs)");
    if (states.size() < 2)
        throw InputError(
            path, 0, "a path needs at least two states, one per line (found " + std::to_string(states.size()) + ")");
    std::vector<std::pair<PoseRecord, PoseRecord>> motions;
    motions.reserve(states.size() - 1);
    for (std::size_t i = 0; i + 1 < states.size(); ++i)
        motions.emplace_back(states[i], states[i + 1]);
    return motions;
}

void writePoses(std::ostream &out, const std::vector<std::vector<double>> &poses)
{
    const auto old = out.precision(std::numeric_limits<double>::max_digits10);
    for (const auto &p : poses)
    {
        for (std::size_t i = 0; i < p.size(); ++i)
            out << (i ? " " : "") << p[i];
        out << '\n';
    }
    out.precision(old);
}
}  // namespace hcd
