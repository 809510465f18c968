// SPDX-License-Identifier: BSD-3-Clause
// Kinodynamic planning: each vehicle's equations against closed-form motions, the propagator
// against a fine-step integration, and solved paths re-propagated finely under brute force.
#include "support/test_support.h"

#include "hybridcd/ompl/control_problem.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace hcd;

namespace
{
std::vector<double> integrated(VehicleModel model, std::vector<double> q, std::vector<double> u, double duration,
                               double step)
{
    integrateVehicle(model, q, u.data(), duration, step);
    return q;
}

// An OBJ box (12 triangles) spanning lo..hi.
std::string boxObj(const std::array<double, 3> &lo, const std::array<double, 3> &hi)
{
    std::ostringstream out;
    for (int i = 0; i < 8; ++i)
        out << "v " << (i & 1 ? hi[0] : lo[0]) << ' ' << (i & 2 ? hi[1] : lo[1]) << ' ' << (i & 4 ? hi[2] : lo[2])
            << '\n';
    out << "f 2 4 8\nf 2 8 6\nf 7 3 1\nf 7 1 5\nf 3 7 8\nf 3 8 4\nf 6 5 1\nf 6 1 2\nf 5 6 8\nf 5 8 7\n"
           "f 4 2 1\nf 4 1 3\n";
    return out.str();
}

// A planar kinematic-car problem: a 0.5 x 0.2 car and a 0.1-thick wall at x in [2, 2.1].
LoadedProblem thinWallProblem()
{
    const std::string robot = test::writeTempFile("car.obj", boxObj({-0.25, -0.1, -0.5}, {0.25, 0.1, 0.5}));
    const std::string world = test::writeTempFile("wall.obj", boxObj({2.0, -5.0, -1.0}, {2.1, 5.0, 1.0}));
    const std::string cfg = test::writeTempFile(
        "thin_wall.cfg", "[problem]\nrobot = " + robot + "\nworld = " + world +
                             "\ncontrol = kinematic_car\nstart.x = 0\nstart.y = 0\nstart.theta = 0\n"
                             "goal.x = 4\ngoal.y = 0\ngoal.theta = 0\nvolume.min.x = -6\nvolume.min.y = -6\n"
                             "volume.max.x = 6\nvolume.max.y = 6\n");
    return loadProblem(cfg);
}

// A blimp problem: a 0.6 x 0.6 x 0.2 body, a pillar between start and goal.
LoadedProblem pillarProblem(const std::string &model)
{
    const std::string robot = test::writeTempFile("body.obj", boxObj({-0.3, -0.3, -0.1}, {0.3, 0.3, 0.1}));
    const std::string world = test::writeTempFile("pillar.obj", boxObj({1.5, -0.5, 0.0}, {2.0, 0.5, 10.0}));
    const std::string cfg = test::writeTempFile(
        model + "_pillar.cfg", "[problem]\nrobot = " + robot + "\nworld = " + world + "\ncontrol = " + model +
                                   "\nstart.x = 0\nstart.y = 0\nstart.z = 5\ngoal.x = 4\ngoal.y = 0\ngoal.z = 5\n"
                                   "volume.min.x = -6\nvolume.min.y = -6\nvolume.min.z = 0\nvolume.max.x = 6\n"
                                   "volume.max.y = 6\nvolume.max.z = 10\n");
    return loadProblem(cfg);
}

// Re-propagates every control of `path` from its own start state in steps of 1 ms, checking each
// pose with brute force and the bounds; the end must match the path's next state and the last
// state must satisfy the goal.
void expectPathValid(const ControlProblem &planning, const LoadedProblem &problem,
                     const ompl::control::PathControl &path)
{
    const auto bruteForce = makeChecker("bruteforce", problem.scene);
    const auto si = planning.setup->getSpaceInformation();
    ompl::base::State *s = si->allocState();
    std::size_t checked = 0;
    for (std::size_t i = 0; i < path.getControlCount(); ++i)
    {
        const double *u = path.getControl(i)->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
        std::vector<double> q = vehicleCoordinates(planning.model, path.getState(i));
        // Propagation step by step, as OMPL propagates (the post-step, a velocity clamp for
        // some models, ends each), each step in 1 ms pieces.
        const double step = si->getPropagationStepSize();
        const int propagations = int(std::lround(path.getControlDuration(i) / step));
        ASSERT_NEAR(propagations * step, path.getControlDuration(i), 1e-9);
        for (int p = 0; p < propagations; ++p)
        {
            if (p > 0)
                finishPropagation(planning.model, q);
            const int pieces = int(std::ceil(step / 1e-3 - 1e-9));
            for (int k = 0; k < pieces; ++k)
            {
                integrateVehicle(planning.model, q, u, step / pieces, 1e-3);
                std::vector<double> shown = q;
                finishPropagation(planning.model, shown);
                setVehicleCoordinates(planning.model, shown, s);
                ASSERT_TRUE(si->satisfiesBounds(s)) << "control " << i << " step " << p << "." << k;
                ASSERT_FALSE(bruteForce->collides(poseOfState(poseComponent(planning.model, s), problem.config.planar)))
                    << "control " << i << " step " << p << "." << k;
                ++checked;
            }
        }
        finishPropagation(planning.model, q);
        setVehicleCoordinates(planning.model, q, s);
        EXPECT_LT(si->distance(s, path.getState(i + 1)), 1e-6) << "control " << i;
    }
    EXPECT_TRUE(
        planning.setup->getProblemDefinition()->getGoal()->isSatisfied(path.getState(path.getStateCount() - 1)));
    si->freeState(s);
    EXPECT_GT(checked, 10 * path.getControlCount());
}
}  // namespace

