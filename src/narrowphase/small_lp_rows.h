// SPDX-License-Identifier: BSD-3-Clause
// The small LP solver's own rows and scratch lists, for callers that build normalised rows in
// place and skip `solveSmallLp`'s copy (the LP narrow phase, on its hot path).
#pragma once

#include "hybridcd/narrowphase/small_lp.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace hcd::small_lp
{
// A constraint a . x <= b of a (sub)problem, with the index of the input constraint (or box
// bound) it came from, so that the optimum's basis can be reported. Plain arrays: the solver's
// loops over them are its whole cost, and they index coordinates by run-time pivots.
template <int K>
struct Row
{
    double a[K];
    double b;
    int id;
};

// One scratch list per dimension: the level-K step writes the rows of its (K-1)-D subproblem
// into rows<K-1> while reading its own from rows<K>, so no two live subproblems share a list. The
// lists only grow (to the largest problem seen), so once warm nothing is allocated. The caller
// owns the workspace (LpWorkspace); the solver passes it down.
struct Workspace
{
    std::vector<Row<1>> rows1;
    std::vector<Row<2>> rows2;
    std::vector<Row<3>> rows3;
    std::vector<Row<4>> rows4;
    std::vector<Row<1>> spare1;
    std::vector<Row<2>> spare2;
    std::vector<Row<3>> spare3;
    std::vector<Row<4>> spare4;
    std::vector<std::pair<double, int>> keys;
    std::vector<int> counts;
    std::vector<Halfspace<3>> primalRows;

    // A second list per dimension, for reordering rows<K> through a copy.
    template <int K>
    std::vector<Row<K>> &spare()
    {
        if constexpr (K == 1)
            return spare1;
        else if constexpr (K == 2)
            return spare2;
        else if constexpr (K == 3)
            return spare3;
        else
            return spare4;
    }

    template <int K>
    std::vector<Row<K>> &rows()
    {
        if constexpr (K == 1)
            return rows1;
        else if constexpr (K == 2)
            return rows2;
        else if constexpr (K == 3)
            return rows3;
        else
            return rows4;
    }

    // Room for the subproblems of a D-dimensional problem of n rows: each level below has at most
    // two rows (the box's) more than the one above.
    template <int D>
    void reserveSubproblems(std::size_t n)
    {
        if constexpr (D > 2)  // the 2D level solves its 1D subproblems in place
        {
            std::vector<Row<D - 1>> &sub = rows<D - 1>();
            if (sub.size() < n + 2)
                sub.resize(n + 2);
            reserveSubproblems<D - 1>(n + 2);
        }
    }
};

// Runs Seidel on n rows already normalised (unit normals) and ordered, which live in
// ws.rows<D>(). Instantiated for D = 4.
template <int D>
bool solveRows(Workspace &ws, int n, const double *objective, const double *lower, const double *upper,
               double tolerance, double *x, int *basis);
}  // namespace hcd::small_lp

namespace hcd
{
// The workspace behind the public handle.
struct LpWorkspace::Lists : small_lp::Workspace
{
};
}  // namespace hcd
