// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/ellipsoid.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <vector>

namespace hcd
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// Relative margin by which a separation must be certified before "disjoint" is reported.
constexpr double kContactMargin = 1e-9;

/// The Perram–Wertheim contact function F(l) = l(1-l) d^T M(l)^{-1} d, M(l) = (1-l) A^{-1} + l B^{-1},
/// with its first two derivatives, and the candidate normal M(l)^{-1} d.
struct ContactValue
{
    double f = 0.0, df = 0.0, d2f = 0.0;
    Vec3 normal = Vec3::Zero();
    bool ok = false;
};

/// `la`, `lb`: A^{-1} = la la^T, B^{-1} = lb lb^T (columns: semi-axis vectors). M(l) is never formed:
/// for thin ellipsoids (semi-axis ratios down to 1e-9, as fitted to flat sets) its small eigenvalues
/// would drown in the rounding of its large ones. Instead M = C C^T with the 6 x 3 matrix
/// C^T = [sqrt(1-l) la, sqrt(l) lb]^T, whose Householder QR with rows sorted by decreasing norm and
/// column pivoting is row-wise backward stable (Cox & Higham): the R factor represents M as well as
/// the semi-axes themselves do.
ContactValue contactFunction(const Mat3 &la, const Mat3 &lb, const Vec3 &d, double l)
{
    using Rows = Eigen::Matrix<double, 6, 3>;
    ContactValue value;
    Rows rows;
    rows.topRows<3>() = std::sqrt(1.0 - l) * la.transpose();
    rows.bottomRows<3>() = std::sqrt(l) * lb.transpose();
    std::array<int, 6> order{0, 1, 2, 3, 4, 5};
    std::array<double, 6> norms{};
    for (int i = 0; i < 6; ++i)
        norms[std::size_t(i)] = rows.row(i).squaredNorm();
    std::sort(order.begin(), order.end(), [&](int i, int j) { return norms[std::size_t(i)] > norms[std::size_t(j)]; });
    Rows sorted;
    for (int i = 0; i < 6; ++i)
        sorted.row(i) = rows.row(order[std::size_t(i)]);
    const Eigen::ColPivHouseholderQR<Rows> qr(sorted);
    const Mat3 r = qr.matrixR().topLeftCorner<3, 3>().triangularView<Eigen::Upper>();
    if (!(r.diagonal().cwiseAbs().minCoeff() > 0.0))
        return value;
    // M = P R^T R P^T, so d^T M^{-1} d = |R^{-T} P^T d|^2 and M^{-1} d = P R^{-1} R^{-T} P^T d.
    const auto &permutation = qr.colsPermutation();
    auto halfSolve = [&](const Vec3 &v) {
        return Vec3(r.transpose().triangularView<Eigen::Lower>().solve(permutation.transpose() * v));
    };
    const Vec3 y = halfSolve(d);
    const Vec3 x = permutation * Vec3(r.triangularView<Eigen::Upper>().solve(y));
    // dM/dl = B^{-1} - A^{-1}; g = d^T M^{-1} d, g' = -x^T M' x, g'' = 2 (M' x)^T M^{-1} (M' x).
    const Vec3 ax = la.transpose() * x, bx = lb.transpose() * x;
    const Vec3 mx = lb * bx - la * ax;
    const double g = y.squaredNorm();
    const double g1 = ax.squaredNorm() - bx.squaredNorm();
    const double g2 = 2.0 * halfSolve(mx).squaredNorm();
    const double w = l * (1.0 - l);
    value.f = w * g;
    value.df = (1.0 - 2.0 * l) * g + w * g1;
    value.d2f = -2.0 * g + 2.0 * (1.0 - 2.0 * l) * g1 + w * g2;
    value.normal = x;
    value.ok =
        std::isfinite(value.f) && std::isfinite(value.df) && std::isfinite(value.d2f) && x.allFinite() && g > 0.0;
    return value;
}

/// True when the plane with normal `n` provably separates a from b (d = cb - ca): n.d exceeds the sum of
/// the support radii by the relative margin plus a term covering the rounding of n.d.
bool separatedAlong(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &d, const Vec3 &n, double slack)
{
    const double gap = n.dot(d);
    const double reach = a.supportRadius(n) + b.supportRadius(n);
    return gap > reach * (1.0 + kContactMargin) + 1e-14 * n.norm() * d.norm() + slack * n.norm();
}

struct ContactSearch
{
    bool separated = false;  ///< a certified separating normal was found
    double bestValue = 0.0;  ///< largest F(l) evaluated
    Vec3 bestNormal = Vec3::Zero();
};

