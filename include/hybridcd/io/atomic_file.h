// SPDX-License-Identifier: BSD-3-Clause
// Output files that appear whole or not at all, the checks made before any work is done, and
// input files read whole within a bound.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace hcd
{
/** \brief Writes FILE by way of a temporary file in the same folder (".FILE.tmp.XXXXXX") that is
    renamed over FILE by commit(). rename() within one file system is atomic, so readers see the
    old file or the complete new one, never a partial write. Without commit() (an error or an
    exception part way) the destructor removes the temporary file and FILE is left untouched.
    A symbolic link is followed (the file it names is replaced); an existing device or pipe
    (/dev/null, /dev/stdout) is written directly, since renaming over it would replace the device. */
class AtomicFile
{
public:
    /// Creates the temporary file; throws InputError naming `path` when that is impossible.
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    /// The stream to write the content to.
    std::ostream &stream() { return out_; }
    /// Flushes, checks every write succeeded, and renames the temporary file to the target.
    /// Throws InputError naming the target on failure (the temporary file is then removed).
    void commit();

    const std::string &path() const { return path_; }

private:
    std::string path_;
    std::string target_;     ///< path_, or the file a symbolic link path_ names
    std::string temporary_;  ///< empty when writing a device or pipe directly
    std::ofstream out_;
    bool committed_ = false;
};

/** \brief Fails early, before any planning or loading, when `path` cannot be written: throws
    InputError naming `option` and `path` when its folder is missing, when it is a folder, when the
    folder refuses new files (checked by creating and removing a temporary file there), or when it
    is one of `inputs` (compared as the same file on disk, so "./a/../a.cfg" counts). */
void checkOutputPath(const std::string &path, const std::string &option, const std::vector<std::string> &inputs);

/** \brief The whole of the text input file `path` (a problem file, a pose file), at most `maxBytes`.
    Only regular files are read: a folder would read as empty, a device such as /dev/zero without
    end, and a pipe would wait for a writer forever. Throws InputError naming `path` when it is a
    folder ("is a folder, not a WHAT"), not a regular file, cannot be opened (missing, unreadable, a
    loop of symbolic links: "cannot open WHAT (reason)"), or holds more than `maxBytes` bytes.
    `what` names the kind of file in the messages: "pose file", "problem file (.cfg)". */
std::string readInputFile(const std::string &path, const std::string &what, std::uintmax_t maxBytes);
}  // namespace hcd
