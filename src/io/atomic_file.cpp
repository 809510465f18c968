// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/atomic_file.h"

#include "hybridcd/io/input_error.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace hcd
{
namespace
{
// The folder a file is created in ("." for a bare name).
fs::path folderOf(const std::string &path)
{
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

// Creates "FOLDER/.NAME.tmp.XXXXXX" (mkstemp: unique, not following links) and returns its name;
// on failure returns an empty string with errno set.
std::string createTemporaryBeside(const std::string &path)
{
    std::string pattern = (folderOf(path) / ("." + fs::path(path).filename().string() + ".tmp.XXXXXX")).string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const int fd = ::mkstemp(buffer.data());
    if (fd < 0)
        return {};
    // mkstemp creates the file private (0600); give it the permissions a plain open would.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    ::close(fd);
    return std::string(buffer.data());
}

std::string whyNotWritable(const std::string &path)
{
    const fs::path folder = folderOf(path);
    std::error_code ec;
    if (fs::is_directory(path, ec))
        return "is a folder, not a file";
    if (!fs::exists(folder, ec))
        return "its folder " + folder.string() + " does not exist";
    if (!fs::is_directory(folder, ec))
        return folder.string() + " is not a folder";
    return {};
}
}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path))
{
    if (const std::string why = whyNotWritable(path_); !why.empty())
        throw InputError(path_, 0, "cannot write: " + why);
    std::error_code ec;
    if (fs::exists(path_, ec) && !fs::is_regular_file(path_, ec))
    {
        // A device or pipe such as /dev/null or /dev/stdout: renaming over it would replace the
        // device itself, so it is written directly (a stream has no half-written state to avoid).
        out_.open(path_, std::ios::binary);
        if (!out_)
            throw InputError(path_, 0, "cannot write");
        return;
    }
    // Through a symbolic link, the file it points to is replaced, not the link.
    target_ = path_;
    if (fs::is_symlink(path_, ec))
    {
        std::error_code linkError;
        target_ = fs::canonical(path_, linkError).string();
        if (linkError)
            throw InputError(path_, 0, "cannot follow the symbolic link: " + linkError.message());
    }
    temporary_ = createTemporaryBeside(target_);
    if (temporary_.empty())
        throw InputError(path_, 0, std::string("cannot write: ") + std::strerror(errno));
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_)
    {
        std::remove(temporary_.c_str());
        throw InputError(path_, 0, "cannot write the temporary file " + temporary_);
    }
}

AtomicFile::~AtomicFile()
{
    if (!committed_ && !temporary_.empty())
    {
        out_.close();
        std::remove(temporary_.c_str());
    }
}

void AtomicFile::commit()
{
    out_.flush();
    const bool written = bool(out_);
    out_.close();
    if (temporary_.empty())  // written directly (a device or pipe)
    {
        committed_ = true;
        if (!written)
            throw InputError(path_, 0, "writing failed");
        return;
    }
    if (!written || out_.fail())
        throw InputError(path_, 0, "writing failed (disk full?); the file was left unchanged");
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
        throw InputError(path_, 0, std::string("cannot replace the file: ") + std::strerror(errno));
    committed_ = true;
}

void checkOutputPath(const std::string &path, const std::string &option, const std::vector<std::string> &inputs)
{
    const std::string where = option.empty() ? std::string("output ") : option + " ";
    if (path.empty())
        throw InputError(where + "''", 0, "empty output file name");
    if (const std::string why = whyNotWritable(path); !why.empty())
        throw InputError(path, 0, where + "cannot be written: " + why);
    std::error_code ec;
    for (const std::string &input : inputs)
        if (!input.empty() && fs::exists(path, ec) && fs::equivalent(path, input, ec))
            throw InputError(path, 0, where + "names an input of this run (" + input + "); refusing to overwrite it");
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    {
        // A device or pipe is written in place (see AtomicFile); it only needs write permission.
        if (::access(path.c_str(), W_OK) != 0)
            throw InputError(path, 0, where + "cannot be written: " + std::strerror(errno));
        return;
    }
    std::error_code linkError;
    const fs::path target = fs::is_symlink(path, ec) ? fs::canonical(path, linkError) : fs::path(path);
    if (linkError)
        throw InputError(path, 0, where + "is a symbolic link that cannot be followed: " + linkError.message());
    const std::string probe = createTemporaryBeside(target.string());
    if (probe.empty())
        throw InputError(path, 0, where + "cannot be written: " + std::strerror(errno));
    std::remove(probe.c_str());
}

std::string readInputFile(const std::string &path, const std::string &what, std::uintmax_t maxBytes)
{
    const std::string notRegular = "is not a regular file (a device, pipe or socket); a " + what + " is expected";
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // the file a symbolic link names
    if (fs::is_directory(status))
        throw InputError(path, 0, "is a folder, not a " + what);
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw InputError(path, 0, notRegular);
    // O_NONBLOCK: should `path` have become a pipe since, opening it does not wait for a writer;
    // the descriptor is checked again below, so what is read is the regular file that was opened.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw InputError(path, 0, "cannot open " + what + " (" + std::strerror(errno) + ")");
    struct Closer
    {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat info
    {
    };
    if (::fstat(fd, &info) != 0)
        throw InputError(path, 0, "cannot read " + what + " (" + std::strerror(errno) + ")");
    if (!S_ISREG(info.st_mode))
        throw InputError(path, 0, notRegular);
    const auto tooLarge = [&](std::uintmax_t bytes) {
        return InputError(path, 0,
                          "the " + what + " has " + std::to_string(bytes) + " bytes, above the limit of " +
                              std::to_string(maxBytes) + " bytes");
    };
    if (std::uintmax_t(info.st_size) > maxBytes)
        throw tooLarge(std::uintmax_t(info.st_size));
    // Read up to one byte past the limit: the file may have grown since fstat.
    std::string text;
    text.reserve(std::size_t(info.st_size));
    char block[1 << 16];
    while (text.size() <= maxBytes)
    {
        const ssize_t n = ::read(fd, block, sizeof block);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            throw InputError(path, 0, "cannot read " + what + " (" + std::strerror(errno) + ")");
        if (n == 0)
            break;
        text.append(block, std::size_t(n));
    }
    if (text.size() > maxBytes)
        throw tooLarge(text.size());
    return text;
}
}  // namespace hcd
