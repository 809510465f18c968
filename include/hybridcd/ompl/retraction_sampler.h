// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: a state sampler that retracts colliding samples onto the free space's boundary.
//
// Narrow passages (Twistycool's hole, the alpha puzzle) hold a tiny share of the space, so uniform
// samples rarely land in them; but many colliding samples land in the walls around them. Retraction
// (as in OBPRM and retraction-based RRT) pushes each colliding sample out along the penetration
// vectors of its intersecting triangle pairs to a nearby free state, keeping its orientation: the
// samples then gather on the obstacles' surfaces, where passages are. Only an exact checker with
// penetration vectors can do this cheaply; a free sample is kept as drawn. A sample that cannot be
// pushed out (deeply inside, or only contained in a solid) is returned as drawn, and the planner
// rejects it as it would any colliding sample.
#pragma once

#include "hybridcd/ompl/planning_problem.h"

#include <ompl/base/StateSampler.h>

#include <atomic>
#include <memory>

namespace hcd
{
class RetractionStateSampler : public ompl::base::StateSampler
{
public:
    /// Draws from the space's default sampler and retracts through `validity`.
    RetractionStateSampler(const ompl::base::StateSpace *space, std::shared_ptr<const StateValidityChecker> validity);
    ~RetractionStateSampler() override;
    RetractionStateSampler(const RetractionStateSampler &) = delete;
    RetractionStateSampler &operator=(const RetractionStateSampler &) = delete;

    void sampleUniform(ompl::base::State *state) override;
    void sampleUniformNear(ompl::base::State *state, const ompl::base::State *near, double distance) override;
    void sampleGaussian(ompl::base::State *state, const ompl::base::State *mean, double stdDev) override;

    /// Uniform samples drawn, and how many of them were colliding and retracted to a valid state.
    std::uint64_t drawn() const { return drawn_; }
    std::uint64_t retracted() const { return retracted_; }

private:
    ompl::base::StateSamplerPtr uniform_;
    std::shared_ptr<const StateValidityChecker> validity_;
    ompl::base::State *scratch_;
    std::uint64_t drawn_ = 0, retracted_ = 0;
};

/// Makes every state sampler of `planning`'s space a RetractionStateSampler over its validity
/// checker (each planner thread allocates its own sampler). Call it after installChecker, which
/// replaces the validity checker.
void useRetractionSampling(PlanningProblem &planning);
}  // namespace hcd
