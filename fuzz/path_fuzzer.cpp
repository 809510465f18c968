// SPDX-License-Identifier: BSD-3-Clause
// Harness for OMPL.app .path files: what is read, written back with writePoses and read again must
// give the same numbers bit for bit (`solve --out` writes the paths `check` reads).
#include "fuzz_target.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"

#include <cstring>
#include <sstream>

namespace hcd::fuzz
{
int fuzzOne(const std::uint8_t *data, std::size_t size)
{
    for (const bool planar : {false, true})
    {
        std::vector<std::vector<double>> first;
        try
        {
            for (const PoseRecord &p : parsePoses(asText(data, size), "fuzz/input.path", planar))
                first.push_back(p.values);
        }
        catch (const InputError &)
        {
            continue;
        }
        std::ostringstream written;
        writePoses(written, first);
        std::vector<PoseRecord> second;
        try
        {
            second = parsePoses(written.str(), "fuzz/written.path", planar);
        }
        catch (const InputError &)
        {
            check(false, "a written path reads back");
        }
        check(second.size() == first.size(), "a written path has as many poses as were read");
        for (std::size_t i = 0; i < first.size(); ++i)
        {
            check(second[i].line == int(i) + 1, "a written path has one pose per line");
            // memcmp, so that -0 and 0 differ as they would in the planner.
            check(second[i].values.size() == first[i].size() &&
                      std::memcmp(second[i].values.data(), first[i].data(), first[i].size() * sizeof(double)) == 0,
                  "a written pose reads back bit for bit");
        }
    }
    return 0;
}
}  // namespace hcd::fuzz
