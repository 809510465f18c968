// SPDX-License-Identifier: BSD-3-Clause
// Per-motion comparison: the same random motions (fixed seed; valid start, end within the range a
// sampling planner would use) through hybridcd's continuous validator and OMPL's discrete validator
// at its default resolution, with hybridcd's and with FCL's state checker. Reports the median time
// per motion (median and mean) and how many motions each discrete validator accepts although they touch an obstacle
// (the continuous validator rejects them; brute force at 20x OMPL's resolution confirms contact).
//
//   hybridcd_bench_motions [--motions N] [--seed S] [--repeat K] [--no-touching] [--translations] PROBLEM.cfg...
//
// --no-touching skips the brute-force pass (the last column then reads "-"), for quick timing runs.
// --translations makes every motion a pure translation (the end keeps the start's rotation) and adds
// a row with the exact first contact of the time-augmented LP turned off (bisection alone).
#include "bench_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>

using namespace hcd;
using hcd::bench::median;
namespace ob = ompl::base;

namespace
{

struct Timing
{
    double median = 0.0, mean = 0.0;
    std::vector<char> valid;
};

using TimedCheck = std::function<bool(ob::State *, ob::State *)>;

// Each check over every motion in turn, `repeat` passes of all the checks one after the other,
// each motion timed by its fastest pass: a long motion's time no longer moves with what else the
// machine did meanwhile, the checks' passes interleave (so the machine's slow spells fall on all
// of them alike, and ratios between them hold), and each check still follows the motion before it
// (the caches a query stream warms stay as one pass leaves them).
std::vector<Timing> timeAll(const std::vector<std::pair<ob::State *, ob::State *>> &motions,
                            const std::vector<TimedCheck> &checks, std::size_t repeat)
{
    std::vector<std::vector<double>> us(checks.size(),
                                        std::vector<double>(motions.size(), std::numeric_limits<double>::infinity()));
    std::vector<Timing> timings(checks.size());
    for (Timing &t : timings)
        t.valid.assign(motions.size(), 0);
    for (std::size_t pass = 0; pass < repeat; ++pass)
        for (std::size_t c = 0; c < checks.size(); ++c)
            for (std::size_t i = 0; i < motions.size(); ++i)
            {
                const auto t0 = std::chrono::steady_clock::now();
                timings[c].valid[i] = checks[c](motions[i].first, motions[i].second);
                us[c][i] = std::min(
                    us[c][i], std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
            }
    for (std::size_t c = 0; c < checks.size(); ++c)
    {
        double sum = 0.0;
        for (double t : us[c])
            sum += t;
        timings[c].median = median(us[c]);
        timings[c].mean = motions.empty() ? 0.0 : sum / double(motions.size());
    }
    return timings;
}
}  // namespace

namespace
{
// Gives `b` the rotation of `a`.
void keepRotation(const ob::SpaceInformation &si, bool planar, const ob::State *a, ob::State *b)
{
    if (planar)
        b->as<ob::SE2StateSpace::StateType>()->setYaw(a->as<ob::SE2StateSpace::StateType>()->getYaw());
    else
        si.getStateSpace()->as<ob::SE3StateSpace>()->getSubspace(1)->copyState(
            b->as<ob::SE3StateSpace::StateType>()->as<ob::SO3StateSpace::StateType>(1),
            a->as<ob::SE3StateSpace::StateType>()->as<ob::SO3StateSpace::StateType>(1));
}

int run(const cli::CommandLine &cl, const CheckerCatalogue &checkers)
{
    const std::size_t count = std::size_t(cl.positiveInteger("motions", 2000));
    const std::size_t repeat = std::size_t(cl.positiveInteger("repeat", 1));
    const std::uint_fast32_t seed = cl.has("seed") ? cli::seedOf(cl) : 1;
    const bool touchingPass = !cl.has("no-touching");
    const bool translations = cl.has("translations");
    // The planning set-up brackets first contacts to 1e-3 of a motion or one validity segment;
    // check-motion and the API default to 1e-6.
    const std::optional<double> contactTolerance =
        cl.has("contact-tolerance") ? std::optional<double>(cl.positiveNumber("contact-tolerance", 1e-6))
                                    : std::nullopt;
    const std::vector<std::string> &problems = cl.positionals();
    if (problems.empty())
        throw cli::UsageError("missing the problem files (.cfg)");
    ompl::RNG::setSeed(seed);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    std::cout << "| problem | validator | state checker | median us/motion | vs discrete+fcl | mean us/motion | "
                 "vs discrete+fcl | accepted | accepted but touching |\n|---|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string &cfg : problems)
    {
        const LoadedProblem problem = loadProblem(cfg);
        PlanningProblem obb =
            makePlanningProblem(problem, checkers.make("obb", problem.scene), MotionCheck::Continuous);
        PlanningProblem fcl = makePlanningProblem(problem, checkers.make("fcl", problem.scene), MotionCheck::Discrete);
        PlanningProblem obbDiscrete =
            makePlanningProblem(problem, checkers.make("obb", problem.scene), MotionCheck::Discrete);
        for (auto *p : {&obb, &fcl, &obbDiscrete})
            p->setup->setup();
        if (contactTolerance)
            obb.continuousValidator->setContactTolerance(*contactTolerance);
        const auto si = obb.setup->getSpaceInformation();
        auto sampler = si->allocStateSampler();
        // Motions as RRT-style planners make them: valid start, end at up to 20% of the extent.
        std::vector<std::pair<ob::State *, ob::State *>> motions;
        while (motions.size() < count)
        {
            ob::State *a = si->allocState(), *b = si->allocState();
            do
                sampler->sampleUniform(a);
            while (!si->isValid(a));
            do
            {
                sampler->sampleUniformNear(b, a, 0.2 * si->getMaximumExtent());
                if (translations)
                    keepRotation(*si, problem.config.planar, a, b);
                si->enforceBounds(b);
            } while (!si->isValid(b));
            motions.emplace_back(a, b);
        }
        // With lastValid asked for, the validator also brackets the first contact of a blocked motion.
        std::pair<ob::State *, double> lastValid(si->allocState(), 0.0);
        auto &validator = *obb.continuousValidator;
        std::vector<TimedCheck> checks{
            [&](ob::State *a, ob::State *b) { return si->checkMotion(a, b); },
            [&](ob::State *a, ob::State *b) { return si->getMotionValidator()->checkMotion(a, b, lastValid); },
            [&](ob::State *a, ob::State *b) { return fcl.setup->getSpaceInformation()->checkMotion(a, b); },
            [&](ob::State *a, ob::State *b) { return obbDiscrete.setup->getSpaceInformation()->checkMotion(a, b); }};
        // With --translations, also without the exact first contact (bisection alone).
        if (translations)
            checks.push_back([&, finder = std::make_shared<const TranslationContactFinder>(problem.scene)](
                                 ob::State *a, ob::State *b) {
                validator.setTranslationContactFinder(nullptr);
                const bool free = validator.checkMotion(a, b, lastValid);
                validator.setTranslationContactFinder(finder);
                return free;
            });
        const std::vector<Timing> timings = timeAll(motions, checks, repeat);
        si->freeState(lastValid.first);
        const Timing &continuous = timings[0], &bracketed = timings[1], &discreteFcl = timings[2],
                     &discreteObb = timings[3];
        // Touching: brute force at 20x OMPL's resolution finds a contact.
        const auto reference = checkers.make("bruteforce", problem.scene);
        ob::State *s = si->allocState();
        std::vector<char> touching;
        for (const auto &[a, b] : motions)
        {
            if (!touchingPass)
                break;
            const unsigned n = 20 * std::max(1u, si->getStateSpace()->validSegmentCount(a, b));
            bool hit = false;
            for (unsigned k = 0; k <= n && !hit; ++k)
            {
                si->getStateSpace()->interpolate(a, b, double(k) / n, s);
                hit = reference->collides(poseOfState(s, problem.config.planar));
            }
            touching.push_back(hit);
        }
        si->freeState(s);
        const auto row = [&](const char *validator, const char *checker, const Timing &r) {
            std::size_t accepted = 0, wrong = 0;
            for (std::size_t i = 0; i < motions.size(); ++i)
            {
                accepted += r.valid[i];
                wrong += touchingPass && r.valid[i] && touching[i];
            }
            std::cout << std::fixed << std::setprecision(1) << "| " << problem.config.name << " | " << validator
                      << " | " << checker << " | " << r.median << " | " << std::setprecision(2)
                      << r.median / discreteFcl.median << " | " << std::setprecision(1) << r.mean << " | "
                      << std::setprecision(2) << r.mean / discreteFcl.mean << " | " << accepted << " | "
                      << (touchingPass ? std::to_string(wrong) : std::string("-")) << " |\n";
        };
        row("continuous", "obb", continuous);
        row("continuous, lastValid", "obb", bracketed);
        if (translations)
            row("continuous, lastValid, bisection only", "obb", timings[4]);
        row("discrete", "obb", discreteObb);
        row("discrete", "fcl", discreteFcl);
        for (auto &[a, b] : motions)
        {
            si->freeState(a);
            si->freeState(b);
        }
    }
    return 0;
}
}  // namespace

int main(int argc, char **argv)
{
    const CheckerCatalogue checkers = checkersWithFcl();
    CLI::App app("Time per motion of the continuous and discrete validators on the same random motions, as a "
                 "Markdown table.",
                 "hybridcd_bench_motions");
    cli::configureApp(app);
    cli::CommandLine cl(app);
    cl.positionals("PROBLEM.cfg", "the problems, one table block per problem")
        .option("motions", "N", "random motions per problem (default 2000)")
        .option("seed", "N", "seed of OMPL's random numbers (default 1)")
        .option("repeat", "K", "check each motion K times and keep its fastest time (default 1)")
        .flag("no-touching", "skip the brute-force pass (the last column then reads '-')")
        .flag("translations", "pure translations only, with a row for the bisection alone")
        .option("contact-tolerance", "FRACTION",
                "bracket first contacts to this fraction of a motion (default: the planning set-up's, 1e-3 or one "
                "validity segment)")
        .footer("\nExample:\n  hybridcd_bench_motions --motions 500 --no-touching problems/window_3d.cfg\n");
    return bench::runProgram(app, cl, argc, argv, [&] { return run(cl, checkers); });
}
