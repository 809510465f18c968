// SPDX-License-Identifier: BSD-3-Clause
// Replays inputs through a harness without libFuzzer: `replay DIR_OR_FILE...`. Every regular file
// under the arguments is fed once; a finding aborts, as in the fuzzer. Fails when nothing was found
// to replay, so a mistyped corpus path cannot pass silently.
#include "fuzz_target.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

int main(int argc, char **argv)
{
    namespace fs = std::filesystem;
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i)
    {
        const fs::path arg(argv[i]);
        if (fs::is_directory(arg))
        {
            for (const auto &entry : fs::recursive_directory_iterator(arg))
                if (entry.is_regular_file())
                    inputs.push_back(entry.path());
        }
        else if (fs::is_regular_file(arg))
            inputs.push_back(arg);
        else
        {
            std::cerr << "replay: no such file or folder: " << arg << '\n';
            return 2;
        }
    }
    std::sort(inputs.begin(), inputs.end());  // a stable order makes a failure easy to reproduce
    for (const fs::path &p : inputs)
    {
        std::ifstream in(p, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::cout << "replay: " << p.string() << std::endl;  // flushed, so a crash names its input
        hcd::fuzz::fuzzOne(reinterpret_cast<const std::uint8_t *>(bytes.data()), bytes.size());
    }
    std::cout << "replay: " << inputs.size() << " inputs, no finding\n";
    return inputs.empty() ? 1 : 0;
}
