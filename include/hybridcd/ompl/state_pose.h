// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: pose rows (pose_codec.h) in and out of SE2 and SE3 states. These functions only
// copy fields; every numeric decision (yaw wrapping, quaternion normalisation) is the codec's.
#pragma once

#include "hybridcd/io/pose_codec.h"

#include <ompl/base/State.h>

#include <vector>

namespace hcd
{
/// The row an SE2 or SE3 state holds: x y yaw, or x y z qx qy qz qw (OMPL.app's .path order).
/// Fixed storage: called per state check.
PoseRow rowOfState(const ompl::base::State *state, bool planar);

/// The world-from-robot transform of an SE2 or SE3 state, following OMPL.app's conventions
/// (transformOfStateRow of rowOfState). A state written by poseValuesToState from a row gives
/// bit for bit transformOfRow of that row, so `check` and `check-motion` place the robot alike.
RigidTransform poseOfState(const ompl::base::State *state, bool planar);

/// The angle (radians) through which OMPL's interpolation from `from` to `to` turns the robot, at a
/// constant rate in t: SE2's yaw difference the way SO2StateSpace::interpolate takes it (the
/// shorter way round for yaws in [-pi, pi], and whatever it turns for others), SE3's slerp angle
/// 2 atan2(|v|, |w|) of from^-1 to, which stays accurate for tiny angles where acos of a dot product
/// rounds to zero. Infinity when no bound holds: a non-finite value, or a quaternion whose length
/// is more than 1e-9 from 1 (OMPL's slerp then turns at an uneven rate).
double interpolationTurn(const ompl::base::State *from, const ompl::base::State *to, bool planar);

/// Fills a state from .path columns (`values` holds 7 numbers, x y z qx qy qz qw, or 3, x y theta),
/// in the form stateRowOf gives: the quaternion made unit (rescaled when its squares over- or
/// underflow; zero is the identity), the yaw wrapped into [-pi, pi), the bounds OMPL asserts.
void poseValuesToState(const double *values, bool planar, ompl::base::State *state);

/// The .path columns of a state: x y z qx qy qz qw, or x y theta.
std::vector<double> stateToPoseValues(const ompl::base::State *state, bool planar);
}  // namespace hcd
