// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/retraction_sampler.h"

#include <ompl/base/SpaceInformation.h>

namespace hcd
{
RetractionStateSampler::RetractionStateSampler(const ompl::base::StateSpace *space,
                                               std::shared_ptr<const StateValidityChecker> validity)
    : ompl::base::StateSampler(space),
      uniform_(space->allocDefaultStateSampler()),
      validity_(std::move(validity)),
      scratch_(space->allocState())
{
}

RetractionStateSampler::~RetractionStateSampler() { space_->freeState(scratch_); }

void RetractionStateSampler::sampleUniform(ompl::base::State *state)
{
    uniform_->sampleUniform(state);
    ++drawn_;
    if (validity_->collisionFree(state))
        return;
    if (validity_->pushedOut(state, scratch_))
    {
        space_->copyState(state, scratch_);
        ++retracted_;
    }
}

void RetractionStateSampler::sampleUniformNear(ompl::base::State *state, const ompl::base::State *near, double distance)
{
    uniform_->sampleUniformNear(state, near, distance);
}

void RetractionStateSampler::sampleGaussian(ompl::base::State *state, const ompl::base::State *mean, double stdDev)
{
    uniform_->sampleGaussian(state, mean, stdDev);
}

void useRetractionSampling(PlanningProblem &planning)
{
    const std::shared_ptr<const StateValidityChecker> validity = planning.validity;
    planning.setup->getStateSpace()->setStateSamplerAllocator(
        [validity](const ompl::base::StateSpace *space) -> ompl::base::StateSamplerPtr {
            return std::make_shared<RetractionStateSampler>(space, validity);
        });
}
}  // namespace hcd
