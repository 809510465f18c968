// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/linear_program.h"

#include "hybridcd/narrowphase/candidate_axes.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace hcd
{
namespace
{
// A constraint a . x <= b of a (sub)problem, with the index of the input constraint (or box
// bound) it came from, so that the optimum's basis can be reported. Plain arrays: the loops
// below are the whole cost of the solver, and they index coordinates by run-time pivots.
template <int K>
struct Row
{
    double a[K];
    double b;
    int id;
};

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
bool seidel(Row<K> *rows, int n, const double *c, const Box<K> &box, double eps, double *x, int *basis,
            Workspace &ws);

template <>
bool seidel<1>(Row<1> *rows, int n, const double *c, const Box<1> &box, double eps, double *x, int *basis,
               Workspace &)
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
bool seidel<2>(Row<2> *rows, int n, const double *c, const Box<2> &box, double eps, double *x, int *basis,
               Workspace &)
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
bool seidel(Row<K> *rows, int n, const double *c, const Box<K> &box, double eps, double *x, int *basis,
            Workspace &ws)
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
            std::memmove(static_cast<void *>(rows + 1), static_cast<const void *>(rows), sizeof(Row<K>) * std::size_t(i));
            rows[0] = moved;
        }
    }
    return true;
}

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

// Writes rows[0..n) to `sorted` in increasing order of b (the slack at the origin with t = 0)
// up to buckets: a stable counting sort into n equal buckets between the smallest and largest b.
// It orders the rows as well as a full sort does for Seidel's purposes (the same number of
// subproblem rows within a few percent) at a fraction of the cost, and without a branch.
// `counts` has room for 2 n + 1 entries.
void orderBySlack(const Row<4> *rows, int n, Row<4> *sorted, std::vector<int> &counts)
{
    if (n == 0)
        return;
    double lo = rows[0].b, hi = rows[0].b;
    for (int i = 1; i < n; ++i)
        lo = std::min(lo, rows[i].b), hi = std::max(hi, rows[i].b);
    const double scale = hi > lo ? double(n) / (hi - lo) : 0.0;
    const double last = double(n - 1);
    int *const count = counts.data();          // n + 1 entries
    int *const bucketOf = counts.data() + n + 1;  // n entries
    std::fill(count, count + n + 1, 0);
    for (int i = 0; i < n; ++i)
    {
        const double v = (rows[i].b - lo) * scale;
        const int bucket = int(std::min(v >= 0.0 ? v : 0.0, last));  // NaN goes first
        bucketOf[i] = bucket;
        ++count[bucket + 1];
    }
    for (int k = 0; k < n; ++k)
        count[k + 1] += count[k];
    for (int i = 0; i < n; ++i)
        sorted[count[bucketOf[i]]++] = rows[i];
}

