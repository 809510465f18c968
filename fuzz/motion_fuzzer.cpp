// SPDX-License-Identifier: BSD-3-Clause
// Harness for the motion line reader (`check-motion`), in 3D and in the plane: every accepted line
// must give two rigid transforms.
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
            for (const auto &[from, to] : parseMotions(asText(data, size), "fuzz/motions.txt", planar))
            {
                check(from.line == to.line, "both poses of a motion come from one line");
                for (const PoseRecord *p : {&from, &to})
                {
                    check(p->values.size() == poseColumns(planar), "a pose has exactly its columns");
                    for (double v : p->values)
                        check(std::isfinite(v), "pose numbers are finite");
                    checkRigid(transformOfRow(p->values.data(), planar));
                }
            }
        }
        catch (const InputError &)
        {
        }
    }
    return 0;
}
}  // namespace hcd::fuzz
