// SPDX-License-Identifier: BSD-3-Clause
// OMPL.app's kinodynamic vehicles: their equations of motion, limits and OMPL spaces.
//
// The models, bounds and constants follow OMPL.app (Rice University, BSD licence):
// KinematicCarPlanning, DynamicCarPlanning, BlimpPlanning and QuadrotorPlanning in
// src/omplapp/apps/ of github.com/ompl/omplapp. Two deliberate differences, both where OMPL.app's
// code departs from the equations it documents:
//  - blimp: OMPL.app integrates the heading in the quaternion's x field, so the heading restarts
//    from zero at every propagation; here it is the heading of the state, as the equations say.
//  - quadrotor: OMPL.app's orientation rate is (omega / 2, 0) projected orthogonal to q, which is
//    q' = (0, omega) q / 2 only at the identity; here it is that product (omega in the world frame).
//
// Model coordinates q (units: metres, radians, seconds) and controls u, per model:
//  kinematic car: q = (x, y, theta); u = (speed, steering angle)
//    x' = u0 cos(theta), y' = u0 sin(theta), theta' = u0 tan(u1) / L
//  dynamic car: q = (x, y, theta, v, phi); u = (acceleration, steering rate)
//    x' = v cos(theta), y' = v sin(theta), theta' = v m tan(phi) / L, v' = u0, phi' = u1
//  blimp: q = (x, y, z, theta, vx, vy, vz, omega); u = (forward thrust, lift, turn)
//    p' = v, theta' = omega, vx' = u0 cos(theta), vy' = u0 sin(theta), vz' = u1, omega' = u2
//  quadrotor: q = (x, y, z, qx, qy, qz, qw, vx, vy, vz, wx, wy, wz); u = (thrust, angular accel.)
//    p' = v, m v' = -u0 n - beta v - m g e_z (n: the body z axis in the world), w' = (u1, u2, u3)
//    The thrust acts along -n (OMPL.app's sign): the body hovers with its z axis pointing down.
#pragma once

#include <ompl/base/StateSpace.h>
#include <ompl/control/ControlSpace.h>

#include <optional>
#include <string>
#include <vector>

namespace hcd
{
enum class VehicleModel
{
    KinematicCar,
    DynamicCar,
    Blimp,
    Quadrotor,
};

/// The model a .cfg `control` value names (kinematic_car, dynamic_car, blimp, quadrotor).
std::optional<VehicleModel> vehicleModelOfName(const std::string &name);

/// The .cfg name of a model, e.g. "kinematic_car".
const char *vehicleModelName(VehicleModel model);

/// Constants and limits of a model (OMPL.app's defaults).
struct VehicleSpec
{
    bool planar = true;        ///< SE2 pose (cars) or SE3 pose (blimp, quadrotor)
    unsigned coordinates = 0;  ///< size of q
    std::vector<double> controlLow, controlHigh;
    /// Bounds of the state beyond the pose, in OMPL's state order (velocities, steering angle).
    std::vector<double> extraLow, extraHigh;
    /// Whether those bounds are enforced by clamping after each propagation (blimp, quadrotor) or
    /// make a state invalid when left (dynamic car), as OMPL.app does.
    bool clampExtra = false;
    double length = 1.0;    ///< cars: distance between the axles, m
    double mass = 1.0;      ///< dynamic car and quadrotor, kg
    double damping = 1.0;   ///< quadrotor: linear drag coefficient beta, kg/s
    double gravity = 9.81;  ///< quadrotor, m/s^2
};

const VehicleSpec &vehicleSpec(VehicleModel model);

/// qdot = f(q, u), all arrays of the model's sizes.
void vehicleDerivative(VehicleModel model, const double *q, const double *u, double *qdot);

/// Integrates q' = f(q, u) with u constant for `duration` seconds by the classic fourth-order
/// Runge-Kutta method, in equal steps no longer than `maxStep` (OMPL.app: 0.01 s).
void integrateVehicle(VehicleModel model, std::vector<double> &q, const double *u, double duration, double maxStep);

/// What OMPL.app does after each propagation: angles wrapped into [-pi, pi), the quaternion made
/// unit, and the velocities clamped to their bounds where the model clamps them.
void finishPropagation(VehicleModel model, std::vector<double> &q);

/// The OMPL state space: SE2 (kinematic car), SE2 x R^2 (dynamic car), SE3 x R^3 x R^1 (blimp),
/// SE3 x R^6 (quadrotor), with OMPL.app's weights; `poseBounds` bound the position, the extra
/// components get the spec's bounds.
ompl::base::StateSpacePtr makeVehicleStateSpace(VehicleModel model, const ompl::base::RealVectorBounds &poseBounds);

/// The control space (real vectors within the spec's bounds) over `space`.
ompl::control::ControlSpacePtr makeVehicleControlSpace(VehicleModel model, const ompl::base::StateSpacePtr &space);

/// The SE2 or SE3 component of a state of makeVehicleStateSpace's space.
const ompl::base::State *poseComponent(VehicleModel model, const ompl::base::State *state);
ompl::base::State *poseComponent(VehicleModel model, ompl::base::State *state);

/// Bounds on how fast the vehicle moves during a time interval: the speed of the robot origin
/// (m/s) and the angular speed (rad/s), so that a robot point p moves at most
/// (speed + angularSpeed |p|) per second. Infinite when the model gives no bound.
struct MotionBounds
{
    double speed = 0.0;
    double angularSpeed = 0.0;
};

/// Bounds valid over [t, t + length] for the trajectory from model coordinates `q` at t under the
/// constant control `u`, from the equations alone (velocities as integrated, before any clamp).
MotionBounds motionBounds(VehicleModel model, const std::vector<double> &q, const double *u, double length);

/// State <-> model coordinates (the blimp's heading is read from its quaternion as a yaw).
std::vector<double> vehicleCoordinates(VehicleModel model, const ompl::base::State *state);
void setVehicleCoordinates(VehicleModel model, const std::vector<double> &q, ompl::base::State *state);
}  // namespace hcd