std::uint64_t splitMix64(std::uint64_t &state)
{
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// ---------------------------------------------------------------------------------------------
// Convex pieces.

// The pair's scale for tolerances: the largest absolute vertex coordinate.
double pairTolerance(const ConvexPiece &a, const ConvexPiece &b)
{
    return kNarrowPhaseRelativeTolerance * std::max(a.magnitude(), b.magnitude()) + 1e-300;
}

// Working frame: x = center + scale * x', with every vertex in |x'_i| <= 1.
struct Frame
{
    Vec3 center;
    double scale;
};

// The working frame and, in the same pass over the vertices, `pairTolerance`.
Frame workingFrame(const ConvexPiece &a, const ConvexPiece &b, double *tolerance = nullptr)
{
    Frame f{0.5 * (a.centroid + b.centroid), 0.0};
    Vec3 extent = Vec3::Zero(), magnitude = Vec3::Zero();
    for (const ConvexPiece *p : {&a, &b})
        for (const Vec3 &v : p->vertices)
        {
            extent = extent.cwiseMax((v - f.center).cwiseAbs());
            magnitude = magnitude.cwiseMax(v.cwiseAbs());
        }
    f.scale = extent.maxCoeff();
    const double largest = magnitude.maxCoeff();  // max(a.magnitude(), b.magnitude())
    if (!(f.scale > 0.0))  // both pieces one and the same point
        f.scale = std::max(1.0, largest);
    if (tolerance)
        *tolerance = kNarrowPhaseRelativeTolerance * largest + 1e-300;
    return f;
}

// n . x <= d in working coordinates, with n made unit: n . x' <= (d - n . center) / scale.
template <typename Emit>
void forEachScaledPlane(const ConvexPiece &p, const Frame &f, Emit emit)
{
    const double inverseScale = 1.0 / f.scale;
    for (std::size_t i = 0; i < p.normals.size(); ++i)
    {
        const double length = p.normals[i].norm();
        if (!(length > 0.0))
            continue;
        // Multiplying by the inverse (the normals are unit, so it is one up to rounding) is
        // several times cheaper than dividing; a length so small that the inverse overflows
        // divides instead.
        const double inverse = 1.0 / length;
        if (inverse <= 1e300)
        {
            const Vec3 n = p.normals[i] * inverse;
            emit(n, (p.offsets[i] * inverse - n.dot(f.center)) * inverseScale);
        }
        else
        {
            const Vec3 n = p.normals[i] / length;
            emit(n, (p.offsets[i] / length - n.dot(f.center)) / f.scale);
        }
    }
}

// Box of the working frame: four times the data's extent, so never active where it matters.
constexpr double kBox = 4.0;
// Bounds on the slack: above the largest inscribed radius (sqrt 3), below the smallest slack
// anywhere in the box (-(sqrt 3 + 4 sqrt 3)), so neither is active at the optimum.
constexpr double kSlackHigh = 4.0, kSlackLow = -16.0;
// Violations below this fraction of the tolerance (1e-13 relative) are rounding: exactly touching
// pieces land there, and are answered without the separating-axis search of the band above it.
// A sharp vertex (angle above 2e-4 rad) within the band is within the tolerance of touching.
constexpr double kRoundingFraction = 1e-4;
// Seidel's tolerance in the working frame (unit size): far above rounding, far below the
// narrow phase's 1e-9.
constexpr double kLpTolerance = 1e-12;

// Sets the plane normal to `direction` halfway between the pieces when the gap between their
// vertex projections exceeds `minimumGap`.
bool separateAlong(const Vec3 &direction, const ConvexPiece &a, const ConvexPiece &b, double minimumGap,
                   IntersectionResult &result)
{
    const double length = direction.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        return false;
    const Vec3 n = direction / length;
    double maxA = -std::numeric_limits<double>::infinity(), minB = std::numeric_limits<double>::infinity();
    for (const Vec3 &v : a.vertices)
        maxA = std::max(maxA, n.dot(v));
    for (const Vec3 &v : b.vertices)
        minB = std::min(minB, n.dot(v));
    if (!(minB - maxA > minimumGap))
        return false;
    result.separatingNormal = n;
    result.separatingOffset = 0.5 * (maxA + minB);  // lies in [maxA, minB] in floating point too
    return true;
}

// Separating-axis search, stopping early once some axis gives a gap above `stopAbove`.
class AxisSearch
{
public:
    AxisSearch(const ConvexPiece &a, const ConvexPiece &b, double stopAbove) : a_(a), b_(b), stopAbove_(stopAbove) {}

    double run(Vec3 *axis)
    {
        forEachCandidateAxis(a_, b_, [this](const Vec3 &u) { consider(u); });
        if (axis)
            *axis = bestAxis_;
        return best_;
    }

private:
    void consider(const Vec3 &u)
    {
        if (best_ > stopAbove_)
            return;
        const double length = u.norm();
        if (!(length > 0.0) || !std::isfinite(length))
            return;
        const Vec3 n = u / length;
        double loA, hiA, loB, hiB;
        projectOnto(a_.vertices, n, loA, hiA);
        projectOnto(b_.vertices, n, loB, hiB);
        if (loB - hiA >= loA - hiB)
        {
            if (loB - hiA > best_)
                best_ = loB - hiA, bestAxis_ = n;
        }
        else if (loA - hiB > best_)
            best_ = loA - hiB, bestAxis_ = -n;
    }

    const ConvexPiece &a_, &b_;
    double stopAbove_;
    double best_ = -std::numeric_limits<double>::infinity();
    Vec3 bestAxis_ = Vec3::UnitX();
};
}  // namespace

