// SPDX-License-Identifier: BSD-3-Clause
// The checker catalogue: names with descriptions, no duplicates, options refused where unsupported.
#include "support/test_support.h"

#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

using namespace hcd;

TEST(CheckerCatalogue, BuiltInListsTheCoreCheckersWithDescriptions)
{
    const CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
    const std::vector<std::string> expected = {"obb",    "ellipsoid",  "hybrid",     "hybrid-ellipsoid-first",
                                               "sphere", "aabb",       "aabb-fixed", "kdop14",
                                               "kdop18", "kdop26",     "ssv",        "octree",
                                               "auto",   "bruteforce", "lp",         "medial",
                                               "ctree"};
    EXPECT_EQ(catalogue.names(), expected);
    for (const CheckerEntry &e : catalogue.entries())
    {
        EXPECT_FALSE(e.description.empty()) << e.name;
        EXPECT_EQ(e.description.find('\n'), std::string::npos) << e.name << ": one line";
    }
    EXPECT_EQ(catalogue.find("nosuch"), nullptr);
}

TEST(CheckerCatalogue, UnknownNamesAndDuplicatesAreRefused)
{
    CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
    try
    {
        catalogue.check("nosuch");
        FAIL() << "an unknown name was accepted";
    }
    catch (const std::invalid_argument &e)
    {
        EXPECT_NE(std::string(e.what()).find("valid checkers: obb, ellipsoid"), std::string::npos) << e.what();
    }
    const CheckerFactory factory = [](const CollisionScene &s, const CheckerOptions &) {
        return std::make_unique<BruteForceChecker>(s);
    };
    EXPECT_THROW(catalogue.add({"obb", "again", factory}), std::invalid_argument);
    EXPECT_THROW(catalogue.add({"", "nameless", factory}), std::invalid_argument);
    catalogue.add({"mine", "an application's own checker", factory});
    EXPECT_EQ(catalogue.names().back(), "mine");
    // Another catalogue is untouched: nothing is shared.
    EXPECT_EQ(CheckerCatalogue::builtIn().find("mine"), nullptr);
}

TEST(CheckerCatalogue, ApproximateModeOnlyWhereSupported)
{
    const CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
    CheckerOptions approximate;
    approximate.approximateTolerance = 0.01;
    EXPECT_NO_THROW(catalogue.check("lp", approximate));
    EXPECT_NO_THROW(catalogue.check("medial", approximate));
    for (const std::string &name : catalogue.names())
    {
        if (name == "lp" || name == "medial")
            continue;
        try
        {
            catalogue.check(name, approximate);
            ADD_FAILURE() << name << " accepted approximate mode";
        }
        catch (const std::invalid_argument &e)
        {
            EXPECT_NE(std::string(e.what()).find("has no approximate mode (checkers that have one: lp, medial)"),
                      std::string::npos)
                << e.what();
        }
    }
    approximate.approximateTolerance = -1.0;
    EXPECT_THROW(catalogue.check("lp", approximate), std::invalid_argument);
    // make() checks too, before building anything.
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    approximate.approximateTolerance = 0.01;
    EXPECT_THROW(catalogue.make("obb", problem.scene, approximate), std::invalid_argument);
    EXPECT_NE(catalogue.make("lp", problem.scene, approximate), nullptr);
}
