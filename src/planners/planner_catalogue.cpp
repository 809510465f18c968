// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/planners/planner_catalogue.h"

#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/planners/pose_nearest_neighbors.h"

#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>
#include <ompl/geometric/planners/AnytimePathShortening.h>
#include <ompl/geometric/planners/cforest/CForest.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/quotientspace/QRRT.h>
#include <ompl/geometric/planners/rlrt/BiRLRT.h>
#include <ompl/geometric/planners/rlrt/RLRT.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/rrt/pRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sbl/pSBL.h>
#include <ompl/geometric/planners/sst/SST.h>
#include <ompl/geometric/planners/stride/STRIDE.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>

// Left out on purpose: TSRRT and VFRRT need a task space / vector field, XXL cannot plan without a
// problem-specific decomposition, Thunder/Lightning need an experience database, and LazyLBTRRT
// trips an assertion inside Debian's libompl (LPAstarOnGraph::removeEdge) on ordinary problems with
// obstacles, which aborts the whole process.

namespace hcd
{
namespace
{

namespace og = ompl::geometric;

using Factory = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &, NeighborSearch)>;

template <typename T>
Factory make()
{
    return [](const ompl::base::SpaceInformationPtr &si, NeighborSearch) -> ompl::base::PlannerPtr {
        return std::make_shared<T>(si);
    };
}

// T, or WithPoses (T searching its trees or roadmap with PoseNearestNeighbors) when asked for.
template <typename T, typename WithPoses>
Factory makeWithPoseSearch()
{
    return [](const ompl::base::SpaceInformationPtr &si, NeighborSearch search) -> ompl::base::PlannerPtr {
        if (search == NeighborSearch::Poses)
            return std::make_shared<WithPoses>(si);
        return std::make_shared<T>(si);
    };
}

// The planners' nearest neighbours found by PoseNearestNeighbors on SE(2) and SE(3): the same
// neighbours as OMPL's GNAT finds (so the same tree or roadmap for the same seed), measured with a
// fraction of the distances. Any other space keeps OMPL's default (nullptr here). setup() makes the
// structures only where the planner has none yet, so they are installed before it.
template <typename Element>
std::shared_ptr<ompl::NearestNeighbors<Element>> poseNeighbors(const ompl::base::SpaceInformationPtr &si,
                                                               typename PoseNearestNeighbors<Element>::StateOf stateOf)
{
    const std::optional<PoseMetric> metric = PoseMetric::of(*si->getStateSpace());
    if (!metric)
        return nullptr;
    // OMPL's GNAT takes a seed from OMPL's seed sequence (for its pivot selector) when it is made;
    // taking one here too keeps the planner's sampler on the seed it gets with GNAT, so that a
    // seeded run plans the same tree with either structure.
    const ompl::RNG seedTakenAsGnatTakesIt;
    (void)seedTakenAsGnatTakesIt;
    return std::make_shared<PoseNearestNeighbors<Element>>(*metric, std::move(stateOf));
}

// RRT's and RRTConnect's tree nodes hold their state.
template <typename Motion>
std::shared_ptr<ompl::NearestNeighbors<Motion *>> motionNeighbors(const ompl::base::SpaceInformationPtr &si)
{
    return poseNeighbors<Motion *>(si, [](Motion *const &m) -> const ompl::base::State * { return m->state; });
}

// Implemented by the planners below, for searchesWithPoseNeighbors.
class SearchesPoses
{
public:
    virtual ~SearchesPoses() = default;
    virtual bool searchesPoses() const = 0;
};

template <typename Element>
bool isPoseSearch(const std::shared_ptr<ompl::NearestNeighbors<Element>> &nn)
{
    return dynamic_cast<const PoseNearestNeighbors<Element> *>(nn.get()) != nullptr;
}

class RRTConnectWithPoseNeighbors : public og::RRTConnect, public SearchesPoses
{
public:
    explicit RRTConnectWithPoseNeighbors(const ompl::base::SpaceInformationPtr &si) : og::RRTConnect(si) {}

    void setup() override
    {
        if (!tStart_)
            tStart_ = motionNeighbors<Motion>(si_);
        if (!tGoal_)
            tGoal_ = motionNeighbors<Motion>(si_);
        og::RRTConnect::setup();
    }

    bool searchesPoses() const override { return isPoseSearch(tStart_) && isPoseSearch(tGoal_); }
};

class RRTWithPoseNeighbors : public og::RRT, public SearchesPoses
{
public:
    explicit RRTWithPoseNeighbors(const ompl::base::SpaceInformationPtr &si) : og::RRT(si) {}

    void setup() override
    {
        if (!nn_)
            nn_ = motionNeighbors<Motion>(si_);
        og::RRT::setup();
    }

