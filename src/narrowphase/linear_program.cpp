// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/linear_program.h"

#include "hybridcd/narrowphase/candidate_axes.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace hcd
{
namespace
{
template <int K>
using VecK = Eigen::Matrix<double, K, 1>;

// A constraint a . x <= b of a (sub)problem, with the index of the input constraint (or box
// bound) it came from, so that the optimum's basis can be reported.
template <int K>
struct Row
{
    VecK<K> a;
    double b;
    int id;
};

template <int K>
struct Box
{
    VecK<K> lo, hi;
    std::array<int, K> loId, hiId;
};

// A substituted constraint whose coefficients all fall below this (the input rows have unit
// normals and substitution never more than doubles a coefficient) is parallel to the current
// flat: within the box its left side is below ~1e-13, so it is checked as the constant 0 <= b.
constexpr double kConstant = 1e-14;

// One scratch list per dimension and thread: the level-K step writes the rows of its (K-1)-D
// subproblem into scratch<K-1>() while reading its own from scratch<K>(), so no two live
// subproblems share a list and nothing is allocated once the lists have grown.
template <int K>
std::vector<Row<K>> &scratch()
{
    thread_local std::vector<Row<K>> rows;
    return rows;
}

template <int K>
VecK<K - 1> drop(const VecK<K> &v, int k)
{
    VecK<K - 1> r;
    for (int j = 0, m = 0; j < K; ++j)
        if (j != k)
            r[m++] = v[j];
    return r;
}

template <int K>
VecK<K> lift(const VecK<K - 1> &y, int k, double xk)
{
    VecK<K> x;
    for (int j = 0, m = 0; j < K; ++j)
        x[j] = j == k ? xk : y[m++];
    return x;
}

// The feasible interval of one variable, narrowed one constraint a y <= b at a time; the ends
// remember which constraint made them, and their coefficient, to judge crossed ends.
class Interval
{
public:
    Interval(double lo, double hi, int loId, int hiId) : lo_(lo), hi_(hi), loId_(loId), hiId_(hiId) {}

    // False when the constraint is (numerically) a constant 0 <= b that fails.
    bool add(double a, double b, int id, double eps)
    {
        // Compare before dividing: most constraints do not move an end.
        if (a > kConstant)
        {
            if (b < hi_ * a)
                hi_ = b / a, hiId_ = id, weightHi_ = a;
        }
        else if (a < -kConstant)
        {
            if (b < lo_ * a)
                lo_ = b / a, loId_ = id, weightLo_ = -a;
        }
        else if (b < -eps)
            return false;
        return true;
    }

    // The end the objective coefficient points to (the upper one when it is zero).
    bool optimum(double c, double eps, double &y, int &id) const
    {
        if (lo_ > hi_)
        {
            // Crossed ends may still be feasible within the tolerance, which is measured in the
            // constraints' own units: take the point where both violations are equal.
            y = (weightHi_ * hi_ + weightLo_ * lo_) / (weightHi_ + weightLo_);
            if (!(weightHi_ * (y - hi_) <= eps))
                return false;
        }
        else
            y = c >= 0.0 ? hi_ : lo_;
        id = c >= 0.0 ? hiId_ : loId_;
        return true;
    }

private:
    double lo_, hi_, weightLo_ = 1.0, weightHi_ = 1.0;
    int loId_, hiId_;
};

// Start of every level: the box corner the objective points to.
template <int K>
void boxCorner(const VecK<K> &c, const Box<K> &box, VecK<K> &x, std::array<int, K> &basis)
{
    for (int j = 0; j < K; ++j)
    {
        const bool up = c[j] > 0.0;
        x[j] = up ? box.hi[j] : box.lo[j];
        basis[j] = up ? box.hiId[j] : box.loId[j];
    }
}

template <int K>
bool seidel(const Row<K> *rows, int n, const VecK<K> &c, const Box<K> &box, double eps, VecK<K> &x,
            std::array<int, K> &basis);

template <>
bool seidel<1>(const Row<1> *rows, int n, const VecK<1> &c, const Box<1> &box, double eps, VecK<1> &x,
               std::array<int, 1> &basis)
{
    Interval interval(box.lo[0], box.hi[0], box.loId[0], box.hiId[0]);
    for (int i = 0; i < n; ++i)
        if (!interval.add(rows[i].a[0], rows[i].b, rows[i].id, eps))
            return false;
    return interval.optimum(c[0], eps, x[0], basis[0]);
}

// Two dimensions, with the one-dimensional subproblem done in place (it is where most of the
// work happens, so its rows are never written out).
template <>
bool seidel<2>(const Row<2> *rows, int n, const VecK<2> &c, const Box<2> &box, double eps, VecK<2> &x,
               std::array<int, 2> &basis)
{
    boxCorner<2>(c, box, x, basis);
    for (int i = 0; i < n; ++i)
    {
        const Row<2> &h = rows[i];
        if (h.a.dot(x) - h.b <= eps)
            continue;
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
        for (int m = 0; m < i; ++m)
        {
            const Row<2> &r = rows[m];
            if (!interval.add(r.a[j] + r.a[k] * g, r.b - r.a[k] * q, r.id, eps))
                return false;
        }
        double y;
        int id;
        if (!interval.optimum(c[j] + c[k] * g, eps, y, id))
            return false;
        x[j] = y;
        x[k] = q + g * y;
        basis = {h.id, id};
    }
    return true;
}

template <int K>
bool seidel(const Row<K> *rows, int n, const VecK<K> &c, const Box<K> &box, double eps, VecK<K> &x,
            std::array<int, K> &basis)
{
    boxCorner<K>(c, box, x, basis);
    std::vector<Row<K - 1>> &sub = scratch<K - 1>();
    if (sub.size() < std::size_t(n) + 2)
        sub.resize(std::size_t(n) + 2);
    for (int i = 0; i < n; ++i)
    {
        const Row<K> &h = rows[i];
        if (h.a.dot(x) - h.b <= eps)
            continue;
        int k = 0;
        const double pivot = h.a.cwiseAbs().maxCoeff(&k);
        if (pivot <= kConstant)
        {
            if (h.b < -eps)
                return false;
            continue;
        }
        // On the hyperplane, x_k = q + g . y over the other coordinates y. Pivoting on the
        // largest coefficient keeps |g_j| <= 1.
        const double inverse = 1.0 / h.a[k];
        const VecK<K - 1> g = -drop<K>(h.a, k) * inverse;
        const double q = h.b * inverse;

        int kept[K - 1];  // the coordinates other than k
        for (int j = 0, m = 0; j < K; ++j)
            if (j != k)
                kept[m++] = j;
        Row<K - 1> *out = sub.data();
        out[0] = {g, box.hi[k] - q, box.hiId[k]};   // x_k <= hi_k
        out[1] = {-g, q - box.lo[k], box.loId[k]};  // x_k >= lo_k
        for (int j = 0; j < i; ++j)
        {
            const Row<K> &r = rows[j];
            Row<K - 1> &o = out[j + 2];
            for (int m = 0; m < K - 1; ++m)
                o.a[m] = r.a[kept[m]] + r.a[k] * g[m];
            o.b = r.b - r.a[k] * q;
            o.id = r.id;
        }
        Box<K - 1> subBox;
        subBox.lo = drop<K>(box.lo, k);
        subBox.hi = drop<K>(box.hi, k);
        for (int j = 0, m = 0; j < K; ++j)
            if (j != k)
                subBox.loId[m] = box.loId[j], subBox.hiId[m++] = box.hiId[j];
        const VecK<K - 1> subObjective = drop<K>(c, k) + c[k] * g;

        VecK<K - 1> y;
        std::array<int, K - 1> subBasis;
        if (!seidel<K - 1>(out, i + 2, subObjective, subBox, eps, y, subBasis))
            return false;
        x = lift<K>(y, k, q + g.dot(y));
        basis[0] = h.id;
        std::copy(subBasis.begin(), subBasis.end(), basis.begin() + 1);
    }
    return true;
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

Frame workingFrame(const ConvexPiece &a, const ConvexPiece &b)
{
    Frame f{0.5 * (a.centroid + b.centroid), 0.0};
    for (const ConvexPiece *p : {&a, &b})
        for (const Vec3 &v : p->vertices)
            f.scale = std::max(f.scale, (v - f.center).cwiseAbs().maxCoeff());
    if (!(f.scale > 0.0))  // both pieces one and the same point
        f.scale = std::max(1.0, std::max(a.magnitude(), b.magnitude()));
    return f;
}

// n . x <= d in working coordinates, with n made unit: n . x' <= (d - n . center) / scale.
template <typename Emit>
void forEachScaledPlane(const ConvexPiece &p, const Frame &f, Emit emit)
{
    for (std::size_t i = 0; i < p.normals.size(); ++i)
    {
        const double length = p.normals[i].norm();
        if (!(length > 0.0))
            continue;
        const Vec3 n = p.normals[i] / length;
        emit(n, (p.offsets[i] / length - n.dot(f.center)) / f.scale);
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
    static void project(const std::vector<Vec3> &points, const Vec3 &n, double &lo, double &hi)
    {
        lo = std::numeric_limits<double>::infinity();
        hi = -lo;
        for (const Vec3 &p : points)
        {
            const double s = n.dot(p);
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
    }

    void consider(const Vec3 &u)
    {
        if (best_ > stopAbove_)
            return;
        const double length = u.norm();
        if (!(length > 0.0) || !std::isfinite(length))
            return;
        const Vec3 n = u / length;
        double loA, hiA, loB, hiB;
        project(a_.vertices, n, loA, hiA);
        project(b_.vertices, n, loB, hiB);
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

template <int D>
LpSolution<D> solveSmallLp(const std::vector<Halfspace<D>> &constraints, const Eigen::Matrix<double, D, 1> &objective,
                           const Eigen::Matrix<double, D, 1> &lower, const Eigen::Matrix<double, D, 1> &upper,
                           double tolerance, const Eigen::Matrix<double, D, 1> *orderHint, std::uint64_t seed)
{
    LpSolution<D> solution;
    if (!((lower.array() <= upper.array() + tolerance).all()))
        return solution;
    std::vector<Row<D>> &rows = scratch<D>();
    rows.clear();
    for (std::size_t i = 0; i < constraints.size(); ++i)
    {
        const double length = constraints[i].a.norm();
        if (!(length > 0.0))
        {
            if (!(constraints[i].b >= -tolerance))
                return solution;
            continue;
        }
        rows.push_back({constraints[i].a / length, constraints[i].b / length, int(i)});
    }
    if (orderHint)
    {
        // Most of Seidel's work is done when late constraints are violated; taking first the
        // constraints tightest at a point near the optimum makes that rare (five to eight times
        // fewer subproblem rows on convex pieces). Ties go by index.
        thread_local std::vector<std::pair<double, int>> keys;
        thread_local std::vector<Row<D>> unsorted;
        keys.clear();
        for (std::size_t i = 0; i < rows.size(); ++i)
            keys.emplace_back(rows[i].b - rows[i].a.dot(*orderHint), int(i));
        std::sort(keys.begin(), keys.end());
        unsorted.assign(rows.begin(), rows.end());
        for (std::size_t i = 0; i < rows.size(); ++i)
            rows[i] = unsorted[std::size_t(keys[i].second)];
    }
    else
    {
        // Seeded Fisher-Yates shuffle: Seidel's expected bound needs a random order, the tests
        // and the planner need reproducible answers.
        std::uint64_t state = seed;
        for (std::size_t i = rows.size(); i > 1; --i)
            std::swap(rows[i - 1], rows[splitMix64(state) % i]);
    }

    Box<D> box;
    box.lo = lower;
    box.hi = upper;
    for (int j = 0; j < D; ++j)
        box.loId[j] = lpLowerBoundId(j), box.hiId[j] = lpUpperBoundId(j);
    if (seidel<D>(rows.data(), int(rows.size()), objective, box, tolerance, solution.x, solution.basis))
        solution.status = LpStatus::Optimal;
    return solution;
}

#define HYBRIDCD_INSTANTIATE_SMALL_LP(D)                                                                               \
    template LpSolution<D> solveSmallLp<D>(const std::vector<Halfspace<D>> &, const Eigen::Matrix<double, D, 1> &,     \
                                           const Eigen::Matrix<double, D, 1> &, const Eigen::Matrix<double, D, 1> &,   \
                                           double, const Eigen::Matrix<double, D, 1> *, std::uint64_t);
HYBRIDCD_INSTANTIATE_SMALL_LP(1)
HYBRIDCD_INSTANTIATE_SMALL_LP(2)
HYBRIDCD_INSTANTIATE_SMALL_LP(3)
HYBRIDCD_INSTANTIATE_SMALL_LP(4)
#undef HYBRIDCD_INSTANTIATE_SMALL_LP

IntersectionResult intersectConvexPieces(const ConvexPiece &a, const ConvexPiece &b)
{
    const double tolerance = pairTolerance(a, b);
    const Frame frame = workingFrame(a, b);

    // Rows in the working frame: (n, 1) . (x', t') <= d', A's first.
    thread_local std::vector<Halfspace<4>> rows;
    rows.clear();
    const auto emit = [&](const Vec3 &n, double d) {
        Halfspace<4> h;
        h.a << n, 1.0;
        h.b = d;
        rows.push_back(h);
    };
    forEachScaledPlane(a, frame, emit);
    const int rowsOfA = int(rows.size());
    forEachScaledPlane(b, frame, emit);

    const Eigen::Vector4d objective(0.0, 0.0, 0.0, 1.0);
    const Eigen::Vector4d lower(-kBox, -kBox, -kBox, kSlackLow), upper(kBox, kBox, kBox, kSlackHigh);
    // Ordering hint: the working frame's origin (between the centroids) with zero slack.
    const Eigen::Vector4d hint = Eigen::Vector4d::Zero();
    const LpSolution<4> lp = solveSmallLp<4>(rows, objective, lower, upper, kLpTolerance, &hint);

    IntersectionResult result;
    if (lp.status == LpStatus::Optimal)
    {
        result.witness = frame.center + frame.scale * lp.x.head<3>();
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
        if (std::all_of(lp.basis.begin(), lp.basis.end(), [](int id) { return id >= 0; }))
        {
            Eigen::Matrix4d columns;
            for (int j = 0; j < 4; ++j)
                columns.col(j) = rows[std::size_t(lp.basis[j])].a;
            const Eigen::Vector4d lambda = columns.fullPivLu().solve(objective);
            Vec3 direction = Vec3::Zero();
            for (int j = 0; j < 4; ++j)
                direction +=
                    (lp.basis[j] < rowsOfA ? 1.0 : -1.0) * lambda[j] * rows[std::size_t(lp.basis[j])].a.head<3>();
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

bool convexPiecesIntersectPrimal(const ConvexPiece &a, const ConvexPiece &b)
{
    const Frame frame = workingFrame(a, b);
    thread_local std::vector<Halfspace<3>> rows;
    rows.clear();
    const auto emit = [&](const Vec3 &n, double d) { rows.push_back({n, d}); };
    forEachScaledPlane(a, frame, emit);
    forEachScaledPlane(b, frame, emit);
    const LpSolution<3> lp = solveSmallLp<3>(rows, Vec3::Ones(), Vec3::Constant(-kBox), Vec3::Constant(kBox),
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
}  // namespace hcd