struct LpWorkspace::Lists : Workspace
{
};

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
    template LpSolution<D> solveSmallLp<D>(LpWorkspace &, const std::vector<Halfspace<D>> &,                         \
                                           const Eigen::Matrix<double, D, 1> &, const Eigen::Matrix<double, D, 1> &,   \
                                           const Eigen::Matrix<double, D, 1> &, double,                                 \
                                           const Eigen::Matrix<double, D, 1> *, std::uint64_t);
HYBRIDCD_INSTANTIATE_SMALL_LP(1)
HYBRIDCD_INSTANTIATE_SMALL_LP(2)
HYBRIDCD_INSTANTIATE_SMALL_LP(3)
HYBRIDCD_INSTANTIATE_SMALL_LP(4)
#undef HYBRIDCD_INSTANTIATE_SMALL_LP

IntersectionResult intersectConvexPieces(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace)
{
    double tolerance;
    const Frame frame = workingFrame(a, b, &tolerance);

    // Rows in the working frame: (n, 1) . (x', t') <= d', A's first, each scaled to a unit
    // normal as solveSmallLp does. The rows are staged by id behind the sorted copy the solver
    // permutes, so that the dual can look up its basis rows.
    Workspace &ws = workspace.lists();
    const std::size_t faces = a.normals.size() + b.normals.size();
    if (ws.rows4.size() < 2 * faces)
        ws.rows4.resize(2 * faces);
    if (ws.counts.size() < 2 * faces + 1)
        ws.counts.resize(2 * faces + 1);
    Row<4> *const staged = ws.rows4.data() + faces;  // the rows by id; sorted into the front
    int n = 0;
    const auto emit = [&](const Vec3 &unit, double d) {
        // (unit, 1) has length sqrt 2 up to rounding.
        constexpr double kInverseLength = 0.70710678118654752440;
        Row<4> &r = staged[n];
        r.a[0] = unit[0] * kInverseLength, r.a[1] = unit[1] * kInverseLength, r.a[2] = unit[2] * kInverseLength;
        r.a[3] = kInverseLength;
        r.b = d * kInverseLength;
        r.id = n;
        ++n;
    };
    forEachScaledPlane(a, frame, emit);
    const int rowsOfA = n;
    forEachScaledPlane(b, frame, emit);
    orderBySlack(staged, n, ws.rows4.data(), ws.counts);

    const double objective[4] = {0.0, 0.0, 0.0, 1.0};
    const double lower[4] = {-kBox, -kBox, -kBox, kSlackLow}, upper[4] = {kBox, kBox, kBox, kSlackHigh};
    struct
    {
        LpStatus status = LpStatus::Infeasible;
        double x[4];
        int basis[4];
    } lp;
    if (solveRows<4>(ws, n, objective, lower, upper, kLpTolerance, lp.x, lp.basis))
        lp.status = LpStatus::Optimal;

    IntersectionResult result;
    if (lp.status == LpStatus::Optimal)
    {
        result.witness = frame.center + frame.scale * Vec3(lp.x[0], lp.x[1], lp.x[2]);
        result.depth = -std::max(a.maxViolation(result.witness), b.maxViolation(result.witness));
        if (result.depth >= -kRoundingFraction * tolerance)
        {
            result.intersecting = true;
            result.certificate = IntersectionResult::Certificate::Witness;
            return result;
        }
        // Dual certificate: sum lambda_j (n_j, 1) = (0, 0, 0, 1) over the basis; the A part of
        // sum lambda_j n_j separates (see the header).
        const bool clearlyApart = result.depth < -tolerance;
        if (std::all_of(lp.basis, lp.basis + 4, [](int id) { return id >= 0; }))
        {
            Eigen::Matrix4d columns;
            for (int j = 0; j < 4; ++j)
            {
                // (n_j, 1) / sqrt 2: a common scale of the columns only scales lambda.
                const Row<4> &r = staged[lp.basis[j]];
                columns.col(j) << r.a[0], r.a[1], r.a[2], r.a[3];
            }
            const Eigen::Vector4d lambda = columns.fullPivLu().solve(Eigen::Vector4d::UnitW());
            Vec3 direction = Vec3::Zero();
            for (int j = 0; j < 4; ++j)
                direction +=
                    (lp.basis[j] < rowsOfA ? 1.0 : -1.0) * lambda[j] * columns.col(j).head<3>();
            if (lambda.allFinite() && separateAlong(direction, a, b, clearlyApart ? 0.0 : tolerance, result))
            {
                result.certificate = IntersectionResult::Certificate::LpDual;
                return result;
            }
        }
        if (!clearlyApart)
        {
            // The witness violates some inequality, but by no more than the tolerance. Near a
            // sharp edge or vertex that violation can be far smaller than the distance, so the
            // pieces count as touching only if no axis separates them by more than the tolerance
            // either (the reference test's criterion). Rare, so the axis search's cost is too.
            Vec3 axis;
            if (AxisSearch(a, b, tolerance).run(&axis) > tolerance && separateAlong(axis, a, b, tolerance, result))
            {
                result.certificate = IntersectionResult::Certificate::AxisSearch;
                return result;
            }
            result.intersecting = true;
            result.certificate = IntersectionResult::Certificate::Witness;
            return result;
        }
    }
    Vec3 axis;
    if (separatingAxisGap(a, b, &axis) > 0.0 && separateAlong(axis, a, b, 0.0, result))
    {
        result.certificate = IntersectionResult::Certificate::AxisSearch;
        return result;
    }
    result.intersecting = true;
    result.certificate = IntersectionResult::Certificate::Conservative;
    if (lp.status != LpStatus::Optimal)
        result.witness = frame.center;
    return result;
}

