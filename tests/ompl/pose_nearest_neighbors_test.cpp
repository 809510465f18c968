// SPDX-License-Identifier: BSD-3-Clause
// PoseNearestNeighbors against OMPL's NearestNeighborsLinear (every element measured), on random
// and adversarial poses, and RRTConnect planning with it against RRTConnect with OMPL's default.
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/planners/pose_nearest_neighbors.h"

#include "support/test_support.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace hcd;
namespace ob = ompl::base;

namespace
{

constexpr double kPi = 3.14159265358979323846;
using StatePtr = ob::State *;

// Owns the states of one space and compares the structure with a linear search over them.
class Fixture
{
public:
    explicit Fixture(ob::StateSpacePtr space) : space_(std::move(space)), metric_(PoseMetric::of(*space_))
    {
        const auto distance = [this](const StatePtr &a, const StatePtr &b) { return space_->distance(a, b); };
        poses_ = std::make_unique<PoseNearestNeighbors<StatePtr>>(*metric_, [](const StatePtr &s) { return s; });
        poses_->setDistanceFunction(distance);
        linear_.setDistanceFunction(distance);
    }

    ~Fixture()
    {
        for (StatePtr s : states_)
            space_->freeState(s);
    }

    bool hasMetric() const { return metric_.has_value(); }

    StatePtr make()
    {
        states_.push_back(space_->allocState());
        return states_.back();
    }

    void add(StatePtr s)
    {
        poses_->add(s);
        linear_.add(s);
    }

    void remove(StatePtr s) { EXPECT_EQ(poses_->remove(s), linear_.remove(s)); }

    // The same nearest distance, the same k nearest distances, the same distances within radius.
    void expectSameAnswers(StatePtr query, std::size_t k, double radius)
    {
        ASSERT_EQ(poses_->size(), linear_.size());
        if (linear_.size() == 0)
            return;
        EXPECT_EQ(space_->distance(query, poses_->nearest(query)), space_->distance(query, linear_.nearest(query)));
        expectSameDistances(query, [&](auto &nn, std::vector<StatePtr> &out) { nn.nearestK(query, k, out); });
        expectSameDistances(query, [&](auto &nn, std::vector<StatePtr> &out) { nn.nearestR(query, radius, out); });
    }

    StatePtr nearest(StatePtr query) const { return poses_->nearest(query); }
    StatePtr nearestByLinearSearch(StatePtr query) const { return linear_.nearest(query); }

    // The radius that holds about `count` neighbours of query.
    double radiusHolding(StatePtr query, std::size_t count)
    {
        std::vector<StatePtr> near;
        linear_.nearestK(query, count, near);
        return near.empty() ? 0.0 : space_->distance(query, near.back());
    }

    const ob::StateSpacePtr &space() const { return space_; }
    const std::vector<StatePtr> &states() const { return states_; }

private:
    template <typename Search>
    void expectSameDistances(StatePtr query, Search search)
    {
        std::vector<StatePtr> fast;
        std::vector<StatePtr> reference;
        search(*poses_, fast);
        search(linear_, reference);
        ASSERT_EQ(fast.size(), reference.size());
        for (std::size_t i = 0; i < fast.size(); ++i)
            EXPECT_EQ(space_->distance(query, fast[i]), space_->distance(query, reference[i])) << "neighbour " << i;
    }

