// SPDX-License-Identifier: BSD-3-Clause
// Harness for the pose line reader (`check`, `clearance` and `contacts` states), in 3D and in the
// plane: every accepted line must give a rigid transform.
#include "fuzz_target.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"

#include <cmath>

namespace hcd::fuzz
{
int fuzzOne(const std::uint8_t *data, std::size_t size)
{
    for (const bool planar : {false, true})
    {
        try
        {
            int previousLine = 0;
            for (const PoseRecord &p : parsePoses(asText(data, size), "fuzz/poses.txt", planar))
            {
                check(p.values.size() == poseColumns(planar), "a pose has exactly its columns");
                check(p.line > previousLine, "poses come in line order");
                previousLine = p.line;
                for (double v : p.values)
                    check(std::isfinite(v), "pose numbers are finite");
                checkRigid(transformOfRow(p.values.data(), planar));
            }
        }
        catch (const InputError &)
        {
        }
    }
    return 0;
}
}  // namespace hcd::fuzz