    bool searchesPoses() const override { return isPoseSearch(nn_); }
};

// OMPL 1.5's BIT* (and ABIT*, built on it) reports the sizes of its graph and of its sample set as
// progress properties, which OMPL's Benchmark reads from a second thread while the planner changes
// them: `bench` runs of BIT* died at random of heap corruption (OMPL issue 779; OMPL removed the two
// after 1.5). They are left out here; the best cost and the counters stay.
template <typename T>
class WithThreadSafeProgress : public T
{
public:
    explicit WithThreadSafeProgress(const ompl::base::SpaceInformationPtr &si) : T(si)
    {
        for (const char *name : kThreadUnsafeBitStarProgress)
            this->plannerProgressProperties_.erase(name);
    }
};

// PRM's and PRM*'s roadmap vertices hold their state in a property map of the graph. PRM grows
// the roadmap under its graph mutex, so one thread at a time searches it, as with OMPL's default
// (GNAT without thread safety). Installed when the planner is made: PRM's max_nearest_neighbors
// parameter makes OMPL's default structure at once if there is none yet.
template <typename Prm>
class PrmWithPoseNeighbors : public Prm, public SearchesPoses
{
public:
    explicit PrmWithPoseNeighbors(const ompl::base::SpaceInformationPtr &si) : Prm(si)
    {
        using Vertex = typename Prm::Vertex;
        this->nn_ = poseNeighbors<Vertex>(
            this->si_, [this](const Vertex &v) -> const ompl::base::State * { return this->stateProperty_[v]; });
        // PRM gives the roadmap's structure its distance only when it makes the structure itself.
        if (this->nn_)
            this->nn_->setDistanceFunction(
                [this](const Vertex a, const Vertex b) { return this->distanceFunction(a, b); });
    }