TEST(VehicleModel, NamesRoundTripAndUnknownNamesAreNone)
{
    for (VehicleModel m :
         {VehicleModel::KinematicCar, VehicleModel::DynamicCar, VehicleModel::Blimp, VehicleModel::Quadrotor})
        EXPECT_EQ(vehicleModelOfName(vehicleModelName(m)), m);
    EXPECT_FALSE(vehicleModelOfName("hovercraft"));
    EXPECT_FALSE(vehicleModelOfName(""));
}

TEST(VehicleModel, KinematicCarDrivesStraightAndOnACircleOfItsTurningRadius)
{
    // Straight: x = v t.
    const auto line = integrated(VehicleModel::KinematicCar, {1.0, 2.0, 0.0}, {3.0, 0.0}, 2.0, 0.01);
    EXPECT_NEAR(line[0], 7.0, 1e-12);
    EXPECT_NEAR(line[1], 2.0, 1e-12);
    EXPECT_NEAR(line[2], 0.0, 1e-12);
    // Constant steering phi: a circle of radius L / tan(phi) about (0, R), heading v t / R.
    const double phi = 0.3, v = 2.0, t = 3.0, radius = 1.0 / std::tan(phi);
    const auto arc = integrated(VehicleModel::KinematicCar, {0.0, 0.0, 0.0}, {v, phi}, t, 0.01);
    const double heading = v * t / radius;
    EXPECT_NEAR(arc[2], heading, 1e-12);
    EXPECT_NEAR(arc[0], radius * std::sin(heading), 1e-8);
    EXPECT_NEAR(arc[1], radius * (1.0 - std::cos(heading)), 1e-8);
    EXPECT_NEAR(std::hypot(arc[0], arc[1] - radius), radius, 1e-8);
}

TEST(VehicleModel, DynamicCarAcceleratesAndCircles)
{
    // From rest with acceleration a and no steering: x = a t^2 / 2, v = a t.
    const auto line = integrated(VehicleModel::DynamicCar, {0, 0, 0, 0, 0}, {0.5, 0.0}, 2.0, 0.01);
    EXPECT_NEAR(line[0], 0.25 * 4.0, 1e-12);
    EXPECT_NEAR(line[3], 1.0, 1e-12);
    // Constant speed and steering angle: a circle of radius L / (m tan(phi)).
    const double phi = 0.4, v = 0.8, t = 5.0, radius = 1.0 / std::tan(phi);
    const auto arc = integrated(VehicleModel::DynamicCar, {0, 0, 0, v, phi}, {0.0, 0.0}, t, 0.01);
    EXPECT_NEAR(std::hypot(arc[0], arc[1] - radius), radius, 1e-8);
    EXPECT_NEAR(arc[2], v * t / radius, 1e-12);
    // Steering rate: phi = u1 t.
    const auto steer = integrated(VehicleModel::DynamicCar, {0, 0, 0, 0, 0}, {0.0, 0.02}, 3.0, 0.01);
    EXPECT_NEAR(steer[4], 0.06, 1e-12);
}

