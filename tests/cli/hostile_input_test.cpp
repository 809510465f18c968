// SPDX-License-Identifier: BSD-3-Clause
// Runs every case of the hostile-input corpus (tests/hostile/cases.txt) through the command line:
// the exit status, a message naming the file and line or the option, and no output written half-way.
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
struct Case
{
    std::string name;
    std::vector<std::string> setup;
    int status = 0;
    std::string expected;
    std::string arguments;
    int line = 0;
};

std::string trim(const std::string &s)
{
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos)
        return {};
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

std::vector<std::string> split(const std::string &text, char separator)
{
    std::vector<std::string> parts;
    std::stringstream s(text);
    std::string part;
    while (std::getline(s, part, separator))
        parts.push_back(trim(part));
    return parts;
}

std::string replaceAll(std::string text, const std::string &from, const std::string &to)
{
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

std::vector<Case> readCases(const std::string &path)
{
    std::ifstream in(path);
    std::vector<Case> cases;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line))
    {
        ++lineNo;
        if (trim(line).empty() || trim(line)[0] == '#')
            continue;
        const std::vector<std::string> f = split(line, '|');
        if (f.size() != 5)
        {
            ADD_FAILURE() << path << ":" << lineNo << ": expected 5 fields separated by '|'";
            continue;
        }
        Case c;
        c.name = f[0];
        if (f[1] != "-")
            c.setup = split(f[1], ',');
        c.status = std::stoi(f[2]);
        c.expected = replaceAll(f[3], "\\n", "\n");
        c.arguments = f[4];
        c.line = lineNo;
        cases.push_back(c);
    }
    return cases;
}

// What a file looked like: its size, and its content when small (the sparse 500 MB mesh is
// compared by size and modification time only).
struct FileState
{
    std::uintmax_t size;
    fs::file_time_type modified;
    std::string content;
    bool operator==(const FileState &o) const
    {
        return size == o.size && modified == o.modified && content == o.content;
    }
};

std::map<std::string, FileState> snapshot(const fs::path &root)
{
    std::map<std::string, FileState> files;
    for (const auto &entry : fs::recursive_directory_iterator(root))
    {
        std::error_code ec;  // a symbolic link to itself has no status
        if (!entry.is_regular_file(ec))
            continue;
        FileState state{entry.file_size(), entry.last_write_time(), {}};
        if (state.size < (1u << 20))
        {
            std::ifstream in(entry.path(), std::ios::binary);
            state.content.assign(std::istreambuf_iterator<char>(in), {});
        }
        files[fs::relative(entry.path(), root).string()] = state;
    }
    return files;
}

// A binary STL whose header claims `triangles` triangles, at its full size but sparse on disk.
void writeSparseStl(const fs::path &path, std::uint32_t triangles)
{
    {
        std::ofstream out(path, std::ios::binary);
        const std::string header(80, ' ');
        out.write(header.data(), 80);
        out.write(reinterpret_cast<const char *>(&triangles), 4);  // little-endian on the platforms we build for
    }
    fs::resize_file(path, 84 + 50ull * triangles);
}

// Applies one SETUP step inside `tmp`; returns the file the run may replace, if any.
std::string applySetup(const std::string &step, const fs::path &tmp)
{
    const std::vector<std::string> p = split(step, ':');
    const fs::path target = tmp / p.at(1);
    if (p[0] == "existing" || p[0] == "replaceable")
    {
        std::ofstream(target) << "# written before the run; it must never be left half-written\n0 0 0\n";
        return p[0] == "replaceable" ? p[1] : std::string();
    }
    if (p[0] == "folder")
        fs::create_directories(target);
    else if (p[0] == "binary")
    {
        // A PNG signature and header: NUL bytes and control characters, as any binary file has.
        const unsigned char bytes[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0,    0,    0,
                                       13,   'I', 'H', 'D', 'R',  0,    0,    1,    0,    0,    0,
                                       1,    0,   8,   6,   0,    0,    0,    0x5c, 0x72, 0xa8, 0x66};
        std::ofstream(target, std::ios::binary).write(reinterpret_cast<const char *>(bytes), sizeof bytes);
    }
    else if (p[0] == "sparse-stl")
        writeSparseStl(target, std::uint32_t(std::stoul(p.at(2))));
    else if (p[0] == "sparse")
    {
        std::ofstream(target) << "0 0 0 0 0 0 1\n";
        fs::resize_file(target, std::stoull(p.at(2)));
    }
    else if (p[0] == "fifo")
        EXPECT_EQ(::mkfifo(target.c_str(), 0600), 0) << target;
    else if (p[0] == "loop")
        fs::create_symlink(target, target);
    else
        ADD_FAILURE() << "unknown setup step '" << step << "'";
    return {};
}

