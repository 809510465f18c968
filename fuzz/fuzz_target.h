// SPDX-License-Identifier: BSD-3-Clause
// What every harness provides, and the checks they share.
//
// Each *_fuzzer.cpp defines fuzzOne() once; it is linked either with libfuzzer_entry.cpp (the
// libFuzzer binaries, clang) or with replay_main.cpp (the corpus replay run by CTest, any compiler).
// A harness accepts InputError, the documented way to reject input; any other exception, a failed
// check() or a sanitizer report is a finding.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace hcd::fuzz
{
/// Feeds one input to the code under test. Returns 0 (libFuzzer's convention); aborts on a finding.
int fuzzOne(const std::uint8_t *data, std::size_t size);

/// The input as text (the readers take any bytes, including NUL and invalid UTF-8).
inline std::string_view asText(const std::uint8_t *data, std::size_t size)
{
    return {reinterpret_cast<const char *>(data), size};
}

/// Aborts with a message when a property of accepted input does not hold, so the fuzzer stops
/// there and saves the input.
inline void check(bool holds, const char *property)
{
    if (holds)
        return;
    std::fprintf(stderr, "fuzz check failed: %s\n", property);
    std::abort();
}

/// An accepted pose must give a rigid transform: finite, orthonormal, no reflection.
inline void checkRigid(const RigidTransform &t)
{
    check(t.isFinite(), "pose gives a finite transform");
    check((t.rotation.transpose() * t.rotation - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-9,
          "pose gives an orthonormal rotation");
    check(t.rotation.determinant() > 0.0, "pose gives a proper rotation");
}
}  // namespace hcd::fuzz
