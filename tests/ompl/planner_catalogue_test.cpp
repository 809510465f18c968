// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/planners/planner_catalogue.h"

#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>

#include <ompl/base/spaces/SE2StateSpace.h>

#include <gtest/gtest.h>

using namespace hcd;

namespace
{
ompl::base::SpaceInformationPtr se3()
{
    auto space = std::make_shared<ompl::base::SE3StateSpace>();
    ompl::base::RealVectorBounds b(3);
    b.setLow(-1);
    b.setHigh(1);
    space->setBounds(b);
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    si->setStateValidityChecker([](const ompl::base::State *) { return true; });
    si->setup();
    return si;
}
}  // namespace

TEST(PlannerCatalogue, EveryNamedPlannerConstructs)
{
    const auto si = se3();
    const auto names = plannerNames();
    for (const char *expected :
         {"rrtconnect", "rrt",      "rrtstar", "prm",   "prmstar", "lazyprm", "lazyprmstar", "kpiece",
          "bkpiece",    "lbkpiece", "est",     "biest", "sbl",     "stride",  "pdst",        "fmt",
          "bfmt",       "bitstar",  "lbtrrt",  "trrt",  "spars",   "spars2",  "cforest",     "aps"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    for (const std::string &n : names)
    {
        const auto planner = makePlanner({n, "", {}}, si);
        ASSERT_TRUE(planner) << n;
    }
}

TEST(PlannerCatalogue, InformedSetPlannersAreRefusedWhereOmplCannotMakeTheirSets)
{
    // Two SE(2) poses in one compound space, as a scene of two robots plans: OMPL 1.5's informed
    // sampler throws there (CForest's worker threads then ended the process).
    auto compound = std::make_shared<ompl::base::CompoundStateSpace>();
    for (int robot = 0; robot < 2; ++robot)
    {
        auto pose = std::make_shared<ompl::base::SE2StateSpace>();
        ompl::base::RealVectorBounds bounds(2);
        bounds.setLow(-1);
        bounds.setHigh(1);
        pose->setBounds(bounds);
        compound->addSubspace(pose, 1.0);
    }
    auto scene = std::make_shared<ompl::base::SpaceInformation>(compound);
    scene->setStateValidityChecker([](const ompl::base::State *) { return true; });
    scene->setup();
    for (const char *name : {"abitstar", "aitstar", "bitstar", "cforest", "informedrrtstar", "sorrtstar"})
    {
        try
        {
            makePlanner({name, "", {}}, scene);
            ADD_FAILURE() << name << " made on a compound of poses";
        }
        catch (const std::invalid_argument &e)
        {
            EXPECT_NE(std::string(e.what()).find("samples OMPL's informed sets"), std::string::npos) << e.what();
        }
        EXPECT_TRUE(makePlanner({name, "", {}}, se3())) << name;  // one robot: made as before
    }
    for (const char *name : {"rrtconnect", "rrtstar", "prm", "kpiece"})
        EXPECT_TRUE(makePlanner({name, "", {}}, scene)) << name;
    // RRT* and RRTX with informed sampling or sample rejection sample the informed set too.
    for (const char *name : {"rrtstar", "rrtxstatic"})
        for (const char *key : {"informed_sampling", "sample_rejection"})
        {
            try
            {
                makePlanner({name, "", {{key, "1"}}}, scene);
                ADD_FAILURE() << name << " with " << key << "=1 made on a compound of poses";
            }
            catch (const std::invalid_argument &e)
            {
                EXPECT_NE(std::string(e.what()).find(std::string(key) + "=1 samples OMPL's informed sets"),
                          std::string::npos)
                    << e.what();
            }
            EXPECT_TRUE(makePlanner({name, "", {{key, "0"}}}, scene)) << name << " " << key << "=0";
            EXPECT_TRUE(makePlanner({name, "", {{key, "1"}}}, se3())) << name << " " << key << "=1, one robot";
        }
}

TEST(PlannerCatalogue, BitStarKeepsOnlyThreadSafeProgress)
{
    // OMPL's Benchmark reads progress properties from a second thread while the planner runs; BIT*'s
    // graph and sample counts are not safe to read then (bench runs died at random). The cost and
    // the counters stay, for anytime summaries.
    const auto si = se3();
    for (const char *name : {"bitstar", "abitstar"})
    {
        const auto planner = makePlanner({name, "", {}}, si);
        const auto &progress = planner->getPlannerProgressProperties();
        for (const char *unsafe : kThreadUnsafeBitStarProgress)
            EXPECT_EQ(progress.count(unsafe), 0u) << name << ": " << unsafe;
        EXPECT_EQ(progress.count("best cost DOUBLE"), 1u) << name;
        EXPECT_EQ(progress.count("state collision checks INTEGER"), 1u) << name;
    }
    // The names are OMPL's: the unwrapped planner has them.
    const ompl::geometric::BITstar plain(si);
    for (const char *unsafe : kThreadUnsafeBitStarProgress)
        EXPECT_EQ(plain.getPlannerProgressProperties().count(unsafe), 1u) << unsafe;
}

TEST(PlannerCatalogue, AppliesNamesAndParameters)
{
    const auto planner = makePlanner({"RRT", "fast rrt", {{"range", "10"}, {"goal_bias", "0.2"}}}, se3());
    EXPECT_EQ(planner->getName(), "fast rrt");
    std::string value;
    ASSERT_TRUE(planner->params().getParam("range", value));
    EXPECT_EQ(std::stod(value), 10.0);
}

// OMPL sets any value a parameter is given; values below the low end of its declared range, or not
// finite, are refused (a negative range makes RRTConnect step backwards). The high end is only a
// suggestion: a range above OMPL's 10000 is kept.
TEST(PlannerCatalogue, ValuesBelowTheDeclaredRangeAreRefused)
{
    for (const auto &[key, value] : std::vector<std::pair<std::string, std::string>>{
             {"range", "-5"}, {"range", "nan"}, {"range", "inf"}, {"goal_bias", "-0.1"}})
    {
        try
        {
            makePlanner({"rrt", "", {{key, value}}}, se3());
            ADD_FAILURE() << key << " = " << value << " was accepted";
        }
        catch (const std::invalid_argument &e)
        {
            const std::string message = e.what();
            EXPECT_NE(message.find("invalid value '" + value + "' for parameter '" + key + "'"), std::string::npos)
                << message;
            EXPECT_TRUE(message.find("below") != std::string::npos || message.find("finite") != std::string::npos)
                << message;
        }
    }
    const auto planner = makePlanner({"rrtconnect", "", {{"range", "25000"}}}, se3());
    std::string range;
    ASSERT_TRUE(planner->params().getParam("range", range));
    EXPECT_EQ(std::stod(range), 25000.0);
    EXPECT_NO_THROW(makePlanner({"rrt", "", {{"goal_bias", "0"}, {"range", "0.5"}}}, se3()));
}

TEST(PlannerCatalogue, UnknownNamesListTheValidOnes)
{
    try
    {
        makePlanner({"nosuchplanner", "", {}}, se3());
        FAIL();
    }
    catch (const std::invalid_argument &e)
    {
        EXPECT_NE(std::string(e.what()).find("rrtconnect"), std::string::npos) << e.what();
    }
    try
    {
        makePlanner({"rrt", "", {{"no_such_param", "1"}}}, se3());
        FAIL();
    }
    catch (const std::invalid_argument &e)
    {
        EXPECT_NE(std::string(e.what()).find("range"), std::string::npos) << e.what();
    }
}
