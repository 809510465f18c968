// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/minimum_volume_ellipsoid.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <type_traits>

// Qhull's reentrant C API; its macros (True, False, FORALLvertices, ...) stay confined to this file.
extern "C"
{
#include <libqhull_r/qhull_ra.h>
}

namespace hcd
{
namespace
{
/// A principal direction whose width is below this fraction of the largest width is treated as missing:
/// the set is fitted in its affine hull instead (whitening such a direction would amplify rounding noise).
constexpr double kFlatRatio = 1e-9;
/// Half-thickness given to missing directions, relative to the set's extent.
constexpr double kThickness = 1e-9;
/// Radius of the ball around a single point.
constexpr double kPointRadius = 1e-12;

#ifdef _WIN32
constexpr const char *kNullDevice = "NUL";
#else
constexpr const char *kNullDevice = "/dev/null";
#endif

/// Indices of the convex-hull vertices of `count` points of dimension `dim` stored one after another in
/// `coords`, by Qhull; empty when Qhull fails (e.g. for degenerate input), in which case callers use all
/// points. Qhull's messages go to the null device: a failure here is expected and handled.
std::vector<int> hullVertices(std::vector<double> coords, int dim)
{
    const int count = int(coords.size() / std::size_t(dim));
    std::vector<int> ids;
    FILE *sink = std::fopen(kNullDevice, "w");
    FILE *errors = sink ? sink : stderr;
    qhT storage;
    qhT *qh = &storage;
    QHULL_LIB_CHECK
    qh_zero(qh, errors);
    char command[] = "qhull";
    const int exitCode = qh_new_qhull(qh, dim, count, coords.data(), False, command, nullptr, errors);
    if (exitCode == 0)
    {
        vertexT *vertex;
        FORALLvertices
        {
            const int id = qh_pointid(qh, vertex->point);
            if (id >= 0 && id < count)
                ids.push_back(id);
        }
    }
    qh_freeqhull(qh, !qh_ALL);
    int currentLong = 0, totalLong = 0;
    qh_memfreeshort(qh, &currentLong, &totalLong);
    if (sink)
        std::fclose(sink);
    return ids;
}

/// Outcome of the first-order method in K whitened dimensions.
template <int K>
struct DesignFit
{
    Eigen::Matrix<double, K, 1> center;      ///< weighted mean c of the design
    Eigen::Matrix<double, K, K> covariance;  ///< weighted covariance S of the design
    double maxValue = 0.0;                   ///< max over all points of (y - c)^T S^{-1} (y - c)
    int iterations = 0;
    std::size_t removed = 0;
};

/// WA-TY (Todd–Yildirim with Kumar–Yildirim initialisation and away steps) on the lifted points
/// q = (y, 1), i.e. the D-optimal design problem max log det sum_i u_i q_i q_i^T over the simplex, with
/// Harman–Pronzato elimination of points that cannot support the optimum. `active` lists the candidates.
/// Afterwards every point (not only the candidates) is checked, and violators rejoin the iteration, so
/// an imprecise hull or an elimination spoilt by rounding cannot spoil the certificate.
template <int K>
DesignFit<K> fitDesign(const std::vector<Eigen::Matrix<double, K, 1>> &y, std::vector<int> active,
                       const MveeOptions &options)
{
    constexpr int N = K + 1;
    using VecK = Eigen::Matrix<double, K, 1>;
    using MatK = Eigen::Matrix<double, K, K>;
    using VecN = Eigen::Matrix<double, N, 1>;
    using MatN = Eigen::Matrix<double, N, N>;

    const std::size_t total = y.size();
    const double tolerance = std::max(options.tolerance, 1e-14);
    auto lift = [&](int i) {
        VecN q;
        q << y[std::size_t(i)], 1.0;
        return q;
    };

    std::vector<double> weight(total, 0.0);
    std::vector<char> isActive(total, 0);
    for (int i : active)
        isActive[std::size_t(i)] = 1;

    auto uniformWeights = [&] {
        std::fill(weight.begin(), weight.end(), 0.0);
        for (int i : active)
            weight[std::size_t(i)] = 1.0 / double(active.size());
    };

    // Kumar–Yildirim: extreme points along K mutually orthogonal directions, each new direction
    // orthogonal to the spans found so far; uniform weights on those <= 2K points span the hull.
    {
        std::vector<VecK> basis;
        std::vector<int> core;
        for (int j = 0; j < K; ++j)
        {
            VecK direction = VecK::Zero();
            double bestResidual = -1.0;
            for (int e = 0; e < K; ++e)
            {
                VecK candidate = VecK::Unit(e);
                for (const VecK &b : basis)
                    candidate -= b * b.dot(candidate);
                if (candidate.norm() > bestResidual)
                {
                    bestResidual = candidate.norm();
                    direction = candidate.normalized();
                }
            }
            int hi = active.front(), lo = active.front();
            for (int i : active)
            {
                if (direction.dot(y[std::size_t(i)]) > direction.dot(y[std::size_t(hi)]))
                    hi = i;
                if (direction.dot(y[std::size_t(i)]) < direction.dot(y[std::size_t(lo)]))
                    lo = i;
            }
            core.push_back(hi);
            core.push_back(lo);
            VecK span = y[std::size_t(hi)] - y[std::size_t(lo)];
            for (const VecK &b : basis)
                span -= b * b.dot(span);
            if (span.norm() > 0.0)
                basis.push_back(span.normalized());
        }
        std::sort(core.begin(), core.end());
        core.erase(std::unique(core.begin(), core.end()), core.end());
        for (int i : core)
            weight[std::size_t(i)] = 1.0 / double(core.size());
    }

    // X(u)^{-1} from scratch each step: N <= 4, so this costs no more than the omegas and never drifts.
    auto invertDesign = [&](MatN &inverse) {
        MatN x = MatN::Zero();
        for (int i : active)
            if (weight[std::size_t(i)] > 0.0)
            {
                const VecN q = lift(i);
                x.noalias() += weight[std::size_t(i)] * q * q.transpose();
            }
        const Eigen::LLT<MatN> llt(x);
        if (llt.info() != Eigen::Success)
            return false;
        inverse = llt.solve(MatN::Identity());
        return inverse.allFinite();
    };

    DesignFit<K> fit;
    std::vector<double> omega;
    MatN inverse;
    for (int round = 0;; ++round)
    {
        while (true)
        {
            if (!invertDesign(inverse))
            {
                uniformWeights();  // the active set always spans, so uniform weights are nonsingular
                if (!invertDesign(inverse))
                    break;
            }
            // omega_i = q_i^T X^{-1} q_i = 1 + (y_i - c)^T S^{-1} (y_i - c).
            omega.resize(active.size());
            std::size_t plus = 0, minus = active.size();
            for (std::size_t a = 0; a < active.size(); ++a)
            {
                const VecN q = lift(active[a]);
                omega[a] = q.dot(inverse * q);
                if (omega[a] > omega[plus])
                    plus = a;
                if (weight[std::size_t(active[a])] > 0.0 && (minus == active.size() || omega[a] < omega[minus]))
                    minus = a;
            }
            const double omegaPlus = omega[plus];
            if ((omegaPlus - 1.0) / K - 1.0 <= tolerance || fit.iterations >= options.maxIterations)
                break;

            if (options.cardinalityReduction)
            {
                // Harman & Pronzato (2007): with max_i omega_i = N + eps, no point with
                // omega_i < N (1 + eps/2 - sqrt(eps (4 + eps - 4/N)) / 2) supports a D-optimal design.
                const double eps = std::max(0.0, omegaPlus - N);
                const double bound = N * (1.0 + eps / 2.0 - std::sqrt(eps * (4.0 + eps - 4.0 / N)) / 2.0);
                const double threshold = bound - 1e-9 * N;  // keep points that only rounding would remove
                bool reweigh = false;
                std::size_t kept = 0;
                for (std::size_t a = 0; a < active.size(); ++a)
                {
                    const int i = active[a];
                    if (omega[a] < threshold)
                    {
                        isActive[std::size_t(i)] = 0;
                        reweigh = reweigh || weight[std::size_t(i)] > 0.0;
                        weight[std::size_t(i)] = 0.0;
                        ++fit.removed;
                        continue;
                    }
                    if (a == plus)
                        plus = kept;
                    if (a == minus)
                        minus = kept;
                    omega[kept] = omega[a];
                    active[kept++] = i;
                }
                active.resize(kept);
                omega.resize(kept);
                if (reweigh)
                {
                    double sum = 0.0;
                    for (int i : active)
                        sum += weight[std::size_t(i)];
                    if (sum > 1e-12)
                        for (int i : active)
                            weight[std::size_t(i)] /= sum;
                    else
                        uniformWeights();
                    continue;  // the design changed: recompute X^{-1} and the omegas
                }
            }

            // Frank–Wolfe step towards the most violated point, or away step from the weighted point
            // with the smallest omega, whichever is further from optimality (Todd–Yildirim).
            const double epsPlus = omegaPlus / N - 1.0;
            const double epsMinus = (minus < active.size()) ? 1.0 - omega[minus] / N : 0.0;
            std::size_t j = plus;
            double step = (omegaPlus - N) / (N * (omegaPlus - 1.0));
            bool drop = false;
            if (epsMinus > epsPlus)
            {
                j = minus;
                const double wj = weight[std::size_t(active[j])];
                step = (omega[j] - N) / (N * (omega[j] - 1.0));
                if (wj >= 1.0)
                    break;  // a single weighted point cannot happen for a spanning design
                if (step <= -wj / (1.0 - wj))
                {
                    step = -wj / (1.0 - wj);  // a drop step: the point leaves the support
                    drop = true;
                }
            }
            for (int i : active)
                weight[std::size_t(i)] *= 1.0 - step;
            double &wj = weight[std::size_t(active[j])];
            wj = drop ? 0.0 : std::max(0.0, wj + step);
            ++fit.iterations;
        }

        // Final design statistics, and every point's value against them.
        VecK center = VecK::Zero();
        for (int i : active)
            center += weight[std::size_t(i)] * y[std::size_t(i)];
        MatK covariance = MatK::Zero();
        for (int i : active)
            if (weight[std::size_t(i)] > 0.0)
            {
                const VecK r = y[std::size_t(i)] - center;
                covariance.noalias() += weight[std::size_t(i)] * r * r.transpose();
            }
        fit.center = center;
        fit.covariance = covariance;
        const Eigen::LLT<MatK> llt(covariance);
        fit.maxValue = 0.0;
        std::vector<int> violators;
        for (std::size_t i = 0; i < total; ++i)
        {
            const double value = llt.matrixL().solve(VecK(y[i] - center)).squaredNorm();
            fit.maxValue = std::max(fit.maxValue, value);
            if (!isActive[i] && value / K - 1.0 > tolerance)
                violators.push_back(int(i));
        }
        if (violators.empty() || fit.iterations >= options.maxIterations || round >= 8)
            break;
        for (int i : violators)
        {
            isActive[std::size_t(i)] = 1;
            active.push_back(i);
        }
    }
    return fit;
}

/// The K-dimensional fit of whitened points y, returned as c + G z (|z| <= 1) in whitened coordinates:
/// G G^T = maxValue * S, so that every point is inside.
template <int K>
DesignFit<K> fitWhitened(const std::vector<Eigen::Matrix<double, K, 1>> &y, const MveeOptions &options,
                         std::size_t &candidateCount)
{
    std::vector<int> candidates;
    if (options.useHullCandidates && y.size() > std::size_t(K + 1))
    {
        std::vector<double> coords;
        coords.reserve(y.size() * K);
        for (const auto &p : y)
            for (int j = 0; j < K; ++j)
                coords.push_back(p[j]);
        candidates = hullVertices(std::move(coords), K);
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        if (candidates.size() < std::size_t(K + 1))
            candidates.clear();
    }
    if (candidates.empty())
    {
        candidates.resize(y.size());
        for (std::size_t i = 0; i < y.size(); ++i)
            candidates[i] = int(i);
    }
    candidateCount = candidates.size();
    using MatK = Eigen::Matrix<double, K, K>;
    auto usable = [](const DesignFit<K> &fit) {
        return fit.center.allFinite() && fit.covariance.allFinite() &&
               Eigen::LLT<MatK>(fit.covariance).info() == Eigen::Success && std::isfinite(fit.maxValue) &&
               fit.maxValue > 0.0;
    };
    DesignFit<K> fit = fitDesign<K>(y, std::move(candidates), options);
    if (usable(fit))
        return fit;
    // Only rounding could get here (the points span R^K): retry plainly on all points, and failing
    // that take uniform weights, whose ellipsoid is valid though far from minimal.
    MveeOptions plain = options;
    plain.cardinalityReduction = false;
    std::vector<int> all(y.size());
    for (std::size_t i = 0; i < y.size(); ++i)
        all[i] = int(i);
    fit = fitDesign<K>(y, all, plain);
    if (usable(fit))
        return fit;
    fit.center.setZero();
    for (const auto &p : y)
        fit.center += p / double(y.size());
    fit.covariance.setZero();
    for (const auto &p : y)
        fit.covariance += (p - fit.center) * (p - fit.center).transpose() / double(y.size());
    const Eigen::LLT<MatK> llt(fit.covariance);
    fit.maxValue = 0.0;
    for (const auto &p : y)
        fit.maxValue =
            std::max(fit.maxValue, llt.matrixL().solve(Eigen::Matrix<double, K, 1>(p - fit.center)).squaredNorm());
    return fit;
}
}  // namespace

MveeResult fitMinimumVolumeEllipsoid(const std::vector<Vec3> &points, const MveeOptions &options)
{
    if (points.empty())
        throw std::invalid_argument("fitMinimumVolumeEllipsoid: no points");
    for (const Vec3 &p : points)
        if (!p.allFinite())
            throw std::invalid_argument("fitMinimumVolumeEllipsoid: non-finite coordinate");
    if (points.size() > std::size_t(std::numeric_limits<int>::max()))
        throw std::invalid_argument("fitMinimumVolumeEllipsoid: too many points");

    const std::size_t count = points.size();
    const Vec3 origin = points.front();
    MveeResult result;
    result.candidates = count;

    // The affine hull: an SVD of the offsets from the first point (an input point, so that no rounded
    // mean can lift a flat set off its plane), and the widths of the set along its singular vectors.
    Eigen::MatrixX3d offsets(Eigen::Index(count), 3);
    for (std::size_t i = 0; i < count; ++i)
        offsets.row(Eigen::Index(i)) = (points[i] - origin).transpose();
    const double magnitude = offsets.cwiseAbs().maxCoeff();
    Mat3 hullFrame = Mat3::Identity();
    if (magnitude > 0.0)
        hullFrame = Eigen::JacobiSVD<Eigen::MatrixX3d>(offsets / magnitude, Eigen::ComputeFullV).matrixV();
    Vec3 width = Vec3::Zero();
    {
        const Eigen::MatrixX3d local = offsets * hullFrame;
        width = local.colwise().maxCoeff() - local.colwise().minCoeff();
    }
    const double extent = width.maxCoeff();

    // Kept directions first; their count is the dimension of the (numerical) affine hull.
    int order[3] = {0, 1, 2};
    std::stable_sort(order, order + 3, [&](int i, int j) { return width[i] > width[j]; });
    // A width at the rounding level of the coordinates themselves is no width either: a set that is flat
    // up to that level cannot be represented as thicker, and whitening it would amplify the rounding.
    double coordinateMagnitude = 0.0;
    for (const Vec3 &p : points)
        coordinateMagnitude = std::max(coordinateMagnitude, p.cwiseAbs().maxCoeff());
    const double roundingWidth = 64.0 * std::numeric_limits<double>::epsilon() * coordinateMagnitude;
    int dimension = 0;
    for (int j = 0; j < 3; ++j)
        if (extent > 0.0 && width[order[j]] > std::max(kFlatRatio * extent, roundingWidth))
            ++dimension;
    result.dimension = dimension;

    if (dimension == 0)
    {
        // A single point (possibly repeated, or spread only at the rounding level): a tiny ball on it.
        double spread = 0.0;
        for (const Vec3 &p : points)
            spread = std::max(spread, (p - origin).norm());
        const double radius =
            std::max({kPointRadius, 4.0 * std::numeric_limits<double>::epsilon() * coordinateMagnitude, 2.0 * spread});
        result.ellipsoid = Ellipsoid::fromAxes(origin, Mat3::Identity(), Vec3::Constant(radius));
        result.candidates = 1;
    }

    Mat3 axes = Mat3::Identity();
    Vec3 semiAxes = Vec3::Ones();
    Vec3 center = origin;
    if (dimension > 0)
    {
        // Coordinates in the hull, then its principal directions (an SVD of the centred coordinates)
        // for whitening: y_j = (principal_j - mid_j) / halfWidth_j lies in [-1, 1] in every direction.
        Eigen::Matrix<double, 3, Eigen::Dynamic> hullBasis(3, dimension);
        for (int j = 0; j < dimension; ++j)
            hullBasis.col(j) = hullFrame.col(order[j]);
        Eigen::MatrixXd inHull = offsets * hullBasis;
        const Eigen::RowVectorXd hullMean = inHull.colwise().mean();
        const Vec3 base = origin + hullBasis * hullMean.transpose();
        inHull.rowwise() -= hullMean;
        Eigen::MatrixXd principal = Eigen::MatrixXd::Identity(dimension, dimension);
        if (dimension > 1)
            principal = Eigen::JacobiSVD<Eigen::MatrixXd>(inHull / magnitude, Eigen::ComputeFullV).matrixV();
        const Eigen::MatrixXd local = inHull * principal;
        const Eigen::VectorXd lo = local.colwise().minCoeff().transpose(), hi = local.colwise().maxCoeff().transpose();
        const Eigen::VectorXd mid = 0.5 * (lo + hi);
        const Eigen::VectorXd halfWidth = (0.5 * (hi - lo)).cwiseMax(std::numeric_limits<double>::min());
        const Eigen::Matrix<double, 3, Eigen::Dynamic> kept = hullBasis * principal;
        auto whiten = [&](std::size_t i) {
            return Eigen::VectorXd((local.row(Eigen::Index(i)).transpose() - mid).cwiseQuotient(halfWidth));
        };

        // The fitted ellipsoid in whitened coordinates as cy + gy z, |z| <= 1.
        Eigen::VectorXd cy = Eigen::VectorXd::Zero(dimension);
        Eigen::MatrixXd gy = Eigen::MatrixXd::Identity(dimension, dimension);
        double khachiyanInflation = 1.0;
        auto adopt = [&](const auto &fit) {
            constexpr int K = std::decay_t<decltype(fit.center)>::RowsAtCompileTime;
            cy = fit.center;
            const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, K, K>> solver(fit.covariance);
            gy = solver.eigenvectors() * (fit.maxValue * solver.eigenvalues().cwiseMax(0.0)).cwiseSqrt().asDiagonal();
            khachiyanInflation = std::max(1.0, fit.maxValue / K);
            result.optimalityGap = std::max(0.0, fit.maxValue / K - 1.0);
            result.iterations = fit.iterations;
            result.removed = fit.removed;
        };
        if (dimension == 1)
        {
            // The minimum enclosing "ellipsoid" of collinear points is their segment: y in [-1, 1].
            result.candidates = count;
        }
        else if (dimension == 2)
        {
            std::vector<Eigen::Vector2d> y(count);
            for (std::size_t i = 0; i < count; ++i)
                y[i] = whiten(i);
            adopt(fitWhitened<2>(y, options, result.candidates));
        }
        else
        {
            std::vector<Eigen::Vector3d> y(count);
            for (std::size_t i = 0; i < count; ++i)
                y[i] = whiten(i);
            adopt(fitWhitened<3>(y, options, result.candidates));
        }
        result.inflation = khachiyanInflation;

        // Back to world coordinates: x = base + kept (mid + diag(halfWidth) (cy + gy z)). The SVD of the
        // 3 x k map gives the principal form directly, without forming an ill-conditioned shape matrix.
        center = base + kept * (mid + halfWidth.cwiseProduct(cy));
        const Eigen::MatrixXd g = kept * halfWidth.asDiagonal() * gy;
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(g, Eigen::ComputeFullU);
        axes = svd.matrixU();
        for (int j = 0; j < dimension; ++j)
            semiAxes[j] = svd.singularValues()[j];

        if (dimension < 3)
        {
            // Thickness for the missing directions, large enough (100 times the points' actual
            // deviation from the hull, rounding included) that growing the in-hull axes by at most a
            // factor 1 + 1e-4 (in A) absorbs the deviation.
            double deviation = 0.0;
            for (const Vec3 &p : points)
                deviation = std::max(deviation, (axes.rightCols(3 - dimension).transpose() * (p - center)).norm());
            const double thickness = std::max(kThickness * extent, 1e2 * deviation);
            double growth = 1.0;
            for (const Vec3 &p : points)
            {
                const Vec3 r = axes.transpose() * (p - center);
                double inHull = 0.0, across = 0.0;
                for (int j = 0; j < 3; ++j)
                {
                    if (j < dimension)
                        inHull += (r[j] / semiAxes[j]) * (r[j] / semiAxes[j]);
                    else
                        across += (r[j] / thickness) * (r[j] / thickness);
                }
                growth = std::max(growth, inHull / (1.0 - across));
            }
            for (int j = 0; j < 3; ++j)
                semiAxes[j] = (j < dimension) ? semiAxes[j] * std::sqrt(growth) : thickness;
            result.inflation *= growth;
        }
        if (axes.determinant() < 0.0)
            axes.col(2) = -axes.col(2);
        result.ellipsoid = Ellipsoid::fromAxes(center, axes, semiAxes);
    }

    // Exact containment as contains() evaluates it: grow uniformly until no point is outside. Only
    // rounding in the constructions above is left to cover, so this ends after a step or two.
    for (int attempt = 0; attempt < 200; ++attempt)
    {
        double worst = 0.0;
        for (const Vec3 &p : points)
            worst = std::max(worst, result.ellipsoid.normalizedRadiusSquared(p));
        if (worst <= 1.0)
            break;
        const double growth = worst * (1.0 + 1e-12 * double(1 << std::min(attempt, 30)));
        result.ellipsoid = Ellipsoid::fromAxes(result.ellipsoid.center, result.ellipsoid.axes,
                                               result.ellipsoid.semiAxes * std::sqrt(growth));
        result.inflation *= growth;
    }
    return result;
}
}  // namespace hcd
