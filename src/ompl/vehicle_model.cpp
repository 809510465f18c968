// SPDX-License-Identifier: BSD-3-Clause
// Equations, limits and constants after OMPL.app's apps/*Planning.cpp (Rice University, BSD
// licence); see vehicle_model.h for the two places where the documented equations are followed.
#include "hybridcd/ompl/vehicle_model.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace hcd
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

VehicleSpec makeSpec(VehicleModel model)
{
    VehicleSpec s;
    switch (model)
    {
    case VehicleModel::KinematicCar:
        s.planar = true;
        s.coordinates = 3;
        s.controlLow = {-5.0, -30.0 * kDegree};
        s.controlHigh = {5.0, 30.0 * kDegree};
        break;
    case VehicleModel::DynamicCar:
        s.planar = true;
        s.coordinates = 5;
        s.controlLow = {-0.5, -2.0 * kDegree};
        s.controlHigh = {0.5, 2.0 * kDegree};
        s.extraLow = {-1.0, -30.0 * kDegree};
        s.extraHigh = {1.0, 30.0 * kDegree};
        break;
    case VehicleModel::Blimp:
        s.planar = false;
        s.coordinates = 8;
        s.controlLow = {-1.0, -1.0, -0.3};
        s.controlHigh = {1.0, 1.0, 0.3};
        s.extraLow = {-1.0, -1.0, -1.0, -0.2};
        s.extraHigh = {1.0, 1.0, 1.0, 0.2};
        s.clampExtra = true;
        break;
    case VehicleModel::Quadrotor:
        s.planar = false;
        s.coordinates = 13;
        s.controlLow = {5.0, -1.0, -1.0, -1.0};
        s.controlHigh = {15.0, 1.0, 1.0, 1.0};
        s.extraLow.assign(6, -1.0);
        s.extraHigh.assign(6, 1.0);
        s.clampExtra = true;
        break;
    }
    return s;
}

// Into [-pi, pi), as OMPL's SO2 space keeps its angles.
double wrapAngle(double a)
{
    if (a >= -kPi && a < kPi)
        return a;
    a = std::fmod(a + kPi, 2.0 * kPi);
    if (a < 0.0)
        a += 2.0 * kPi;
    return a - kPi;
}

// Where the extra (non-pose) components start in q.
unsigned extraOffset(VehicleModel model)
{
    switch (model)
    {
    case VehicleModel::KinematicCar:
    case VehicleModel::DynamicCar:
        return 3;
    case VehicleModel::Blimp:
        return 4;
    case VehicleModel::Quadrotor:
        return 7;
    }
    return 0;
}
}  // namespace

std::optional<VehicleModel> vehicleModelOfName(const std::string &name)
{
    for (VehicleModel m :
         {VehicleModel::KinematicCar, VehicleModel::DynamicCar, VehicleModel::Blimp, VehicleModel::Quadrotor})
        if (name == vehicleModelName(m))
            return m;
    return std::nullopt;
}

const char *vehicleModelName(VehicleModel model)
{
    switch (model)
    {
    case VehicleModel::KinematicCar:
        return "kinematic_car";
    case VehicleModel::DynamicCar:
        return "dynamic_car";
    case VehicleModel::Blimp:
        return "blimp";
    case VehicleModel::Quadrotor:
        return "quadrotor";
    }
    return "?";
}

const VehicleSpec &vehicleSpec(VehicleModel model)
{
    static const std::array<VehicleSpec, 4> specs = {makeSpec(VehicleModel::KinematicCar),
                                                     makeSpec(VehicleModel::DynamicCar), makeSpec(VehicleModel::Blimp),
                                                     makeSpec(VehicleModel::Quadrotor)};
    return specs[std::size_t(model)];
}