    bool searchesPoses() const override { return isPoseSearch(this->nn_); }
};

// KPIECE1, BKPIECE1, LBKPIECE1 and STRIDE keep a blocked motion's last valid state only beyond
// their min_valid_path_fraction. For the run, a continuous validator is told so, and then does not
// bracket a contact it finds before that fraction: the planner would throw the bracket away
// (ContinuousMotionValidator::setUnwantedLastValidBelow), so the tree is the same and cheaper.
template <typename Kpiece>
class WithUnwantedLastValid : public Kpiece
{
public:
    explicit WithUnwantedLastValid(const ompl::base::SpaceInformationPtr &si) : Kpiece(si) {}

    ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override
    {
        const std::shared_ptr<ContinuousMotionValidator> validator =
            std::dynamic_pointer_cast<ContinuousMotionValidator>(this->si_->getMotionValidator());
        if (!validator)
            return Kpiece::solve(ptc);
        // Another planner on the same space information gets the setting it had (bench runs
        // several in turn), also when solve throws.
        struct Restore
        {
            ContinuousMotionValidator &validator;
            double before;
            ~Restore() { validator.setUnwantedLastValidBelow(before); }
        } restore{*validator, validator->unwantedLastValidBelow()};
        validator->setUnwantedLastValidBelow(this->getMinValidPathFraction());
        return Kpiece::solve(ptc);
    }
};

// The planners that draw samples from OMPL's informed sets (PathLengthDirectInfSampler). OMPL 1.5
// makes those only for RealVector, SE(2) and SE(3) spaces and throws otherwise, from CForest's
// worker threads too, where the throw ended the process.
bool samplesInformedSets(const std::string &type)
{
    for (const char *name : {"abitstar", "aitstar", "bitstar", "cforest", "informedrrtstar", "sorrtstar"})
        if (type == name)
            return true;
    return false;
}

// The spaces PathLengthDirectInfSampler accepts: SE(2), SE(3), or a space that is not compound and
// either a real vector space or of unknown type (taken as one).
bool informedSetsSupported(const ompl::base::StateSpace &space)
{
    const int type = space.getType();
    if (type == ompl::base::STATE_SPACE_SE2 || type == ompl::base::STATE_SPACE_SE3)
        return true;
    return !space.isCompound() &&
           (type == ompl::base::STATE_SPACE_REAL_VECTOR || type == ompl::base::STATE_SPACE_UNKNOWN);
}

// A std::map keeps the names sorted, so plannerNames() needs no extra sort.
const std::map<std::string, Factory> &catalogue()
{
    static const std::map<std::string, Factory> table = {
        {"abitstar", make<WithThreadSafeProgress<og::ABITstar>>()},
        {"aitstar", make<og::AITstar>()},
        {"aps", make<og::AnytimePathShortening>()},
        {"bfmt", make<og::BFMT>()},
        {"biest", make<og::BiEST>()},
        {"birlrt", make<og::BiRLRT>()},
        {"bitrrt", make<og::BiTRRT>()},
        {"bitstar", make<WithThreadSafeProgress<og::BITstar>>()},
        {"bkpiece", make<WithUnwantedLastValid<og::BKPIECE1>>()},
        {"cforest", make<og::CForest>()},
        {"est", make<og::EST>()},
        {"fmt", make<og::FMT>()},
        {"informedrrtstar", make<og::InformedRRTstar>()},
        {"kpiece", make<WithUnwantedLastValid<og::KPIECE1>>()},
        {"lazyprm", make<og::LazyPRM>()},
        {"lazyprmstar", make<og::LazyPRMstar>()},
        {"lazyrrt", make<og::LazyRRT>()},
        {"lbkpiece", make<WithUnwantedLastValid<og::LBKPIECE1>>()},
        {"lbtrrt", make<og::LBTRRT>()},
        {"pdst", make<og::PDST>()},
        {"prm", makeWithPoseSearch<og::PRM, PrmWithPoseNeighbors<og::PRM>>()},
        {"prmstar", makeWithPoseSearch<og::PRMstar, PrmWithPoseNeighbors<og::PRMstar>>()},
        {"projest", make<og::ProjEST>()},
        {"prrt", make<og::pRRT>()},
        {"psbl", make<og::pSBL>()},
        // QRRT takes a sequence of quotient spaces; a single level plans directly in the given space.
        {"qrrt",
         [](const ompl::base::SpaceInformationPtr &si, NeighborSearch) -> ompl::base::PlannerPtr {
             std::vector<ompl::base::SpaceInformationPtr> levels{si};
             return std::make_shared<og::QRRT>(levels, "QRRT");
         }},
        {"rlrt", make<og::RLRT>()},
        {"rrt", makeWithPoseSearch<og::RRT, RRTWithPoseNeighbors>()},
        {"rrtconnect", makeWithPoseSearch<og::RRTConnect, RRTConnectWithPoseNeighbors>()},
        {"rrtsharp", make<og::RRTsharp>()},
        {"rrtstar", make<og::RRTstar>()},
        {"rrtxstatic", make<og::RRTXstatic>()},
        {"sbl", make<og::SBL>()},
        {"sorrtstar", make<og::SORRTstar>()},
        {"spars", make<og::SPARS>()},
        {"spars2", make<og::SPARStwo>()},
        {"sst", make<og::SST>()},
        {"stride", make<WithUnwantedLastValid<og::STRIDE>>()},
        {"trrt", make<og::TRRT>()},
    };
    return table;
}

std::string toLower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// The .cfg reader may hand over "rrt " or " rrt"; stray blanks should not make a known type unknown.
std::string trim(const std::string &s)
{
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
        return {};
    const auto last = s.find_last_not_of(" \t\r\n");
    return s.substr(first, last - first + 1);
}

std::string join(const std::vector<std::string> &items)
{
    std::string out;
    for (const auto &item : items)
    {
        if (!out.empty())
            out += ", ";
        out += item;
    }
    return out;
}

// OMPL's control planners by OMPL.app's names. Left out: SyclopRRT and SyclopEST need a grid
// decomposition of the workspace.
using ControlFactory = std::function<ompl::base::PlannerPtr(const ompl::control::SpaceInformationPtr &)>;

template <typename T>
ControlFactory makeControl()
{
    return
        [](const ompl::control::SpaceInformationPtr &si) -> ompl::base::PlannerPtr { return std::make_shared<T>(si); };
}

const std::map<std::string, ControlFactory> &controlCatalogue()
{
    namespace oc = ompl::control;
    static const std::map<std::string, ControlFactory> table = {
        {"est", makeControl<oc::EST>()}, {"kpiece", makeControl<oc::KPIECE1>()}, {"pdst", makeControl<oc::PDST>()},
        {"rrt", makeControl<oc::RRT>()}, {"sst", makeControl<oc::SST>()},
    };
    return table;
}

// OMPL declares a numeric parameter's range as "low:step:high" (or "low:high") but sets any value:
// a negative range makes RRTConnect step backwards. A value that is not a finite number, or is
// below the low end, is refused; the high end is a suggestion only (a large world takes a larger
// range than 10000).
std::optional<std::string> belowSuggestedRange(ompl::base::Planner &planner, const std::string &key,
                                               const std::string &value)
{
    const std::string suggestion = planner.params().getParam(key)->getRangeSuggestion();
    const std::size_t colon = suggestion.find(':');
    if (colon == std::string::npos)
        return std::nullopt;  // booleans ("0,1"), enumerations, or none declared
    char *end = nullptr;
    const double low = std::strtod(suggestion.c_str(), &end);
    if (end != suggestion.c_str() + colon || !std::isfinite(low))
        return std::nullopt;
    const std::string trimmed = trim(value);
    const double number = std::strtod(trimmed.c_str(), &end);
    if (trimmed.empty() || end != trimmed.c_str() + trimmed.size())
        return std::nullopt;  // not a number at all: OMPL's own parse refuses it below
    if (!std::isfinite(number))
        return std::string("not a finite number");
    if (number < low)
        return "below its smallest meaningful value, " + suggestion.substr(0, colon) + " (OMPL suggests " + suggestion +
               ")";
    return std::nullopt;
}

// The display name and every parameter of `request`, through OMPL's ParamSet.
void applyRequest(const PlannerRequest &request, const std::string &type, ompl::base::Planner &planner)
{
    if (!request.displayName.empty())
        planner.setName(request.displayName);

    for (const auto &[key, value] : request.parameters)
    {
        // Check first so an unknown name gets a helpful list instead of OMPL's bare log line.
        if (!planner.params().hasParam(key))
        {
            std::vector<std::string> known;
            planner.params().getParamNames(known);
            throw std::invalid_argument("planner '" + type + "' (" + planner.getName() + ") has no parameter '" + key +
                                        "'; valid parameters: " + (known.empty() ? "(none)" : join(known)));
        }
        const std::string rejected =
            "planner '" + type + "': invalid value '" + value + "' for parameter '" + key + "'";
        if (const std::optional<std::string> problem = belowSuggestedRange(planner, key, value))
            throw std::invalid_argument(rejected + ": " + *problem);
        bool accepted = false;
        try
        {
            accepted = planner.params().setParam(key, value);
        }
        catch (const std::exception &e)
        {
            // OMPL 1.5 only turns std::invalid_argument into "false"; a malformed real
            // ("Failed converting string to real number"), an out-of-range integer or a
            // setter's own ompl::Exception escapes as some other exception.
            throw std::invalid_argument(rejected + ": " + e.what());
        }
        if (!accepted)
            throw std::invalid_argument(rejected);
    }
}
}  // namespace