TEST(VehicleModel, BlimpThrustsAlongItsHeadingAndTurns)
{
    const double heading = 0.7, t = 2.0;
    // q = (x, y, z, theta, vx, vy, vz, omega); forward thrust 0.5, lift 0.2, no turn.
    const auto q = integrated(VehicleModel::Blimp, {0, 0, 0, heading, 0, 0, 0, 0}, {0.5, 0.2, 0.0}, t, 0.01);
    EXPECT_NEAR(q[0], 0.25 * std::cos(heading) * t * t, 1e-12);
    EXPECT_NEAR(q[1], 0.25 * std::sin(heading) * t * t, 1e-12);
    EXPECT_NEAR(q[2], 0.1 * t * t, 1e-12);
    EXPECT_NEAR(q[4], 0.5 * std::cos(heading) * t, 1e-12);
    // Turning: theta = theta0 + u2 t^2 / 2, omega = u2 t.
    const auto turn = integrated(VehicleModel::Blimp, {0, 0, 0, heading, 0, 0, 0, 0}, {0.0, 0.0, 0.1}, t, 0.01);
    EXPECT_NEAR(turn[3], heading + 0.05 * t * t, 1e-12);
    EXPECT_NEAR(turn[7], 0.1 * t, 1e-12);
    // The post-step clamps the velocities to OMPL.app's bounds.
    std::vector<double> fast = {0, 0, 0, 0, 3.0, -2.0, 0.5, 0.9};
    finishPropagation(VehicleModel::Blimp, fast);
    EXPECT_EQ(fast[4], 1.0);
    EXPECT_EQ(fast[5], -1.0);
    EXPECT_EQ(fast[6], 0.5);
    EXPECT_EQ(fast[7], 0.2);
}

