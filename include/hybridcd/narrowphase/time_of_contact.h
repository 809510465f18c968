// SPDX-License-Identifier: BSD-3-Clause
// Time of contact of a translating convex piece by linear programming (review, section 5).
//
// Section 4.1 decides whether two convex pieces intersect as the feasibility of the union of their
// inequalities n_i . x <= d_i. Section 5 assumes that over one small time step every motion is a
// translation at constant velocity and adds time as a fourth variable: a point x lies in the
// moving piece at time t exactly when x - t*v lies in it at time 0, i.e. n_i . x - t (n_i . v) <=
// d_i, still linear in (x, t). Minimising t over
//
//     n_j . x                <= d_j     for every face j of the fixed piece,
//     n_i . x - t (n_i . v)  <= d_i     for every face i of the moving piece,
//     0 <= t <= 1,
//
// gives the first instant at which the two pieces share a point, and that point (the contact
// witness). The set of instants at which two convex pieces in relative translation intersect is
// an interval, so the LP's optimum is the exact first contact: no sampling of the motion and no
// backtracking (the review's criticism of feature-tracking methods, section 4.3). The LP is
// infeasible exactly when the pieces stay apart throughout the step.
//
// Conditioning. As in `intersectConvexPieces`, coordinates are translated and scaled into a unit
// working frame (here the frame holds the fixed piece and the moving piece at both ends of the
// step), and time is replaced by the distance travelled in that frame, u = t |v| / scale, so that
// every coefficient of the LP is at most one and its tolerance (1e-12 of the working frame) is a
// distance in both space and time. Seidel's solver (`solveSmallLp<4>`) then needs a few
// microseconds for pieces with a few dozen faces. The returned time is exact up to rounding and
// that tolerance: at a contact where the relative speed along the contact normal is c |v|, the
// time may be early by about 1e-12 * scale / (c |v|) at most, which only matters for grazing
// contacts whose time is ill-conditioned anyway.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"

namespace hcd
{
/// Result of `translationalTimeOfContact`, in the pieces' common frame and units.
struct TimeOfContact
{
    /// True when the pieces intersect or touch at some time in [0, 1].
    bool contact = false;
    /// The first such time, in [0, 1] (0 when the pieces already intersect at the start); 1 when
    /// there is no contact.
    double time = 1.0;
    /// When `contact`: a point in both pieces at `time`: in the fixed piece, and `point -
    /// time * displacement` in the moving piece as given (each inequality within about 1e-12 of
    /// the pair's size).
    Vec3 point = Vec3::Zero();
};

/// First contact of two convex pieces when `moving` translates by `displacement` over t in
/// [0, 1] (its points at time t are x + t * displacement for x in `moving`) and `fixed` stays.
/// Solves the 4-variable LP in (x, y, z, t): minimise t subject to the fixed piece's inequalities
/// n . x <= d, the moving piece's inequalities written at time t, n . (x - t * displacement) <= d,
/// and 0 <= t <= 1 (see the essay above). Exact for pure translation up to rounding; touching
/// (within about 1e-12 of the pair's size) counts as contact; `contact` is false when the LP is
/// infeasible. A zero displacement gives the static answer (time 0 or no contact).
/// Preconditions: both pieces in one frame and non-empty (as `ConvexPiece::hullOf` builds them);
/// `displacement` finite (otherwise std::invalid_argument).
TimeOfContact translationalTimeOfContact(const ConvexPiece &moving, const Vec3 &displacement, const ConvexPiece &fixed);
}  // namespace hcd