bool convexPiecesIntersectPrimal(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace)
{
    const Frame frame = workingFrame(a, b);
    std::vector<Halfspace<3>> &rows = workspace.lists().primalRows;
    rows.clear();
    const auto emit = [&](const Vec3 &n, double d) { rows.push_back({n, d}); };
    forEachScaledPlane(a, frame, emit);
    forEachScaledPlane(b, frame, emit);
    const LpSolution<3> lp = solveSmallLp<3>(workspace, rows, Vec3::Ones(), Vec3::Constant(-kBox), Vec3::Constant(kBox),
                                             pairTolerance(a, b) / frame.scale);
    return lp.status == LpStatus::Optimal;
}

double separatingAxisGap(const ConvexPiece &a, const ConvexPiece &b, Vec3 *axis)
{
    return AxisSearch(a, b, std::numeric_limits<double>::infinity()).run(axis);
}

bool convexPiecesIntersectSat(const ConvexPiece &a, const ConvexPiece &b)
{
    const double tolerance = pairTolerance(a, b);
    return AxisSearch(a, b, tolerance).run(nullptr) <= tolerance;
}
void appendWorkingFrameRows(std::vector<Halfspace<4>> &rows, const ConvexPiece &piece, const Vec3 &center, double scale,
                            const Vec3 &motion)
{
    for (std::size_t i = 0; i < piece.normals.size(); ++i)
    {
        const double norm = piece.normals[i].norm();
        if (!(norm > 0.0))
            continue;
        const Vec3 n = piece.normals[i] / norm;
        Halfspace<4> h;
        h.a << n, n.dot(motion);
        h.b = (piece.offsets[i] / norm - n.dot(center)) / scale;
        rows.push_back(h);
    }
}
}  // namespace hcd