TEST(VehicleModel, QuadrotorHoversFallsWithDragAndSpins)
{
    const VehicleSpec &spec = vehicleSpec(VehicleModel::Quadrotor);
    // Hover: body z axis pointing down (rotation by pi about x), thrust = m g, at rest.
    std::vector<double> hover = {1, 2, 3, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const auto still = integrated(VehicleModel::Quadrotor, hover, {spec.mass * spec.gravity, 0, 0, 0}, 5.0, 0.01);
    for (std::size_t i = 0; i < hover.size(); ++i)
        EXPECT_NEAR(still[i], hover[i], 1e-12) << i;
    // Upright, thrust c - m g pushes down with the weight: m v' = -c - beta v, v(t) = -(c/beta)(1 - e^{-beta t/m}).
    const double thrust = 5.0, t = 1.5;
    const auto fall =
        integrated(VehicleModel::Quadrotor, {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0}, {thrust, 0, 0, 0}, t, 0.01);
    const double c = thrust + spec.mass * spec.gravity;
    const double vz = -(c / spec.damping) * (1.0 - std::exp(-spec.damping * t / spec.mass));
    const double z =
        -(c / spec.damping) * (t - spec.mass / spec.damping * (1.0 - std::exp(-spec.damping * t / spec.mass)));
    EXPECT_NEAR(fall[9], vz, 1e-8);
    EXPECT_NEAR(fall[2], z, 1e-8);
    EXPECT_NEAR(fall[0], 0.0, 1e-12);
    // Constant angular velocity w about z: q(t) = (0, 0, sin(w t / 2), cos(w t / 2)).
    const double w = 0.5;
    auto spin = integrated(VehicleModel::Quadrotor, {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, w},
                           {spec.mass * spec.gravity, 0, 0, 0}, 4.0, 0.01);
    finishPropagation(VehicleModel::Quadrotor, spin);
    EXPECT_NEAR(spin[5], std::sin(w * 2.0), 1e-9);
    EXPECT_NEAR(spin[6], std::cos(w * 2.0), 1e-9);
    EXPECT_NEAR(spin[3], 0.0, 1e-12);
    EXPECT_NEAR(spin[12], w, 1e-15);
}

TEST(VehicleModel, StateCoordinatesRoundTripForEveryModel)
{
    ompl::base::RealVectorBounds bounds(3);
    bounds.setLow(-10);
    bounds.setHigh(10);
    test::TestRandom rng(test::seeded(5));
    std::uniform_real_distribution<double> uniform(-0.9, 0.9);
    for (VehicleModel m :
         {VehicleModel::KinematicCar, VehicleModel::DynamicCar, VehicleModel::Blimp, VehicleModel::Quadrotor})
    {
        const VehicleSpec &spec = vehicleSpec(m);
        ompl::base::RealVectorBounds b(spec.planar ? 2 : 3);
        b.setLow(-10);
        b.setHigh(10);
        const auto space = makeVehicleStateSpace(m, b);
        ompl::base::ScopedState<> state(space);
        std::vector<double> q(spec.coordinates);
        for (double &v : q)
            v = uniform(rng);
        finishPropagation(m, q);  // a unit quaternion for the quadrotor
        setVehicleCoordinates(m, q, state.get());
        const std::vector<double> back = vehicleCoordinates(m, state.get());
        for (std::size_t i = 0; i < q.size(); ++i)
            EXPECT_NEAR(back[i], q[i], 1e-12) << vehicleModelName(m) << " coordinate " << i;
        EXPECT_TRUE(space->satisfiesBounds(state.get())) << vehicleModelName(m);
    }
}

TEST(VehiclePropagator, MatchesAFineStepIntegrationForEveryModel)
{
    for (VehicleModel m :
         {VehicleModel::KinematicCar, VehicleModel::DynamicCar, VehicleModel::Blimp, VehicleModel::Quadrotor})
    {
        const VehicleSpec &spec = vehicleSpec(m);
        ompl::base::RealVectorBounds b(spec.planar ? 2 : 3);
        b.setLow(-100);
        b.setHigh(100);
        const auto space = makeVehicleStateSpace(m, b);
        auto si = std::make_shared<ompl::control::SpaceInformation>(space, makeVehicleControlSpace(m, space));
        VehiclePropagator propagator(si, m, 0.01, nullptr);
        ompl::base::ScopedState<> start(space), result(space), reference(space);
        start.random();
        std::vector<double> q0 = vehicleCoordinates(m, start.get());
        for (std::size_t i = spec.planar ? 3 : (m == VehicleModel::Blimp ? 4 : 7); i < q0.size(); ++i)
            q0[i] *= 0.5;  // within the velocity bounds, away from the clamp
        setVehicleCoordinates(m, q0, start.get());
        ompl::control::Control *u = si->allocControl();
        si->allocControlSampler()->sample(u);
        propagator.propagate(start.get(), u, 0.2, result.get());
        std::vector<double> fine = vehicleCoordinates(m, start.get());
        integrateVehicle(m, fine, u->as<ompl::control::RealVectorControlSpace::ControlType>()->values, 0.2, 1e-5);
        finishPropagation(m, fine);
        setVehicleCoordinates(m, fine, reference.get());
        EXPECT_LT(space->distance(result.get(), reference.get()), 1e-8) << vehicleModelName(m);
        si->freeControl(u);
    }
}

TEST(VehicleModel, MotionBoundsHoldAlongFineTrajectories)
{
    // From random states and controls, no pose along a finely integrated trajectory moves its
    // origin farther, or turns by more, than the bounds allow for the time elapsed.
    test::TestRandom rng(test::seeded(11));
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (VehicleModel m :
         {VehicleModel::KinematicCar, VehicleModel::DynamicCar, VehicleModel::Blimp, VehicleModel::Quadrotor})
    {
        const VehicleSpec &spec = vehicleSpec(m);
        for (int trial = 0; trial < 50; ++trial)
        {
            std::vector<double> q(spec.coordinates);
            for (double &v : q)
                v = 2.0 * unit(rng) - 1.0;
            finishPropagation(m, q);
            if (m == VehicleModel::DynamicCar)
                q[4] *= 0.5;  // within the steering bounds
            std::vector<double> u(spec.controlLow.size());
            for (std::size_t i = 0; i < u.size(); ++i)
                u[i] = spec.controlLow[i] + unit(rng) * (spec.controlHigh[i] - spec.controlLow[i]);
            const double length = 0.2;
            const MotionBounds bounds = motionBounds(m, q, u.data(), length);
            const ompl::base::RealVectorBounds box = [&] {
                ompl::base::RealVectorBounds b(spec.planar ? 2 : 3);
                b.setLow(-100);
                b.setHigh(100);
                return b;
            }();
            const auto space = makeVehicleStateSpace(m, box);
            ompl::base::ScopedState<> a(space), b(space);
            setVehicleCoordinates(m, q, a.get());
            const RigidTransform start = poseOfState(poseComponent(m, a.get()), spec.planar);
            std::vector<double> p = q;
            for (int k = 1; k <= 200; ++k)
            {
                integrateVehicle(m, p, u.data(), length / 200, 1e-4);
                // The bounds hold for the integration itself (clamping comes after it); only the
                // quaternion is normalised to make a pose.
                std::vector<double> shown = p;
                if (m == VehicleModel::Quadrotor)
                {
                    const double n = std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5] + p[6] * p[6]);
                    for (int i = 3; i < 7; ++i)
                        shown[i] = p[i] / n;
                }
                setVehicleCoordinates(m, shown, b.get());
                const RigidTransform now = poseOfState(poseComponent(m, b.get()), spec.planar);
                const double s = length * k / 200;
                EXPECT_LE((now.translation - start.translation).norm(), bounds.speed * s * (1 + 1e-9) + 1e-12)
                    << vehicleModelName(m) << " trial " << trial << " step " << k;
                const double angle = Eigen::AngleAxisd(start.rotation.transpose() * now.rotation).angle();
                EXPECT_LE(angle, bounds.angularSpeed * s * (1 + 1e-9) + 1e-9)
                    << vehicleModelName(m) << " trial " << trial << " step " << k;
            }
        }
    }
}