std::vector<std::string> controlPlannerNames()
{
    std::vector<std::string> names;
    for (const auto &entry : controlCatalogue())
        names.push_back(entry.first);
    return names;
}

ompl::base::PlannerPtr makeControlPlanner(const PlannerRequest &request, const ompl::control::SpaceInformationPtr &si)
{
    const std::string type = toLower(trim(request.type));
    const auto it = controlCatalogue().find(type);
    if (it == controlCatalogue().end())
        throw std::invalid_argument(
            "unknown control planner '" + request.type +
            "' for a kinodynamic problem; valid control planners: " + join(controlPlannerNames()));
    ompl::base::PlannerPtr planner = it->second(si);
    applyRequest(request, type, *planner);
    return planner;
}

std::vector<std::string> plannerNames()
{
    std::vector<std::string> names;
    names.reserve(catalogue().size());
    for (const auto &entry : catalogue())
        names.push_back(entry.first);
    return names;
}

bool searchesWithPoseNeighbors(const ompl::base::Planner &planner)
{
    const auto *searching = dynamic_cast<const SearchesPoses *>(&planner);
    return searching && searching->searchesPoses();
}

NeighborSearch parseNeighborSearch(const std::string &name)
{
    if (name == "poses")
        return NeighborSearch::Poses;
    if (name == "ompl")
        return NeighborSearch::OmplDefault;
    throw std::invalid_argument("unknown nearest-neighbour search '" + name + "'; expected poses or ompl");
}

ompl::base::PlannerPtr makePlanner(const PlannerRequest &request, const ompl::base::SpaceInformationPtr &si,
                                   NeighborSearch search)
{
    const std::string type = toLower(trim(request.type));
    const auto it = catalogue().find(type);
    if (it == catalogue().end())
        throw std::invalid_argument("unknown planner type '" + request.type +
                                    "'; valid types: " + join(plannerNames()));

    const bool informedSets = informedSetsSupported(*si->getStateSpace());
    const auto refuse = [&](const std::string &what) {
        return std::invalid_argument(what +
                                     " samples OMPL's informed sets, which OMPL 1.5 builds only for one robot in "
                                     "SE(2) or SE(3) (or a real vector space); this problem's state space ('" +
                                     si->getStateSpace()->getName() +
                                     "', several bodies' poses) is neither: choose another planner (rrtconnect, "
                                     "rrtstar, prm, kpiece, ...)");
    };
    if (samplesInformedSets(type) && !informedSets)
        throw refuse("planner '" + type + "'");
    ompl::base::PlannerPtr planner = it->second(si, search);
    applyRequest(request, type, *planner);
    // RRT* and RRTX sample (or reject samples by) the informed set when these are set.
    if (!informedSets)
        for (const char *key : {"informed_sampling", "sample_rejection"})
            if (planner->params().hasParam(key) && planner->params()[key].getValue() == "1")
                throw refuse("planner '" + type + "' with " + key + "=1");
    return planner;
}

}  // namespace hcd