void vehicleDerivative(VehicleModel model, const double *q, const double *u, double *qdot)
{
    const VehicleSpec &spec = vehicleSpec(model);
    switch (model)
    {
    case VehicleModel::KinematicCar:
        qdot[0] = u[0] * std::cos(q[2]);
        qdot[1] = u[0] * std::sin(q[2]);
        qdot[2] = u[0] * std::tan(u[1]) / spec.length;
        return;
    case VehicleModel::DynamicCar:
        qdot[0] = q[3] * std::cos(q[2]);
        qdot[1] = q[3] * std::sin(q[2]);
        qdot[2] = q[3] * spec.mass * std::tan(q[4]) / spec.length;
        qdot[3] = u[0];
        qdot[4] = u[1];
        return;
    case VehicleModel::Blimp:
        qdot[0] = q[4];
        qdot[1] = q[5];
        qdot[2] = q[6];
        qdot[3] = q[7];
        qdot[4] = u[0] * std::cos(q[3]);
        qdot[5] = u[0] * std::sin(q[3]);
        qdot[6] = u[1];
        qdot[7] = u[2];
        return;
    case VehicleModel::Quadrotor:
    {
        const double x = q[3], y = q[4], z = q[5], w = q[6];
        const double wx = q[10], wy = q[11], wz = q[12];
        qdot[0] = q[7];
        qdot[1] = q[8];
        qdot[2] = q[9];
        // q' = (0, omega) q / 2, the quaternion product with omega in the world frame.
        qdot[3] = 0.5 * (wx * w + wy * z - wz * y);
        qdot[4] = 0.5 * (wy * w + wz * x - wx * z);
        qdot[5] = 0.5 * (wz * w + wx * y - wy * x);
        qdot[6] = -0.5 * (wx * x + wy * y + wz * z);
        // n, the body z axis in world coordinates, is the third column of R(q).
        const double nx = 2.0 * (x * z + w * y), ny = 2.0 * (y * z - w * x), nz = w * w - x * x - y * y + z * z;
        qdot[7] = (-u[0] * nx - spec.damping * q[7]) / spec.mass;
        qdot[8] = (-u[0] * ny - spec.damping * q[8]) / spec.mass;
        qdot[9] = (-u[0] * nz - spec.damping * q[9]) / spec.mass - spec.gravity;
        qdot[10] = u[1];
        qdot[11] = u[2];
        qdot[12] = u[3];
        return;
    }
    }
}