    ob::StateSpacePtr space_;
    std::optional<PoseMetric> metric_;
    std::unique_ptr<PoseNearestNeighbors<StatePtr>> poses_;
    ompl::NearestNeighborsLinear<StatePtr> linear_;
    std::vector<StatePtr> states_;
};

// OMPL's SE(2) or SE(3) space over the cube [-extent, extent] of positions.
template <typename Space>
std::shared_ptr<Space> poseSpace(unsigned dimensions, double extent)
{
    auto space = std::make_shared<Space>();
    ob::RealVectorBounds bounds(dimensions);
    bounds.setLow(-extent);
    bounds.setHigh(extent);
    space->setBounds(bounds);
    return space;
}

std::shared_ptr<ob::SE3StateSpace> se3Space(double extent) { return poseSpace<ob::SE3StateSpace>(3, extent); }
std::shared_ptr<ob::SE2StateSpace> se2Space(double extent) { return poseSpace<ob::SE2StateSpace>(2, extent); }

void setSpatial(ob::State *s, double x, double y, double z, double qx, double qy, double qz, double qw)
{
    auto *pose = s->as<ob::SE3StateSpace::StateType>();
    pose->setXYZ(x, y, z);
    auto &q = pose->rotation();
    q.x = qx;
    q.y = qy;
    q.z = qz;
    q.w = qw;
}

// A uniform rotation, as a quaternion of norm 1 up to rounding.
void setRandomSpatial(ob::State *s, double extent, test::TestRandom &rng)
{
    std::uniform_real_distribution<double> coordinate(-extent, extent);
    std::normal_distribution<double> gauss;
    double q[4];
    double norm = 0.0;
    do
    {
        norm = 0.0;
        for (double &c : q)
        {
            c = gauss(rng);
            norm += c * c;
        }
    } while (norm < 1e-6);
    norm = std::sqrt(norm);
    setSpatial(s, coordinate(rng), coordinate(rng), coordinate(rng), q[0] / norm, q[1] / norm, q[2] / norm,
               q[3] / norm);
}

// s rotated by `angle` about x, with its translation kept.
void setTurned(ob::State *s, const ob::State *from, double angle)
{
    const auto *p = from->as<ob::SE3StateSpace::StateType>();
    const auto &q = p->rotation();
    const double c = std::cos(angle / 2), d = std::sin(angle / 2);
    // (q) * (d, 0, 0, c) in (x, y, z, w)
    setSpatial(s, p->getX(), p->getY(), p->getZ(), q.w * d + q.x * c, q.y * c + q.z * d, q.z * c - q.y * d,
               q.w * c - q.x * d);
}

void setPlanar(ob::State *s, double x, double y, double yaw)
{
    auto *pose = s->as<ob::SE2StateSpace::StateType>();
    pose->setXY(x, y);
    pose->setYaw(yaw);
}

}  // namespace

TEST(PoseMetric, OnlyOmplsOwnPoseSpaces)
{
    EXPECT_TRUE(PoseMetric::of(*se3Space(1)));
    EXPECT_TRUE(PoseMetric::of(*se2Space(1)));
    EXPECT_FALSE(PoseMetric::of(ob::RealVectorStateSpace(3)));
    // A class derived from SE(3) may measure differently.
    class Derived : public ob::SE3StateSpace
    {
    };
    EXPECT_FALSE(PoseMetric::of(Derived()));
    ob::CompoundStateSpace two;
    two.addSubspace(se3Space(1), 1.0);
    two.addSubspace(se3Space(1), 1.0);
    EXPECT_FALSE(PoseMetric::of(two));
}

// A gap along one coordinate rules out a box only along a translation coordinate, and only when the
// box's own bound is beyond the bar too: boxes on the far side of a split, whatever their other
// coordinates, with translation weights from 1e-3 to 1e3.
TEST(PoseMetric, CoordinateGapRulesOutOnlyWhatTheBoxBoundDoes)
{
    test::TestRandom rng(67);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int ruledOut = 0;
    for (const bool planar : {false, true})
        for (const double weight : {1e-3, 1.0, 1e3})
        {
            ob::StateSpacePtr space = planar ? ob::StateSpacePtr(se2Space(50)) : ob::StateSpacePtr(se3Space(50));
            space->as<ob::CompoundStateSpace>()->setSubspaceWeight(0, weight);
            const PoseMetric metric = *PoseMetric::of(*space);
            ob::State *state = space->allocState();
            space->allocDefaultStateSampler()->sampleUniform(state);
            const PoseCoordinates q = metric.coordinates(state);
            space->freeState(state);
            for (int trial = 0; trial < 2000; ++trial)
            {
                const int d = int(unit(rng) * metric.dimensions()) % metric.dimensions();
                std::array<double, 7> low{}, high{};
                for (int k = 0; k < metric.dimensions(); ++k)
                {
                    const double a = q.values[std::size_t(k)] + (unit(rng) - 0.5) * (k < 3 ? 100.0 : 2.0);
                    const double b = a + unit(rng) * (k < 3 ? 10.0 : 0.5);
                    low[std::size_t(k)] = a;
                    high[std::size_t(k)] = b;
                }
                // The box beyond a split at q + gap along d.
                const double gap = unit(rng) * 30.0;
                low[std::size_t(d)] = q.values[std::size_t(d)] + gap;
                high[std::size_t(d)] = std::max(high[std::size_t(d)], low[std::size_t(d)]);
                const double enough = weight * unit(rng) * 40.0;
                if (!metric.coordinateGapBeyond(d, gap, enough))
                    continue;
                ++ruledOut;
                ASSERT_LT(d, planar ? 2 : 3);
                EXPECT_GT(metric.lowerBound(q, low.data(), high.data()), enough) << "trial " << trial;
            }
        }
    EXPECT_GT(ruledOut, 1000);
}