TEST(VehiclePropagator, ContinuousSweepRefusesToTunnelThroughAThinWall)
{
    const LoadedProblem problem = thinWallProblem();
    for (const MotionCheck motion : {MotionCheck::Continuous, MotionCheck::Discrete})
    {
        ControlSettings settings;
        settings.motion = motion;
        ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene), settings);
        const auto si = planning.setup->getSpaceInformation();
        ompl::base::ScopedState<> from(si->getStateSpace()), to(si->getStateSpace());
        setVehicleCoordinates(VehicleModel::KinematicCar, {1.5, 0.0, 0.0}, from.get());
        ompl::control::Control *u = si->allocControl();
        u->as<ompl::control::RealVectorControlSpace::ControlType>()->values[0] = 5.0;  // 1 m per 0.2 s step
        u->as<ompl::control::RealVectorControlSpace::ControlType>()->values[1] = 0.0;
        ASSERT_TRUE(si->isValid(from.get()));
        si->propagate(from.get(), u, 1, to.get());
        // The car ends at x = 2.5, past the wall: free on its own.
        const std::vector<double> end = vehicleCoordinates(VehicleModel::KinematicCar, to.get());
        if (motion == MotionCheck::Discrete)
        {
            EXPECT_NEAR(end[0], 2.5, 1e-12);
            EXPECT_TRUE(si->isValid(to.get())) << "OMPL.app's discrete checks tunnel through the wall";
        }
        else
        {
            EXPECT_TRUE(std::isnan(end[0]));
            EXPECT_FALSE(si->isValid(to.get()));
            EXPECT_EQ(planning.propagator->blockedPropagations(), 1u);
            EXPECT_EQ(si->propagateWhileValid(from.get(), u, 1, to.get()), 0u);
        }
        si->freeControl(u);
    }
}

TEST(ControlProblem, RefusesUnknownModelsAndWrongDimensions)
{
    LoadedProblem problem = thinWallProblem();
    problem.config.control = "hovercraft";
    EXPECT_THROW(makeControlProblem(problem, makeChecker("obb", problem.scene)), std::invalid_argument);
    problem.config.control = "quadrotor";  // a 3D vehicle in a planar problem
    EXPECT_THROW(makeControlProblem(problem, makeChecker("obb", problem.scene)), std::invalid_argument);
    problem.config.control = "kinematic_car";
    ControlSettings bad;
    bad.minControlSteps = 5;
    bad.maxControlSteps = 2;
    EXPECT_THROW(makeControlProblem(problem, makeChecker("obb", problem.scene), bad), std::invalid_argument);
}

TEST(ControlProblem, EveryControlPlannerDrivesAroundTheWallAndThePathHolds)
{
    // The car must drive around the thin wall: the straight line to the goal crosses it.
    const LoadedProblem problem = thinWallProblem();
    for (const std::string &planner : controlPlannerNames())
    {
        ompl::RNG::setSeed(std::uint_fast32_t(test::seed()));
        ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene));
        planning.setup->setPlanner(makeControlPlanner({planner, "", {}}, planning.setup->getSpaceInformation()));
        // SST keeps improving its path until the time is up: a few seconds are enough here.
        const auto status = planning.setup->solve(planner == "sst" ? 3.0 : 60.0);
        ASSERT_EQ(status, ompl::base::PlannerStatus::EXACT_SOLUTION) << planner;
        expectPathValid(planning, problem, planning.setup->getSolutionPath());
        EXPECT_GT(planning.poseValidity->checkCount(), 0u);
    }
}

