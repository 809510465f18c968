// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/small_lp.h"

#include "small_lp_rows.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace hcd
{
namespace small_lp
{
namespace
{
template <int K>
struct Box
{
    double lo[K], hi[K];
    int loId[K], hiId[K];
};

// A substituted constraint whose coefficients all fall below this (the input rows have unit
// normals and substitution never more than doubles a coefficient) is parallel to the current
// flat: within the box its left side is below ~1e-13, so it is checked as the constant 0 <= b.
constexpr double kConstant = 1e-14;

// The feasible interval of one variable, narrowed one constraint a y <= b at a time. Both ends
// are kept as upper bounds, end_[0] on y and end_[1] on -y, so that either sign of a is the same
// code without a branch on it: with m = |a|, the constraint bounds s y by b / m where s is the
// sign of a. Each end remembers the constraint that made it and its weight |a|, to judge crossed
// ends. (The comparisons b < end m are the exact ones of b < hi a and b < lo a.)
class Interval
{
public:
    Interval(double lo, double hi, int loId, int hiId)
    {
        end_[0] = hi, end_[1] = -lo;
        id_[0] = hiId, id_[1] = loId;
        weight_[0] = weight_[1] = 1.0;
    }

    // False when the constraint is (numerically) a constant 0 <= b that fails.
    bool add(double a, double b, int id, double eps)
    {
        const double m = std::fabs(a);
        if (!(m > kConstant))
            return !(b < -eps);
        const int s = a < 0.0;
        // Compare before dividing: most constraints do not move an end.
        if (b < end_[s] * m)
            end_[s] = b / m, id_[s] = id, weight_[s] = m;
        return true;
    }

    // The end the objective coefficient points to (the upper one when it is zero).
    bool optimum(double c, double eps, double &y, int &id) const
    {
        const double lo = -end_[1], hi = end_[0];
        if (lo > hi)
        {
            // Crossed ends may still be feasible within the tolerance, which is measured in the
            // constraints' own units: take the point where both violations are equal.
            y = (weight_[0] * hi + weight_[1] * lo) / (weight_[0] + weight_[1]);
            if (!(weight_[0] * (y - hi) <= eps))
                return false;
        }
        else
            y = c >= 0.0 ? hi : lo;
        id = c >= 0.0 ? id_[0] : id_[1];
        return true;
    }

private:
    double end_[2], weight_[2];
    int id_[2];
};

// Start of every level: the box corner the objective points to.
template <int K>
void boxCorner(const double *c, const Box<K> &box, double *x, int *basis)
{
    for (int j = 0; j < K; ++j)
    {
        const bool up = c[j] > 0.0;
        x[j] = up ? box.hi[j] : box.lo[j];
        basis[j] = up ? box.hiId[j] : box.loId[j];
    }
}

// The first row from `from` on that x violates by more than eps (n when none does).
template <int K>
int firstViolated(const Row<K> *__restrict rows, int from, int n, const double *xIn, double eps)
{
    double x[K];
    for (int j = 0; j < K; ++j)
        x[j] = xIn[j];
    for (int i = from; i < n; ++i)
    {
        const Row<K> &h = rows[i];
        double v = h.a[0] * x[0];
        for (int j = 1; j < K; ++j)
            v += h.a[j] * x[j];
        if (!(v - h.b <= eps))  // NaN counts as violated
            return i;
    }
    return n;
}

// The largest coefficient (the first of equal ones).
template <int K>
int pivotOf(const Row<K> &h, double &pivot)
{
    int k = 0;
    pivot = std::fabs(h.a[0]);
    for (int j = 1; j < K; ++j)
        if (std::fabs(h.a[j]) > pivot)
            pivot = std::fabs(h.a[j]), k = j;
    return k;
}

template <int K>
bool seidel(Row<K> *rows, int n, const double *c, const Box<K> &box, double eps, double *x, int *basis, Workspace &ws);

template <>
bool seidel<1>(Row<1> *rows, int n, const double *c, const Box<1> &box, double eps, double *x, int *basis, Workspace &)
{
    Interval interval(box.lo[0], box.hi[0], box.loId[0], box.hiId[0]);
    for (int i = 0; i < n; ++i)
        if (!interval.add(rows[i].a[0], rows[i].b, rows[i].id, eps))
            return false;
    return interval.optimum(c[0], eps, x[0], basis[0]);
}

// Two dimensions, with the one-dimensional subproblem done in place (it is where most of the
// work happens, so its rows are never written out).
// The one-dimensional subproblem of the 2D level, on the line x_K = q + g x_J, over rows[0..n).
template <int K>
bool narrowOnLine(const Row<2> *__restrict rows, int n, double g, double q, double eps, Interval &interval)
{
    constexpr int J = 1 - K;
    for (int m = 0; m < n; ++m)
    {
        const Row<2> &r = rows[m];
        if (!interval.add(r.a[J] + r.a[K] * g, r.b - r.a[K] * q, r.id, eps))
            return false;
    }
    return true;
}

// Two dimensions, with the one-dimensional subproblem done in place (it is where most of the
// work happens, so its rows are never written out).
template <>
bool seidel<2>(Row<2> *rows, int n, const double *c, const Box<2> &box, double eps, double *x, int *basis, Workspace &)
{
    boxCorner<2>(c, box, x, basis);
    for (int i = firstViolated<2>(rows, 0, n, x, eps); i < n; i = firstViolated<2>(rows, i + 1, n, x, eps))
    {
        const Row<2> &h = rows[i];
        const int k = std::fabs(h.a[0]) >= std::fabs(h.a[1]) ? 0 : 1, j = 1 - k;
        if (std::fabs(h.a[k]) <= kConstant)
        {
            if (h.b < -eps)
                return false;
            continue;
        }
        // On the line, x_k = q + g x_j with |g| <= 1.
        const double g = -h.a[j] / h.a[k], q = h.b / h.a[k];
        Interval interval(box.lo[j], box.hi[j], box.loId[j], box.hiId[j]);
        if (!interval.add(g, box.hi[k] - q, box.hiId[k], eps) || !interval.add(-g, q - box.lo[k], box.loId[k], eps))
            return false;
        if (!(k == 0 ? narrowOnLine<0>(rows, i, g, q, eps, interval) : narrowOnLine<1>(rows, i, g, q, eps, interval)))
            return false;
        double y;
        int id;
        if (!interval.optimum(c[j] + c[k] * g, eps, y, id))
            return false;
        x[j] = y;
        x[k] = q + g * y;
        basis[0] = h.id, basis[1] = id;
    }
    return true;
}

// The rows of the subproblem on the hyperplane x_P = q + g . y (y: the coordinates other than
// P, in order): a . x <= b becomes (a_y + a_P g) . y <= b - a_P q. The pivot is a template
// argument so that every coordinate is a fixed offset, and the lists cannot alias.
template <int K, int P>
void substituteRows(const Row<K> *__restrict rows, int n, const double *g, double q, Row<K - 1> *__restrict out)
{
    double gl[K - 1];
    for (int m = 0; m < K - 1; ++m)
        gl[m] = g[m];
    for (int j = 0; j < n; ++j)
    {
        const Row<K> &r = rows[j];
        Row<K - 1> &o = out[j];
        const double ak = r.a[P];
        for (int m = 0; m < K - 1; ++m)
            o.a[m] = r.a[m < P ? m : m + 1] + ak * gl[m];
        o.b = r.b - ak * q;
        o.id = r.id;
    }
}

template <int K>
void substituteRows(const Row<K> *rows, int n, int k, const double *g, double q, Row<K - 1> *out)
{
    static_assert(K == 3 || K == 4, "the 2D level substitutes in place");
    switch (k)
    {
    case 0:
        return substituteRows<K, 0>(rows, n, g, q, out);
    case 1:
        return substituteRows<K, 1>(rows, n, g, q, out);
    case 2:
        return substituteRows<K, 2>(rows, n, g, q, out);
    default:
        if constexpr (K == 4)
            return substituteRows<K, 3>(rows, n, g, q, out);
    }
}

template <int K>
bool seidel(Row<K> *rows, int n, const double *c, const Box<K> &box, double eps, double *x, int *basis, Workspace &ws)
{
    boxCorner<K>(c, box, x, basis);
    Row<K - 1> *const out = ws.rows<K - 1>().data();  // room for n + 2 rows (reserveSubproblems)
    for (int i = firstViolated<K>(rows, 0, n, x, eps); i < n; i = firstViolated<K>(rows, i + 1, n, x, eps))
    {
        const Row<K> &h = rows[i];
        double pivot;
        const int k = pivotOf<K>(h, pivot);
        if (pivot <= kConstant)
        {
            if (h.b < -eps)
                return false;
            continue;
        }
        // On the hyperplane, x_k = q + g . y over the other coordinates y. Pivoting on the
        // largest coefficient keeps |g_j| <= 1.
        int kept[K - 1];  // the coordinates other than k
        for (int j = 0, m = 0; j < K; ++j)
            if (j != k)
                kept[m++] = j;
        const double inverse = 1.0 / h.a[k];
        double g[K - 1];
        for (int m = 0; m < K - 1; ++m)
            g[m] = -h.a[kept[m]] * inverse;
        const double q = h.b * inverse;

        substituteRows<K>(rows, i, k, g, q, out);
        // The box's bounds on x_k go last: they are rarely active, and a row that is not active
        // at the optimum costs nothing when it comes late (at the front, it was violated by the
        // starting corner of most subproblems, at the price of a subproblem of its own).
        Row<K - 1> &upper = out[i], &lower = out[i + 1];
        for (int m = 0; m < K - 1; ++m)
            upper.a[m] = g[m], lower.a[m] = -g[m];
        upper.b = box.hi[k] - q, upper.id = box.hiId[k];  // x_k <= hi_k
        lower.b = q - box.lo[k], lower.id = box.loId[k];  // x_k >= lo_k
        Box<K - 1> subBox;
        double subObjective[K - 1];
        for (int m = 0; m < K - 1; ++m)
        {
            const int j = kept[m];
            subBox.lo[m] = box.lo[j], subBox.hi[m] = box.hi[j];
            subBox.loId[m] = box.loId[j], subBox.hiId[m] = box.hiId[j];
            subObjective[m] = c[j] + c[k] * g[m];
        }

        double y[K - 1];
        int subBasis[K - 1];
        if (!seidel<K - 1>(out, i + 2, subObjective, subBox, eps, y, subBasis, ws))
            return false;
        double xk = q;
        for (int m = 0; m < K - 1; ++m)
            xk += g[m] * y[m], x[kept[m]] = y[m];
        x[k] = xk;
        basis[0] = h.id;
        for (int m = 0; m < K - 1; ++m)
            basis[m + 1] = subBasis[m];
        // Move to front: the row just violated is likely to be tight at the end, and the
        // subproblems of later violations take the rows in this order. Rows 0..i are the same
        // set afterwards, so x is still their optimum. (Three to four times fewer subproblem
        // rows for pieces of hundreds of faces, neutral for small ones.)
        if (i > 0)
        {
            const Row<K> moved = rows[i];
            std::memmove(static_cast<void *>(rows + 1), static_cast<const void *>(rows),
                         sizeof(Row<K>) * std::size_t(i));
            rows[0] = moved;
        }
    }
    return true;
}

}  // namespace

// Runs Seidel on rows already normalised and ordered (they live in ws.rows<D>()).
template <int D>
bool solveRows(Workspace &ws, int n, const double *objective, const double *lower, const double *upper,
               double tolerance, double *x, int *basis)
{
    ws.reserveSubproblems<D>(std::size_t(n));
    Box<D> box;
    for (int j = 0; j < D; ++j)
    {
        box.lo[j] = lower[j], box.hi[j] = upper[j];
        box.loId[j] = lpLowerBoundId(j), box.hiId[j] = lpUpperBoundId(j);
    }
    return seidel<D>(ws.rows<D>().data(), n, objective, box, tolerance, x, basis, ws);
}

template bool solveRows<4>(Workspace &, int, const double *, const double *, const double *, double, double *, int *);
}  // namespace small_lp

namespace
{
using small_lp::Row;
using small_lp::solveRows;
using small_lp::Workspace;

// Sorts (key, index) pairs: insertion sort for the few dozen rows of a typical problem, which
// beats std::sort's setup there; the order is the same (pairs are distinct).
void sortKeys(std::pair<double, int> *keys, int n)
{
    if (n > 48)
    {
        std::sort(keys, keys + n);
        return;
    }
    for (int i = 1; i < n; ++i)
    {
        const std::pair<double, int> key = keys[i];
        int j = i;
        for (; j > 0 && key < keys[j - 1]; --j)
            keys[j] = keys[j - 1];
        keys[j] = key;
    }
}

std::uint64_t splitMix64(std::uint64_t &state)
{
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
}  // namespace

LpWorkspace::LpWorkspace() : lists_(std::make_unique<Lists>()) {}
LpWorkspace::~LpWorkspace() = default;
LpWorkspace::LpWorkspace(LpWorkspace &&) noexcept = default;
LpWorkspace &LpWorkspace::operator=(LpWorkspace &&) noexcept = default;

template <int D>
LpSolution<D> solveSmallLp(LpWorkspace &workspace, const std::vector<Halfspace<D>> &constraints,
                           const Eigen::Matrix<double, D, 1> &objective, const Eigen::Matrix<double, D, 1> &lower,
                           const Eigen::Matrix<double, D, 1> &upper, double tolerance,
                           const Eigen::Matrix<double, D, 1> *orderHint, std::uint64_t seed)
{
    LpSolution<D> solution;
    if (!((lower.array() <= upper.array() + tolerance).all()))
        return solution;
    Workspace &ws = workspace.lists();
    std::vector<Row<D>> &rows = ws.rows<D>();
    if (rows.size() < constraints.size())
        rows.resize(constraints.size());
    int n = 0;
    for (std::size_t i = 0; i < constraints.size(); ++i)
    {
        const double length = constraints[i].a.norm();
        if (!(length > 0.0))
        {
            if (!(constraints[i].b >= -tolerance))
                return solution;
            continue;
        }
        Row<D> &r = rows[std::size_t(n++)];
        for (int j = 0; j < D; ++j)
            r.a[j] = constraints[i].a[j] / length;
        r.b = constraints[i].b / length;
        r.id = int(i);
    }
    if (orderHint)
    {
        // Most of Seidel's work is done when late constraints are violated; taking first the
        // constraints tightest at a point near the optimum makes that rare (five to eight times
        // fewer subproblem rows on convex pieces). Ties go by index (here: by position, which
        // is in increasing index).
        if (ws.keys.size() < std::size_t(n))
            ws.keys.resize(std::size_t(n));
        for (int i = 0; i < n; ++i)
        {
            const Row<D> &r = rows[std::size_t(i)];
            double s = r.b;
            for (int j = 0; j < D; ++j)
                s -= r.a[j] * (*orderHint)[j];
            ws.keys[std::size_t(i)] = {s, i};
        }
        sortKeys(ws.keys.data(), n);
        std::vector<Row<D>> &unsorted = ws.spare<D>();
        unsorted.assign(rows.begin(), rows.begin() + n);
        for (int i = 0; i < n; ++i)
            rows[std::size_t(i)] = unsorted[std::size_t(ws.keys[std::size_t(i)].second)];
    }
    else
    {
        // Seeded Fisher-Yates shuffle: Seidel's expected bound needs a random order, the tests
        // and the planner need reproducible answers.
        std::uint64_t state = seed;
        for (std::size_t i = std::size_t(n); i > 1; --i)
            std::swap(rows[i - 1], rows[splitMix64(state) % i]);
    }

    int basis[D];
    double x[D];
    if (solveRows<D>(ws, n, objective.data(), lower.data(), upper.data(), tolerance, x, basis))
    {
        solution.status = LpStatus::Optimal;
        for (int j = 0; j < D; ++j)
            solution.x[j] = x[j], solution.basis[std::size_t(j)] = basis[j];
    }
    return solution;
}

#define HYBRIDCD_INSTANTIATE_SMALL_LP(D)                                                                               \
    template LpSolution<D> solveSmallLp<D>(LpWorkspace &, const std::vector<Halfspace<D>> &,                           \
                                           const Eigen::Matrix<double, D, 1> &, const Eigen::Matrix<double, D, 1> &,   \
                                           const Eigen::Matrix<double, D, 1> &, double,                                \
                                           const Eigen::Matrix<double, D, 1> *, std::uint64_t);
HYBRIDCD_INSTANTIATE_SMALL_LP(1)
HYBRIDCD_INSTANTIATE_SMALL_LP(2)
HYBRIDCD_INSTANTIATE_SMALL_LP(3)
HYBRIDCD_INSTANTIATE_SMALL_LP(4)
#undef HYBRIDCD_INSTANTIATE_SMALL_LP
}  // namespace hcd