// The bounds a leaf's poses get side by side: never above OMPL's distance, and within rounding of
// the box bound over the pose alone, for random poses, near turns and yaws at the wrap. The
// translation's test (translationBeyond) rules a pose out only when its bound and distance are
// beyond the bar.
TEST(PoseMetric, PointBoundsBoundOmplsDistance)
{
    test::TestRandom rng(61);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int ruledOut = 0;
    for (const bool planar : {false, true})
    {
        const ob::StateSpacePtr space = planar ? ob::StateSpacePtr(se2Space(50)) : ob::StateSpacePtr(se3Space(50));
        const PoseMetric metric = *PoseMetric::of(*space);
        std::vector<StatePtr> states;
        for (int i = 0; i < 400; ++i)
        {
            states.push_back(space->allocState());
            if (planar)
                setPlanar(states.back(), 100 * unit(rng) - 50, 100 * unit(rng) - 50,
                          i % 5 == 0 ? (i % 2 ? kPi - 1e-12 : -kPi) : 2 * kPi * unit(rng) - kPi);
            else if (i % 4 == 0 && i > 0)
                setTurned(states.back(), states[i - 1], std::pow(10.0, -9 + 8 * unit(rng)));
            else
                setRandomSpatial(states.back(), 50 * unit(rng), rng);
        }
        std::vector<std::array<double, 7>> points;
        for (StatePtr s : states)
            points.push_back(metric.coordinates(s).values);
        std::vector<double> bounds(points.size());
        for (StatePtr query : states)
        {
            const PoseCoordinates q = metric.coordinates(query);
            ASSERT_TRUE(q.rotationBoundable);
            metric.pointLowerBounds(q, points.data(), points.size(), bounds.data());
            for (std::size_t i = 0; i < points.size(); ++i)
            {
                const double distance = space->distance(query, states[i]);
                EXPECT_LE(bounds[i], distance) << "pose " << i;
                const double box = metric.lowerBound(q, points[i].data(), points[i].data());
                EXPECT_NEAR(bounds[i], box, 1e-12 * (1.0 + box)) << "pose " << i;
                // The translation's test rules out only poses beyond the bar, and most of those
                // far beyond it.
                for (const double enough : {0.25 * distance, 0.999 * distance, distance, 2.0 * distance})
                    if (metric.translationBeyond(q, points[i], enough))
                    {
                        EXPECT_GT(distance, enough) << "pose " << i;
                        EXPECT_GT(bounds[i], enough) << "pose " << i;
                        ++ruledOut;
                    }
            }
        }
        for (StatePtr s : states)
            space->freeState(s);
    }
    EXPECT_GT(ruledOut, 1000);  // a test that is not idle
}

