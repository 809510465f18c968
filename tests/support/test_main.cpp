// SPDX-License-Identifier: BSD-3-Clause
// The main of every test program: OMPL's random generator is reseeded before each test, so a test
// draws the same samples whether it runs alone (as CTest runs it) or after others, and a failing
// test prints the seed that reproduces it.
#include "support/test_support.h"

#ifdef HYBRIDCD_TESTS_WITH_OMPL
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#endif

#include <gtest/gtest.h>

#include <iostream>

namespace
{
class SeedEveryTest : public ::testing::EmptyTestEventListener
{
    void OnTestStart(const ::testing::TestInfo &) override
    {
#ifdef HYBRIDCD_TESTS_WITH_OMPL
        // OMPL complains when it is reseeded after sampling began; reseeding is what is wanted here.
        const auto level = ompl::msg::getLogLevel();
        ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
        ompl::RNG::setSeed(std::uint_fast32_t(hcd::test::seed()));
        ompl::msg::setLogLevel(level);
#endif
    }

    void OnTestEnd(const ::testing::TestInfo &info) override
    {
        if (info.result() && info.result()->Failed())
            std::cout << "[   SEED   ] " << info.test_suite_name() << "." << info.name()
                      << " ran with HYBRIDCD_TEST_SEED=" << hcd::test::seed() << "\n";
    }
};
}  // namespace

int main(int argc, char **argv)
{
    ::testing::InitGoogleTest(&argc, argv);
    ::testing::UnitTest::GetInstance()->listeners().Append(new SeedEveryTest);
    return RUN_ALL_TESTS();
}