/// Maximises the concave F over [0, 1] by Newton's method safeguarded by bisection on the sign of F'.
/// With `decide` it stops as soon as the answer is known: at a certified separation, or when the tangent
/// at the current point bounds F below 1 on the remaining bracket (concavity), so the pair overlaps.
ContactSearch maximiseContact(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &d, bool decide, double slack = 0.0)
{
    ContactSearch search;
    const Mat3 la = a.axes * a.semiAxes.asDiagonal();
    const Mat3 lb = b.axes * b.semiAxes.asDiagonal();
    // For two balls the maximiser is ra / (ra + rb); the support radii along d play that part here.
    const double sa = a.supportRadius(d), sb = b.supportRadius(d);
    double l = (sa + sb > 0.0) ? sa / (sa + sb) : 0.5;
    l = std::clamp(l, 1e-6, 1.0 - 1e-6);
    double lo = 0.0, hi = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration)
    {
        const ContactValue value = contactFunction(la, lb, d, l);
        if (!value.ok)
        {
            // Only rounding makes M(l) look singular; retreat to the middle of the bracket.
            const double mid = 0.5 * (lo + hi);
            if (std::fabs(mid - l) <= 1e-16)
                break;
            l = mid;
            continue;
        }
        if (value.f > search.bestValue)
        {
            search.bestValue = value.f;
            search.bestNormal = value.normal;
        }
        if (value.f > 1.0 + kContactMargin && separatedAlong(a, b, d, value.normal, slack))
        {
            search.separated = true;
            search.bestValue = value.f;
            search.bestNormal = value.normal;
            if (decide)
                return search;
        }
        if (decide && !search.separated)
        {
            const double upper = value.f + std::max(value.df * (lo - l), value.df * (hi - l));
            if (upper < 1.0)
                return search;
        }
        if (value.df > 0.0)
            lo = l;
        else
            hi = l;
        double next = (value.d2f < 0.0) ? l - value.df / value.d2f : -1.0;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (hi - lo <= 1e-15 || std::fabs(next - l) <= 1e-15 * std::min(l, 1.0 - l))
            break;
        l = next;
    }
    return search;
}
}  // namespace

Ellipsoid Ellipsoid::fromShape(const Vec3 &center, const Mat3 &shape)
{
    const Mat3 symmetric = 0.5 * (shape + shape.transpose());
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
    Mat3 axes = solver.eigenvectors();
    if (axes.determinant() < 0.0)
        axes.col(2) = -axes.col(2);  // right-handed, for tidiness only
    Ellipsoid e;
    e.center = center;
    e.shape = symmetric;
    e.axes = axes;
    e.semiAxes = solver.eigenvalues().cwiseSqrt().cwiseInverse();
    return e;
}

Ellipsoid Ellipsoid::fromAxes(const Vec3 &center, const Mat3 &axes, const Vec3 &semiAxes)
{
    Ellipsoid e;
    e.center = center;
    e.axes = axes;
    e.semiAxes = semiAxes;
    const Mat3 shape = axes * semiAxes.cwiseAbs2().cwiseInverse().asDiagonal() * axes.transpose();
    e.shape = 0.5 * (shape + shape.transpose());
    return e;
}

double Ellipsoid::volume() const { return 4.0 / 3.0 * kPi * semiAxes.prod(); }

double Ellipsoid::normalizedRadiusSquared(const Vec3 &p) const
{
    return (axes.transpose() * (p - center)).cwiseQuotient(semiAxes).squaredNorm();
}

Ellipsoid Ellipsoid::transformed(const RigidTransform &pose) const
{
    Ellipsoid e;
    e.center = pose.apply(center);
    e.axes = pose.rotation * axes;
    e.semiAxes = semiAxes;
    const Mat3 shapeWorld = pose.rotation * shape * pose.rotation.transpose();
    e.shape = 0.5 * (shapeWorld + shapeWorld.transpose());
    return e;
}

Mat3 Ellipsoid::inverseShape() const
{
    const Mat3 inverse = axes * semiAxes.cwiseAbs2().asDiagonal() * axes.transpose();
    return 0.5 * (inverse + inverse.transpose());
}

namespace
{
/// A fixed order on ellipsoids, so that the overlap test gives the same answer for (a, b) and (b, a)
/// even for pairs within its rounding margin.
bool comesFirst(const Ellipsoid &a, const Ellipsoid &b)
{
    for (int i = 0; i < 3; ++i)
        if (a.center[i] != b.center[i])
            return a.center[i] < b.center[i];
    for (int i = 0; i < 3; ++i)
        if (a.semiAxes[i] != b.semiAxes[i])
            return a.semiAxes[i] < b.semiAxes[i];
    for (int i = 0; i < 9; ++i)
        if (a.axes(i) != b.axes(i))
            return a.axes(i) < b.axes(i);
    return true;
}
}  // namespace