// An error message must say where: "FILE:LINE:", "FILE:" (no line applies), or an option, with
// FILE ending in an extension or following a '/'.
bool namesFileOrOption(const std::string &fragment)
{
    static const std::regex where(R"((\.[A-Za-z0-9]+|/[^ /:]+)(:[0-9]+)?:|--[a-z])");
    return std::regex_search(fragment, where);
}
}  // namespace

TEST(HostileInput, EveryCorpusCaseThroughTheCommandLine)
{
    const std::string corpus = hcd::test::sourcePath("tests/hostile");
    const std::vector<Case> cases = readCases(corpus + "/cases.txt");
    ASSERT_GE(cases.size(), 40u);
    const std::string omplapp = hcd::test::omplappResources();
    const fs::path base = fs::temp_directory_path() / ("hybridcd-hostile-" + std::to_string(::getpid()));
    int skipped = 0;
    for (const Case &c : cases)
    {
        SCOPED_TRACE("tests/hostile/cases.txt:" + std::to_string(c.line) + ": " + c.name);
        if (c.arguments.find("{omplapp}") != std::string::npos && omplapp.empty())
        {
            ++skipped;
            continue;
        }
        // Every case works on its own copy of the corpus, so that any write to an input shows.
        const fs::path tmp = base / c.name;
        fs::remove_all(tmp);
        fs::create_directories(tmp);
        fs::copy(corpus, tmp / "corpus", fs::copy_options::recursive);
        std::vector<std::string> replaceable;
        for (const std::string &step : c.setup)
            replaceable.push_back(applySetup(step, tmp));
        const auto before = snapshot(tmp);

        auto substitute = [&](std::string text) {
            text = replaceAll(text, "{dir}", (tmp / "corpus").string());
            text = replaceAll(text, "{tmp}", tmp.string());
            return replaceAll(text, "{omplapp}", omplapp);
        };
        const auto start = std::chrono::steady_clock::now();
        const hcd::test::ShellResult r =
            hcd::test::runShell("cd '" + tmp.string() + "' && " + HYBRIDCD_CLI + " " + substitute(c.arguments));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        EXPECT_EQ(r.status, c.status) << r.output;
        const std::string expected = substitute(c.expected);
        EXPECT_NE(r.output.find(expected), std::string::npos) << "expected: " << expected << "\noutput:\n" << r.output;
        const auto after = snapshot(tmp);
        for (const auto &[file, state] : before)
        {
            const auto it = after.find(file);
            const bool mayChange = std::find(replaceable.begin(), replaceable.end(), file) != replaceable.end();
            if (it == after.end())
                ADD_FAILURE() << file << " was removed";
            else if (!mayChange)
                EXPECT_TRUE(it->second == state) << file << " was changed";
            else
                EXPECT_EQ(it->second.content.find("written before the run"), std::string::npos)
                    << file << " was not replaced";
        }
        for (const auto &[file, state] : after)
        {
            // No temporary file may survive any run; after an error, no file at all may appear.
            EXPECT_EQ(file.find(".tmp."), std::string::npos) << file << " was left behind";
            if (c.status != 0)
                EXPECT_TRUE(before.count(file)) << file << " was written by a failing run";
        }
        if (c.status != 0)
        {
            EXPECT_TRUE(namesFileOrOption(c.expected)) << "the expected message names no file, line or option";
            // "At once": no failing case may spend its --time on planning.
            EXPECT_LT(seconds, 20.0) << "took " << seconds << " s";
        }
        fs::remove_all(tmp);
    }
    fs::remove_all(base);
    if (skipped > 0)
        std::cout << "[ hostile ] " << skipped << " case(s) skipped: OMPL.app resources not found "
                  << "(set HYBRIDCD_OMPLAPP_RESOURCES)\n";
}
