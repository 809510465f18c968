// SPDX-License-Identifier: BSD-3-Clause
// The error type for bad user input: it always names the file, and the line when there is one.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hcd
{
/// The largest magnitude a number read from a problem, pose or path file may have: the squares of
/// distances between points that far out still fit in a double (shapes take the same bound).
constexpr double kLargestInputMagnitude = 1e100;

/// `text` with every control byte (below 0x20, and 0x7f) and every byte that is not part of valid
/// UTF-8 written as \xNN, for quoting file content or a command-line word in a message: a NUL would
/// cut the message short, an escape sequence would reach the terminal. With `keepNewlines`, line
/// breaks are kept (a message of several lines).
inline std::string printable(std::string_view text, bool keepNewlines = false)
{
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();)
    {
        const auto c = static_cast<unsigned char>(text[i]);
        // The length of the UTF-8 sequence starting here, 0 when it is not one.
        std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
        if (i + n > text.size())
            n = 0;
        for (std::size_t k = 1; k < n; ++k)
            if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2)
                n = 0;
        if (n == 0 || ((c < 0x20 || c == 0x7f) && !(keepNewlines && c == '\n')))
        {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", unsigned(c));
            out += escaped;
            ++i;
        }
        else
        {
            out.append(text.substr(i, n));
            i += n;
        }
    }
    return out;
}

/// Thrown for unreadable, missing or malformed input files. what() reads "FILE:LINE: message"
/// (or "FILE: message" when no line applies), the form compilers use, so editors can jump to it.
class InputError : public std::runtime_error
{
public:
    InputError(const std::string &file, int line, const std::string &message)
        : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message)
    {
    }
};
}  // namespace hcd