TEST(PoseNearestNeighbors, SpatialPosesMatchLinearSearch)
{
    const std::pair<double, double> weights[] = {{1.0, 1.0}, {1.0, 0.05}, {1.0, 20.0},
                                                 {0.3, 1.0}, {1.0, 0.0},  {0.0, 1.0}};
    for (const double extent : {1e-3, 1.0, 300.0})
        for (const auto &[translationWeight, rotationWeight] : weights)
        {
            auto space = se3Space(extent);
            space->setSubspaceWeight(0, translationWeight);
            space->setSubspaceWeight(1, rotationWeight);
            Fixture f(space);
            ASSERT_TRUE(f.hasMetric());
            test::TestRandom rng(test::seeded(11));
            // Grown one pose at a time, checked at every size up to 64 (insertions, splits and
            // rebuilds), then in steps.
            for (int i = 0; i < 1500; ++i)
            {
                StatePtr s = f.make();
                setRandomSpatial(s, extent, rng);
                f.add(s);
                if (i < 64 || i % 97 == 0)
                {
                    StatePtr query = f.make();
                    setRandomSpatial(query, extent, rng);
                    f.expectSameAnswers(query, 1 + i % 9, f.radiusHolding(query, 1 + i % 13));
                }
            }
            for (int i = 0; i < test::cases(200); ++i)
            {
                StatePtr query = f.make();
                setRandomSpatial(query, extent, rng);
                f.expectSameAnswers(query, 1 + i % 40, f.radiusHolding(query, 1 + i % 50));
            }
            StatePtr query = f.make();
            setRandomSpatial(query, extent, rng);
            f.expectSameAnswers(query, f.states().size() + 3, std::numeric_limits<double>::infinity());
        }
}

// Poses that differ by tiny turns (OMPL measures turns below 4.5e-5 rad as 0), by q against -q,
// and exact duplicates: no bound may exceed OMPL's distance.
TEST(PoseNearestNeighbors, NearAndEqualRotationsMatchLinearSearch)
{
    auto space = se3Space(5);
    Fixture f(space);
    test::TestRandom rng(test::seeded(12));
    std::vector<StatePtr> centres;
    for (int c = 0; c < 20; ++c)
    {
        StatePtr centre = f.make();
        setRandomSpatial(centre, 5, rng);
        f.add(centre);
        centres.push_back(centre);
        for (const double angle : {1e-9, 1e-6, 2e-5, 4.4e-5, 4.6e-5, 1e-4, 3e-4, 1e-3, kPi - 1e-7})
        {
            StatePtr turned = f.make();
            setTurned(turned, centre, angle);
            f.add(turned);
        }
        StatePtr flipped = f.make();
        const auto *p = centre->as<ob::SE3StateSpace::StateType>();
        const auto &q = p->rotation();
        setSpatial(flipped, p->getX(), p->getY(), p->getZ(), -q.x, -q.y, -q.z, -q.w);
        f.add(flipped);
        StatePtr duplicate = f.make();
        space->copyState(duplicate, centre);
        f.add(duplicate);
        // Norms off 1 by less than OMPL's 1e-9 tolerance.
        for (const double stretch : {1.0 + 9e-10, 1.0 - 9e-10})
        {
            StatePtr stretched = f.make();
            setSpatial(stretched, p->getX(), p->getY(), p->getZ(), stretch * q.x, stretch * q.y, stretch * q.z,
                       stretch * q.w);
            f.add(stretched);
        }
    }
    // More identical poses than a leaf holds: the leaf cannot be split and grows.
    for (int i = 0; i < 40; ++i)
    {
        StatePtr duplicate = f.make();
        space->copyState(duplicate, centres.front());
        f.add(duplicate);
    }
    for (StatePtr centre : centres)
        for (const double angle : {0.0, 3e-5, 5e-5, 2e-4})
        {
            StatePtr query = f.make();
            setTurned(query, centre, angle);
            f.expectSameAnswers(query, 7, 0.0);
            f.expectSameAnswers(query, 15, 1e-4);
            f.expectSameAnswers(query, 3, f.radiusHolding(query, 30));
        }
}