void integrateVehicle(VehicleModel model, std::vector<double> &q, const double *u, double duration, double maxStep)
{
    const std::size_t n = q.size();
    if (!(duration > 0.0))
        return;
    // The step count is rounded so that a duration that is a whole number of steps (up to
    // rounding) takes exactly that many.
    const long steps = std::max(1L, long(std::ceil(duration / maxStep - 1e-9)));
    const double h = duration / double(steps);
    std::array<double, 16> k1{}, k2{}, k3{}, k4{}, tmp{};
    for (long s = 0; s < steps; ++s)
    {
        vehicleDerivative(model, q.data(), u, k1.data());
        for (std::size_t i = 0; i < n; ++i)
            tmp[i] = q[i] + 0.5 * h * k1[i];
        vehicleDerivative(model, tmp.data(), u, k2.data());
        for (std::size_t i = 0; i < n; ++i)
            tmp[i] = q[i] + 0.5 * h * k2[i];
        vehicleDerivative(model, tmp.data(), u, k3.data());
        for (std::size_t i = 0; i < n; ++i)
            tmp[i] = q[i] + h * k3[i];
        vehicleDerivative(model, tmp.data(), u, k4.data());
        for (std::size_t i = 0; i < n; ++i)
            q[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

void finishPropagation(VehicleModel model, std::vector<double> &q)
{
    const VehicleSpec &spec = vehicleSpec(model);
    switch (model)
    {
    case VehicleModel::KinematicCar:
    case VehicleModel::DynamicCar:
        q[2] = wrapAngle(q[2]);
        break;
    case VehicleModel::Blimp:
        q[3] = wrapAngle(q[3]);
        break;
    case VehicleModel::Quadrotor:
    {
        const double norm = std::sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
        for (int i = 3; i < 7; ++i)
            q[i] = norm > 0.0 ? q[i] / norm : (i == 6 ? 1.0 : 0.0);
        break;
    }
    }
    if (spec.clampExtra)
    {
        const unsigned offset = extraOffset(model);
        for (std::size_t i = 0; i < spec.extraLow.size(); ++i)
            q[offset + i] = std::clamp(q[offset + i], spec.extraLow[i], spec.extraHigh[i]);
    }
}

MotionBounds motionBounds(VehicleModel model, const std::vector<double> &q, const double *u, double length)
{
    const VehicleSpec &spec = vehicleSpec(model);
    const double inf = std::numeric_limits<double>::infinity();
    MotionBounds b;
    switch (model)
    {
    case VehicleModel::KinematicCar:
        b.speed = std::abs(u[0]);
        b.angularSpeed = std::abs(u[0] * std::tan(u[1])) / spec.length;
        break;
    case VehicleModel::DynamicCar:
    {
        // v and phi change linearly: their extremes are at the ends of the interval.
        b.speed = std::max(std::abs(q[3]), std::abs(q[3] + u[0] * length));
        const double phi = std::max(std::abs(q[4]), std::abs(q[4] + u[1] * length));
        b.angularSpeed = phi < 0.5 * kPi ? b.speed * spec.mass * std::tan(phi) / spec.length : inf;
        break;
    }
    case VehicleModel::Blimp:
        // |v'| = |(u0 cos, u0 sin, u1)| = hypot(u0, u1); |omega'| = |u2|.
        b.speed = std::sqrt(q[4] * q[4] + q[5] * q[5] + q[6] * q[6]) + std::hypot(u[0], u[1]) * length;
        b.angularSpeed = std::abs(q[7]) + std::abs(u[2]) * length;
        break;
    case VehicleModel::Quadrotor:
    {
        // |v'| <= c + k |v| with c = |u0| / m + g, k = beta / m (|n| = 1), so by Gronwall's
        // inequality |v(s)| <= (|v0| + c / k) e^{k s} - c / k.
        const double v0 = std::sqrt(q[7] * q[7] + q[8] * q[8] + q[9] * q[9]);
        const double c = std::abs(u[0]) / spec.mass + spec.gravity, k = spec.damping / spec.mass;
        b.speed = k > 0.0 ? (v0 + c / k) * std::exp(k * length) - c / k : v0 + c * length;
        b.angularSpeed = std::sqrt(q[10] * q[10] + q[11] * q[11] + q[12] * q[12]) +
                         std::sqrt(u[1] * u[1] + u[2] * u[2] + u[3] * u[3]) * length;
        break;
    }
    }
    return b;
}

ob::StateSpacePtr makeVehicleStateSpace(VehicleModel model, const ob::RealVectorBounds &poseBounds)
{
    const VehicleSpec &spec = vehicleSpec(model);
    ob::StateSpacePtr pose;
    if (spec.planar)
    {
        auto se2 = std::make_shared<ob::SE2StateSpace>();
        se2->setBounds(poseBounds);
        pose = se2;
    }
    else
    {
        auto se3 = std::make_shared<ob::SE3StateSpace>();
        se3->setBounds(poseBounds);
        pose = se3;
    }
    if (model == VehicleModel::KinematicCar)
        return pose;
    // OMPL.app's weights: 1 for the pose, 0.3 for each group of velocities.
    auto space = std::make_shared<ob::CompoundStateSpace>();
    space->addSubspace(pose, 1.0);
    auto addReal = [&](std::size_t first, std::size_t count) {
        const unsigned dims = unsigned(count);
        auto real = std::make_shared<ob::RealVectorStateSpace>(dims);
        ob::RealVectorBounds bounds(dims);
        for (std::size_t i = 0; i < count; ++i)
        {
            bounds.low[i] = spec.extraLow[first + i];
            bounds.high[i] = spec.extraHigh[first + i];
        }
        real->setBounds(bounds);
        space->addSubspace(real, 0.3);
    };
    if (model == VehicleModel::Blimp)
    {
        addReal(0, 3);
        addReal(3, 1);
    }
    else
    {
        addReal(0, spec.extraLow.size());
    }
    space->lock();
    return space;
}

oc::ControlSpacePtr makeVehicleControlSpace(VehicleModel model, const ob::StateSpacePtr &space)
{
    const VehicleSpec &spec = vehicleSpec(model);
    auto controls = std::make_shared<oc::RealVectorControlSpace>(space, unsigned(spec.controlLow.size()));
    ob::RealVectorBounds bounds(unsigned(spec.controlLow.size()));
    bounds.low = spec.controlLow;
    bounds.high = spec.controlHigh;
    controls->setBounds(bounds);
    return controls;
}

const ob::State *poseComponent(VehicleModel model, const ob::State *state)
{
    if (model == VehicleModel::KinematicCar)
        return state;
    return state->as<ob::CompoundState>()->components[0];
}

ob::State *poseComponent(VehicleModel model, ob::State *state)
{
    if (model == VehicleModel::KinematicCar)
        return state;
    return state->as<ob::CompoundState>()->components[0];
}

std::vector<double> vehicleCoordinates(VehicleModel model, const ob::State *state)
{
    const VehicleSpec &spec = vehicleSpec(model);
    std::vector<double> q(spec.coordinates, 0.0);
    const ob::State *pose = poseComponent(model, state);
    if (spec.planar)
    {
        const auto *s = pose->as<ob::SE2StateSpace::StateType>();
        q[0] = s->getX();
        q[1] = s->getY();
        q[2] = s->getYaw();
    }
    else
    {
        const auto *s = pose->as<ob::SE3StateSpace::StateType>();
        q[0] = s->getX();
        q[1] = s->getY();
        q[2] = s->getZ();
        const auto &r = s->rotation();
        if (model == VehicleModel::Blimp)
            q[3] = 2.0 * std::atan2(r.z, r.w);  // the yaw of a rotation about z
        else
        {
            q[3] = r.x;
            q[4] = r.y;
            q[5] = r.z;
            q[6] = r.w;
        }
    }
    const auto *compound = model == VehicleModel::KinematicCar ? nullptr : state->as<ob::CompoundState>();
    unsigned at = extraOffset(model);
    if (compound)
        for (unsigned c = 1; c < (model == VehicleModel::Blimp ? 3u : 2u); ++c)
        {
            const auto *real = compound->components[c]->as<ob::RealVectorStateSpace::StateType>();
            const std::size_t count = model == VehicleModel::Blimp ? (c == 1 ? 3 : 1) : spec.extraLow.size();
            for (std::size_t i = 0; i < count; ++i)
                q[at++] = real->values[i];
        }
    return q;
}

void setVehicleCoordinates(VehicleModel model, const std::vector<double> &q, ob::State *state)
{
    const VehicleSpec &spec = vehicleSpec(model);
    if (q.size() != spec.coordinates)
        throw std::invalid_argument(std::string("setVehicleCoordinates: ") + vehicleModelName(model) + " needs " +
                                    std::to_string(spec.coordinates) + " coordinates");
    ob::State *pose = poseComponent(model, state);
    if (spec.planar)
    {
        auto *s = pose->as<ob::SE2StateSpace::StateType>();
        s->setXY(q[0], q[1]);
        s->setYaw(q[2]);
    }
    else
    {
        auto *s = pose->as<ob::SE3StateSpace::StateType>();
        s->setXYZ(q[0], q[1], q[2]);
        auto &r = s->rotation();
        if (model == VehicleModel::Blimp)
        {
            r.x = 0.0;
            r.y = 0.0;
            r.z = std::sin(0.5 * q[3]);
            r.w = std::cos(0.5 * q[3]);
        }
        else
        {
            r.x = q[3];
            r.y = q[4];
            r.z = q[5];
            r.w = q[6];
        }
    }
    if (model == VehicleModel::KinematicCar)
        return;
    auto *compound = state->as<ob::CompoundState>();
    unsigned at = extraOffset(model);
    for (unsigned c = 1; c < (model == VehicleModel::Blimp ? 3u : 2u); ++c)
    {
        auto *real = compound->components[c]->as<ob::RealVectorStateSpace::StateType>();
        const std::size_t count = model == VehicleModel::Blimp ? (c == 1 ? 3 : 1) : spec.extraLow.size();
        for (std::size_t i = 0; i < count; ++i)
            real->values[i] = q[at++];
    }
}
}  // namespace hcd