bool ellipsoidsOverlap(const Ellipsoid &first, const Ellipsoid &second, double slack)
{
    const bool inOrder = comesFirst(first, second);
    const Ellipsoid &a = inOrder ? first : second;
    const Ellipsoid &b = inOrder ? second : first;
    const Vec3 d = b.center - a.center;
    const double distance = d.norm();
    // Each ellipsoid lies in the ball of its largest semi-axis about its centre.
    if (distance > (a.boundingRadius() + b.boundingRadius()) * (1.0 + kContactMargin) + 1e-14 * distance + slack)
        return false;
    if (a.contains(b.center) || b.contains(a.center))
        return true;
    return !maximiseContact(a, b, d, true, slack).separated;
}

double ellipsoidDistance(const Ellipsoid &a, const Ellipsoid &b)
{
    if (ellipsoidsOverlap(a, b))
        return 0.0;
    const Vec3 d = b.center - a.center;
    const Mat3 aInverse = a.inverseShape();
    const Mat3 bInverse = b.inverseShape();

    // For a unit normal u, u.d - h_a(u) - h_b(-u) is the width of the slab between the two supporting
    // planes: a lower bound on the distance, equal to it at the best u (duality for convex sets).
    double best = -std::numeric_limits<double>::infinity();
    Vec3 bestNormal = d.normalized();
    auto slab = [&](const Vec3 &u) { return u.dot(d) - a.supportRadius(u) - b.supportRadius(u); };
    auto consider = [&](const Vec3 &n) {
        const double length = n.norm();
        if (!(length > 0.0) || !n.allFinite())
            return;
        const Vec3 u = n / length;
        const double value = slab(u);
        if (value > best)
        {
            best = value;
            bestNormal = u;
        }
    };
    consider(d);
    const ContactSearch contact = maximiseContact(a, b, d, false);
    consider(contact.bestNormal);

    // Refine over the sphere, parametrised by two tangent coordinates at the current best normal.
    for (int round = 0; round < 2; ++round)
    {
        const Vec3 u0 = bestNormal;
        Eigen::Matrix<double, 3, 2> tangent;
        const Vec3 helper = (std::fabs(u0.x()) < 0.9) ? Vec3::UnitX() : Vec3::UnitY();
        tangent.col(0) = u0.cross(helper).normalized();
        tangent.col(1) = u0.cross(tangent.col(0));
        const double before = best;

        auto objective = [&](const std::vector<double> &theta, std::vector<double> &gradient) -> double {
            const Vec3 w = u0 + tangent * Eigen::Vector2d(theta[0], theta[1]);
            const double length = w.norm();
            const Vec3 u = w / length;
            const double ha = a.supportRadius(u), hb = b.supportRadius(u);
            const double value = u.dot(d) - ha - hb;
            if (value > best && u.allFinite())
            {
                best = value;
                bestNormal = u;
            }
            if (!gradient.empty())
            {
                Vec3 g = d;
                if (ha > 0.0)
                    g -= aInverse * u / ha;
                if (hb > 0.0)
                    g -= bInverse * u / hb;
                const Vec3 projected = (g - u * u.dot(g)) / length;
                const Eigen::Vector2d gt = tangent.transpose() * projected;
                gradient[0] = gt[0];
                gradient[1] = gt[1];
            }
            return value;
        };
        using Objective = decltype(objective);
        nlopt::opt optimiser(nlopt::LD_LBFGS, 2);
        optimiser.set_max_objective(
            [](unsigned n, const double *x, double *grad, void *data) -> double {
                std::vector<double> theta(x, x + n);
                std::vector<double> gradient(grad ? n : 0);
                const double value = (*static_cast<Objective *>(data))(theta, gradient);
                if (grad)
                    std::copy(gradient.begin(), gradient.end(), grad);
                return value;
            },
            &objective);
        optimiser.set_xtol_abs(1e-13);
        optimiser.set_ftol_rel(1e-15);
        optimiser.set_maxeval(200);
        std::vector<double> theta{0.0, 0.0};
        double value = 0.0;
        try
        {
            optimiser.optimize(theta, value);
        }
        catch (const std::exception &)
        {
            // Roundoff-limited stops are expected near the optimum; the best point seen is kept.
        }
        if (!(best > before))
            break;
    }
    // Rounding in the slab width is a few ulps of |d| and the support radii.
    const double rounding = 1e-14 * (d.norm() + a.boundingRadius() + b.boundingRadius());
    return std::max(0.0, best - rounding);
}
}  // namespace hcd
