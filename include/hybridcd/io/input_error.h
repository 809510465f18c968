// SPDX-License-Identifier: BSD-3-Clause
// The error type for bad user input: it always names the file, and the line when there is one.
#pragma once

#include <stdexcept>
#include <string>

namespace hcd
{
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