TEST(PoseNearestNeighbors, PlanarPosesMatchLinearSearch)
{
    for (const double extent : {1e-2, 1.0, 1e4})
    {
        auto space = se2Space(extent);
        Fixture f(space);
        ASSERT_TRUE(f.hasMetric());
        test::TestRandom rng(test::seeded(13));
        std::uniform_real_distribution<double> coordinate(-extent, extent);
        std::uniform_real_distribution<double> yaw(-kPi, std::nextafter(kPi, 0.0));
        // Yaws across the wrap at +-pi (OMPL's SO(2) is [-pi, pi)), and some poses that differ by
        // the yaw alone.
        const double edges[] = {std::nextafter(kPi, 0.0), -kPi, kPi - 1e-12, -kPi + 1e-12, 0.0, kPi / 2};
        for (int i = 0; i < 1200; ++i)
        {
            StatePtr s = f.make();
            if (i % 5 == 0)
                setPlanar(s, 0.25 * extent, -0.5 * extent, edges[i % 6]);
            else
                setPlanar(s, coordinate(rng), coordinate(rng), yaw(rng));
            f.add(s);
            if (i < 40 || i % 101 == 0)
            {
                StatePtr query = f.make();
                setPlanar(query, coordinate(rng), coordinate(rng), yaw(rng));
                f.expectSameAnswers(query, 1 + i % 7, f.radiusHolding(query, 1 + i % 11));
            }
        }
        for (int i = 0; i < test::cases(200); ++i)
        {
            StatePtr query = f.make();
            if (i % 4 == 0)
                setPlanar(query, 0.25 * extent, -0.5 * extent, edges[i % 6]);
            else
                setPlanar(query, coordinate(rng), coordinate(rng), yaw(rng));
            f.expectSameAnswers(query, 1 + i % 30, f.radiusHolding(query, 1 + i % 40));
        }
    }
}

