// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer's entry point, forwarding to the harness linked beside it.
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    return hcd::fuzz::fuzzOne(data, size);
}