TEST(ControlProblem, BlimpFliesAroundAPillarAndThePathHolds)
{
    const LoadedProblem problem = pillarProblem("blimp");
    for (const char *planner : {"kpiece", "rrt"})
    {
        ompl::RNG::setSeed(std::uint_fast32_t(test::seed()));
        ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene));
        EXPECT_EQ(planning.model, VehicleModel::Blimp);
        planning.setup->setPlanner(makeControlPlanner({planner, "", {}}, planning.setup->getSpaceInformation()));
        ASSERT_EQ(planning.setup->solve(60.0), ompl::base::PlannerStatus::EXACT_SOLUTION) << planner;
        expectPathValid(planning, problem, planning.setup->getSolutionPath());
    }
}

TEST(ControlProblem, RrtSolvesTheCorridorAndThePathHolds)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/corridor_kcar.cfg"));
    ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setPlanner(makeControlPlanner({"rrt", "", {}}, planning.setup->getSpaceInformation()));
    ASSERT_EQ(planning.setup->solve(60.0), ompl::base::PlannerStatus::EXACT_SOLUTION);
    expectPathValid(planning, problem, planning.setup->getSolutionPath());
}

TEST(ControlProblem, OmplAppMazeKinematicCarSolves)
{
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    // Planning is bounded by time, and under sanitizers RRT gets a few percent of its iterations
    // in that time; the tests on the project's problems above cover the same code there.
    GTEST_SKIP() << "planning OMPL.app's maze within a time limit is a Release-build test";
#endif
    const auto cfg = test::omplappProblem("2D/Maze_kcar.cfg");
    if (!cfg)
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("OMPL.app resources not found; set HYBRIDCD_OMPLAPP_RESOURCES");
    const LoadedProblem problem = loadProblem(*cfg);
    ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene));
    EXPECT_EQ(planning.model, VehicleModel::KinematicCar);
    planning.setup->setPlanner(makeControlPlanner({"rrt", "", {}}, planning.setup->getSpaceInformation()));
    ASSERT_EQ(planning.setup->solve(120.0), ompl::base::PlannerStatus::EXACT_SOLUTION);
    expectPathValid(planning, problem, planning.setup->getSolutionPath());
}

TEST(ControlProblem, QuadrotorFliesThroughTheWindowAndThePathHolds)
{
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    GTEST_SKIP() << "planning the quadrotor within a time limit is a Release-build test";
#endif
    // The project's quadrotor problem, with OMPL.app's settings but a goal distance of 1.5 (the
    // distance adds the position's, the orientation's and 0.3 x the velocities'), solved exactly by
    // control planners and re-propagated in 1 ms steps under brute force.
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/quadrotor_window.cfg"));
    ControlSettings settings;
    settings.goalThreshold = 1.5;
    for (const char *planner : {"kpiece", "rrt"})
    {
        ompl::RNG::setSeed(std::uint_fast32_t(test::seed()));
        ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene), settings);
        EXPECT_EQ(planning.model, VehicleModel::Quadrotor);
        planning.setup->setPlanner(makeControlPlanner({planner, "", {}}, planning.setup->getSpaceInformation()));
        ASSERT_EQ(planning.setup->solve(60.0), ompl::base::PlannerStatus::EXACT_SOLUTION) << planner;
        const ompl::control::PathControl &path = planning.setup->getSolutionPath();
        expectPathValid(planning, problem, path);
        // It went through the window: the wall stands at x in [-0.1, 0.1] between start and goal.
        const auto pose = [&](std::size_t i) { return vehicleCoordinates(VehicleModel::Quadrotor, path.getState(i)); };
        EXPECT_LT(pose(0)[0], -1.5);
        EXPECT_GT(pose(path.getStateCount() - 1)[0], 0.4);  // the robot reaches 0.3 from its centre
    }
}

TEST(ControlProblem, DynamicCarStartAndGoalCarryZeroVelocity)
{
    LoadedProblem problem = thinWallProblem();
    problem.config.control = "dynamic_car";
    ControlProblem planning = makeControlProblem(problem, makeChecker("obb", problem.scene));
    const auto *start = planning.setup->getProblemDefinition()->getStartState(0);
    const std::vector<double> q = vehicleCoordinates(VehicleModel::DynamicCar, start);
    EXPECT_EQ(q, (std::vector<double>{0, 0, 0, 0, 0}));
    EXPECT_EQ(planning.setup->getSpaceInformation()->getMinControlDuration(), 1u);
    EXPECT_EQ(planning.setup->getSpaceInformation()->getMaxControlDuration(), 20u);
    EXPECT_DOUBLE_EQ(planning.setup->getSpaceInformation()->getPropagationStepSize(), 0.2);
}