TEST(PoseNearestNeighbors, RemovalsAndOddValuesMatchLinearSearch)
{
    auto space = se3Space(2);
    Fixture f(space);
    test::TestRandom rng(test::seeded(14));
    for (int i = 0; i < 400; ++i)
    {
        StatePtr s = f.make();
        setRandomSpatial(s, 2, rng);
        f.add(s);
    }
    // A pose with a coordinate that is not a number is measured, never bounded; the others are
    // found as before.
    StatePtr odd = f.make();
    setSpatial(odd, std::nan(""), 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    f.add(odd);
    std::vector<StatePtr> queries;
    for (int i = 0; i < 30; ++i)
    {
        queries.push_back(f.make());
        setRandomSpatial(queries.back(), 2, rng);
    }
    for (StatePtr query : queries)
        EXPECT_EQ(space->distance(query, f.nearest(query)), space->distance(query, f.nearestByLinearSearch(query)));
    f.remove(odd);
    const std::vector<StatePtr> added(f.states().begin(), f.states().begin() + 400);
    for (std::size_t i = 0; i < added.size(); i += 2)
        f.remove(added[i]);
    for (StatePtr query : queries)
        f.expectSameAnswers(query, 6, f.radiusHolding(query, 9));
    for (StatePtr s : added)
        f.remove(s);
    for (StatePtr query : queries)
        f.expectSameAnswers(query, 6, 1.0);
}

// With either structure, the same seed plans the same tree and so the same path: the structure
// finds the very neighbours OMPL's default finds.
TEST(PoseNearestNeighbors, PlannersPlanTheSameTreeAsWithOmplsDefault)
{
    for (const bool planar : {false, true})
    {
        const ob::StateSpacePtr space = planar ? ob::StateSpacePtr(se2Space(1)) : ob::StateSpacePtr(se3Space(1));
        // A wall at x in [-0.1, 0.1] with a narrow window at y in [0.595, 0.605]: free poses are only those
        // whose position is outside the wall or inside the window.
        auto setup = std::make_shared<ompl::geometric::SimpleSetup>(space);
        setup->setStateValidityChecker([planar](const ob::State *s) {
            const double x =
                planar ? s->as<ob::SE2StateSpace::StateType>()->getX() : s->as<ob::SE3StateSpace::StateType>()->getX();
            const double y =
                planar ? s->as<ob::SE2StateSpace::StateType>()->getY() : s->as<ob::SE3StateSpace::StateType>()->getY();
            return std::fabs(x) > 0.1 || std::fabs(y - 0.6) < 0.005;
        });
        ob::ScopedState<> start(space), goal(space);
        start.random();
        goal.random();
        if (planar)
        {
            setPlanar(start.get(), -0.8, -0.8, 0.0);
            setPlanar(goal.get(), 0.8, -0.8, 1.0);
        }
        else
        {
            setSpatial(start.get(), -0.8, -0.8, 0.0, 0.0, 0.0, 0.0, 1.0);
            setSpatial(goal.get(), 0.8, -0.8, 0.3, 0.0, 0.0, std::sin(0.5), std::cos(0.5));
        }
        setup->setStartAndGoalStates(start, goal);
        setup->getSpaceInformation()->setStateValidityCheckingResolution(0.01);
        // The first set-up draws samples of its own (OMPL's sanity checks of the space): done
        // once here, so that both runs below start from the same seed.
        setup->setup();
        const auto makePlannerAndSetUp = [&](const char *planner, NeighborSearch search) {
            ob::PlannerPtr made = makePlanner({planner, "", {}}, setup->getSpaceInformation(), search);
            made->setProblemDefinition(setup->getProblemDefinition());
            made->setup();
            return made;
        };

        for (const char *planner : {"rrtconnect", "rrt"})
        {
            const std::string what = std::string(planner) + (planar ? " on SE(2)" : " on SE(3)");
            std::vector<std::vector<double>> paths[2];
            std::size_t vertices[2] = {0, 0};
            const NeighborSearch searches[] = {NeighborSearch::Poses, NeighborSearch::OmplDefault};
            for (int run = 0; run < 2; ++run)
            {
                const auto level = ompl::msg::getLogLevel();
                ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
                ompl::RNG::setSeed(std::uint_fast32_t(test::seeded(21)));
                setup->clear();
                setup->setPlanner(makePlanner({planner, "", {}}, setup->getSpaceInformation(), searches[run]));
                const ob::PlannerStatus status = setup->solve(ob::timedPlannerTerminationCondition(60.0));
                ompl::msg::setLogLevel(level);
                ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << what;
                ob::PlannerData data(setup->getSpaceInformation());
                setup->getPlannerData(data);
                vertices[run] = data.numVertices();
                for (const ob::State *s : setup->getSolutionPath().getStates())
                {
                    std::vector<double> values;
                    space->copyToReals(values, s);
                    paths[run].push_back(values);
                }
            }
            EXPECT_GT(vertices[0], 50u) << what << ": the window should take a tree of some size to find";
            EXPECT_TRUE(searchesWithPoseNeighbors(*makePlannerAndSetUp(planner, NeighborSearch::Poses))) << what;
            EXPECT_FALSE(searchesWithPoseNeighbors(*makePlannerAndSetUp(planner, NeighborSearch::OmplDefault))) << what;
            EXPECT_EQ(vertices[0], vertices[1]) << what;
            EXPECT_EQ(paths[0], paths[1]) << what;
        }
        // PRM and PRM* find their roadmap neighbours with the structure too (their roadmaps depend
        // on the timing of PRM's second thread, so only the solution is asked for here).
        // max_nearest_neighbors makes PRM's structure at once: it must still be the pose search.
        EXPECT_TRUE(searchesWithPoseNeighbors(*makePlanner({"prm", "", {{"max_nearest_neighbors", "12"}}},
                                                           setup->getSpaceInformation(), NeighborSearch::Poses)));
        EXPECT_TRUE(searchesWithPoseNeighbors(
            *makePlanner({"prmstar", "", {}}, setup->getSpaceInformation(), NeighborSearch::Poses)));
        setup->clear();
        setup->setPlanner(makePlanner({"prm", "", {}}, setup->getSpaceInformation(), NeighborSearch::Poses));
        const auto level = ompl::msg::getLogLevel();
        ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
        // PRM stops once its second thread finds a path (within milliseconds here, alone); the limit
        // leaves room for a machine busy with other tests. PRM*, which optimizes until the limit and
        // so can only be asked for a path by a given time, once fell short of one in 2 s there.
        const ob::PlannerStatus status = setup->solve(ob::timedPlannerTerminationCondition(30.0));
        ompl::msg::setLogLevel(level);
        EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << (planar ? "prm on SE(2)" : "prm on SE(3)");
        if (status == ob::PlannerStatus::EXACT_SOLUTION)
            EXPECT_TRUE(setup->getSolutionPath().check());
    }
}
