// SPDX-License-Identifier: BSD-3-Clause
// The Python module `hybridcd`: loads a problem (or two meshes) and checks batches of poses and
// motions given as NumPy arrays, with the answers of the command-line tool's `check`, `clearance`
// and `check-motion`.
//
// Poses are rows in the .path files' column order: x y theta in the plane, x y z qx qy qz qw in 3D.
// Quaternions are read as pose files read them: a zero quaternion, or one whose norm differs from
// 1 by more than kQuaternionNormTolerance, is refused (ValueError); others are normalised. A row
// holding NaN or an infinity is not refused: the checker reports it as colliding.
//
// Each batch is copied out of NumPy while the GIL is held; the checks then run without it, so
// other Python threads (and other batches on the same checker, which is immutable) run meanwhile.
#include "hybridcd/io/input_error.h"
#include "hybridcd/io/pose_codec.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/penetration_estimate.h"
#ifdef HYBRIDCD_HAVE_FCL
#include "hybridcd/fcl/fcl_checker.h"
#endif

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorBounds.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace hcd::python
{
namespace
{
/// A robot and an environment, with the configuration they came from (a problem file's, or a
/// default one naming the two meshes). Immutable once built, shared by the checkers made from it.
struct Scene
{
    std::shared_ptr<const LoadedProblem> data;
    virtual ~Scene() = default;
};

/// A scene read from an OMPL.app .cfg, with its start, goal and volume.
struct Problem : Scene
{
};

using Pose = PoseRow;  // the first 3 or 7 columns are used

std::string shapeOf(const py::array &a)
{
    std::ostringstream s;
    s << '(';
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
        s << (d ? ", " : "") << a.shape(d);
    s << (a.ndim() == 1 ? ",)" : ")");
    return s.str();
}

std::string layoutOf(bool planar)
{
    return planar ? "N x 3 (x, y, yaw) for a planar scene" : "N x 7 (x, y, z, qx, qy, qz, qw) for a 3D scene";
}

/// Copies an N x 3 or N x 7 array of poses out of NumPy, checking its shape and its quaternions.
/// `what` names the argument in error messages. Needs the GIL.
std::vector<Pose> readPoses(const py::handle &object, bool planar, const char *what)
{
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
    if (!array)
        throw py::type_error(std::string(what) + " must be an array of numbers, " + layoutOf(planar));
    const std::size_t columns = poseColumns(planar);
    if (array.ndim() != 2 || std::size_t(array.shape(1)) != columns)
        throw py::value_error(std::string(what) + " must be an array of shape " + layoutOf(planar) + ", got shape " +
                              shapeOf(array));
    const auto rows = array.unchecked<2>();
    std::vector<Pose> poses(std::size_t(rows.shape(0)));
    for (py::ssize_t i = 0; i < rows.shape(0); ++i)
    {
        Pose &p = poses[std::size_t(i)];
        bool finite = true;
        for (std::size_t c = 0; c < columns; ++c)
        {
            p[c] = rows(i, py::ssize_t(c));
            finite = finite && std::isfinite(p[c]);
        }
        if (planar || !finite)
            continue;
        // As pose files are read (path_file.h): unit quaternions only, normalised.
        const QuaternionCheck check = normaliseRowQuaternion(p.data());
        if (check.verdict != QuaternionCheck::Verdict::Unit)
        {
            std::ostringstream message;
            message << what << "[" << i << "]: the quaternion (qx qy qz qw) has norm " << check.norm
                    << "; a unit quaternion is expected (within " << kQuaternionNormTolerance << ")";
            throw py::value_error(message.str());
        }
    }
    return poses;
}

bool isFinite(const Pose &p, bool planar)
{
    for (std::size_t c = 0; c < poseColumns(planar); ++c)
        if (!std::isfinite(p[c]))
            return false;
    return true;
}

template <typename T>
py::array_t<T> toArray(const std::vector<T> &values)
{
    py::array_t<T> out(py::ssize_t(values.size()));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::array_t<bool> toBoolArray(const std::vector<char> &values)
{
    py::array_t<bool> out(py::ssize_t(values.size()));
    bool *data = out.mutable_data();
    for (std::size_t i = 0; i < values.size(); ++i)
        data[i] = values[i] != 0;
    return out;
}

/// A .cfg pose in .path columns, through the OMPL state the planner is given.
py::array_t<double> configPoseColumns(const ConfigPose &pose, bool planar, const ompl::base::StateSpacePtr &space)
{
    ompl::base::State *state = space->allocState();
    configPoseToState(pose, planar, state);
    const std::vector<double> values = stateToPoseValues(state, planar);
    space->freeState(state);
    return toArray(values);
}

py::object volumeOf(const std::optional<std::pair<double, double>> &range)
{
    if (!range)
        return py::none();
    return py::make_tuple(range->first, range->second);
}

/// The checkers the module offers: the core ones, and FCL's when it was built.
const CheckerCatalogue &catalogue()
{
#ifdef HYBRIDCD_HAVE_FCL
    static const CheckerCatalogue checkers = checkersWithFcl();
#else
    static const CheckerCatalogue checkers = CheckerCatalogue::builtIn();
#endif
    return checkers;
}

/// A collision checker over a scene, with the continuous motion validator of `check-motion`.
class Checker
{
public:
    Checker(std::shared_ptr<const Scene> scene, const std::string &name, bool surfaceOnly,
            std::optional<double> approximateTolerance, double contactTolerance)
        : scene_(std::move(scene))
    {
        if (!scene_)
            throw py::type_error("Checker needs a Scene or a Problem, got None");
        if (!(contactTolerance > 0.0 && contactTolerance <= 1.0))
            throw py::value_error("contact_tolerance must be a fraction of the motion in (0, 1], got " +
                                  py::repr(py::float_(contactTolerance)).cast<std::string>());
        CheckerOptions options;
        options.semantics = surfaceOnly ? ContactSemantics::SurfaceOnly : ContactSemantics::Solid;
        if (approximateTolerance)
        {
            if (!(*approximateTolerance > 0.0) || !std::isfinite(*approximateTolerance))
                throw py::value_error("approximate_tolerance must be a positive distance");
            options.approximateTolerance = *approximateTolerance;
        }
        const LoadedProblem &problem = *scene_->data;
        checker_ = catalogue().make(name, problem.scene, options);
        // As `check-motion`: the validator OMPL is given, with only collisions deciding.
        planning_ = makePlanningProblem(problem, checker_, MotionCheck::Continuous);
        si_ = planning_.setup->getSpaceInformation();
        validator_ = planning_.continuousValidator;
        validator_->setContactTolerance(contactTolerance);
        validator_->setApplyBounds(false);
        validator_->setStartChecked(true);  // a listed motion may start in collision
    }

    const std::shared_ptr<const Scene> &scene() const { return scene_; }
    std::string name() const { return checker_->name(); }
    bool planar() const { return scene_->data->config.planar; }

    py::array_t<bool> collides(const py::handle &posesObject) const
    {
        const std::vector<Pose> poses = readPoses(posesObject, planar(), "poses");
        std::vector<char> out(poses.size());
        {
            py::gil_scoped_release release;
            QueryContext context;  // one per batch: no allocation per pose once warm
            for (std::size_t i = 0; i < poses.size(); ++i)
                out[i] = checker_->collides(transformOfRow(poses[i].data(), planar()), context) ? 1 : 0;
        }
        return toBoolArray(out);
    }

    py::array_t<double> clearance(const py::handle &posesObject) const
    {
        const std::vector<Pose> poses = readPoses(posesObject, planar(), "poses");
        std::vector<double> out(poses.size());
        {
            py::gil_scoped_release release;
            const CollisionScene &scene = scene_->data->scene;
            QueryContext context;
            for (std::size_t i = 0; i < poses.size(); ++i)
            {
                // As `clearance`: the distance when free, else minus the penetration estimate. A
                // non-finite pose is touching (CollisionChecker::distance gives 0 for it).
                if (!isFinite(poses[i], planar()))
                {
                    out[i] = 0.0;
                    continue;
                }
                const RigidTransform pose = transformOfRow(poses[i].data(), planar());
                out[i] = signedClearance(*checker_, scene, pose, context).value;
            }
        }
        return toArray(out);
    }

    py::object checkMotions(const py::handle &startsObject, const py::handle &goalsObject, bool lastFree) const
    {
        const std::vector<Pose> starts = readPoses(startsObject, planar(), "starts");
        const std::vector<Pose> goals = readPoses(goalsObject, planar(), "goals");
        if (starts.size() != goals.size())
            throw py::value_error("starts and goals must have the same number of rows, got " +
                                  std::to_string(starts.size()) + " and " + std::to_string(goals.size()));
        std::vector<char> free(starts.size());
        std::vector<double> fraction(starts.size());
        {
            py::gil_scoped_release release;
            ompl::base::State *a = si_->allocState(), *b = si_->allocState(), *last = si_->allocState();
            for (std::size_t i = 0; i < starts.size(); ++i)
            {
                // A non-finite pose collides, so a motion from or to one is blocked at once.
                if (!isFinite(starts[i], planar()) || !isFinite(goals[i], planar()))
                {
                    free[i] = 0;
                    fraction[i] = 0.0;
                    continue;
                }
                poseValuesToState(starts[i].data(), planar(), a);
                poseValuesToState(goals[i].data(), planar(), b);
                if (!lastFree)
                {
                    // The verdict alone, as `check-motion --verdict-only` (no bracketing).
                    free[i] = validator_->checkMotion(a, b) ? 1 : 0;
                    continue;
                }
                std::pair<ompl::base::State *, double> lastValid{last, 0.0};
                const bool isFree = validator_->checkMotion(a, b, lastValid);
                free[i] = isFree ? 1 : 0;
                fraction[i] = isFree ? 1.0 : lastValid.second;
            }
            si_->freeState(a);
            si_->freeState(b);
            si_->freeState(last);
        }
        if (!lastFree)
            return toBoolArray(free);
        return py::make_tuple(toBoolArray(free), toArray(fraction));
    }

private:
    std::shared_ptr<const Scene> scene_;
    std::shared_ptr<const CollisionChecker> checker_;
    PlanningProblem planning_;
    ompl::base::SpaceInformationPtr si_;
    std::shared_ptr<ContinuousMotionValidator> validator_;
};

std::shared_ptr<Problem> loadProblemFile(const std::string &path)
{
    // A name with a zero byte would be cut short there by the file system's calls.
    if (path.find('\0') != std::string::npos)
        throw py::value_error("cfg_path holds a zero byte");
    auto problem = std::make_shared<Problem>();
    problem->data = std::make_shared<const LoadedProblem>(loadProblem(path));
    // A Checker checks one robot against the environment mesh; a scene's other robots and its
    // primitive obstacles would be left out, and its answers wrong.
    if (problem->data->config.isScene())
        throw InputError(path, 0,
                         "a scene problem (several robots or primitive obstacles) is not read by the Python "
                         "module, whose checkers test one robot against the environment mesh: use the command "
                         "line (hybridcd check, check-motion, clearance, solve)");
    return problem;
}

std::shared_ptr<Scene> sceneFromMeshes(const std::string &robot, const std::string &environment, bool planar)
{
    LoadedProblem p;
    p.config.path = robot;
    p.config.name = robot;
    p.config.planar = planar;
    p.config.robotMesh = robot;
    p.config.worldMesh = environment;
    p.robot = loadMesh(robot, planar ? MeshRole::RobotPlanar : MeshRole::Robot3D);
    p.world = loadMesh(environment, MeshRole::Environment);
    p.scene.robot = p.robot.mesh;
    p.scene.environment = p.world.mesh;
    p.scene.robotName = robot;
    p.scene.environmentName = environment;
    // As loadProblem sets them for a planar problem: SE(2) poses, turns about the robot's z axis.
    p.scene.planarPoses = p.scene.turnsAboutRobotZ = planar;
    auto scene = std::make_shared<Scene>();
    scene->data = std::make_shared<const LoadedProblem>(std::move(p));
    return scene;
}
}  // namespace
}  // namespace hcd::python

PYBIND11_MODULE(hybridcd, m)
{
    using namespace hcd::python;
    using hcd::LoadedProblem;
    m.doc() = "Exact collision checking for rigid-body planning (OMPL.app problems): batches of poses and "
              "motions as NumPy arrays. Poses are rows x, y, yaw (planar) or x, y, z, qx, qy, qz, qw (3D), "
              "the column order of .path files.";
    // Bad input files: "FILE:LINE: message", as the command-line tool prints them.
    py::register_exception<hcd::InputError>(m, "InputError", PyExc_ValueError);

    m.def(
        "checker_names", [] { return catalogue().names(); }, "Names Checker accepts, e.g. 'obb'.");

    py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A robot mesh and an environment mesh.")
        .def_static("from_meshes", &sceneFromMeshes, py::arg("robot"), py::arg("environment"),
                    py::arg("planar") = false,
                    "Loads two mesh files (any format assimp reads) placed as OMPL.app places them: the robot "
                    "centred on its vertex mean (in x and y only when planar), the environment as it is.")
        .def_property_readonly(
            "planar", [](const Scene &s) { return s.data->config.planar; },
            "True for SE(2) poses (x, y, yaw), False for SE(3) poses.")
        .def_property_readonly(
            "pose_size", [](const Scene &s) { return hcd::poseColumns(s.data->config.planar); },
            "Columns of a pose row: 3 (planar) or 7 (3D).")
        .def_property_readonly("robot_mesh", [](const Scene &s) { return s.data->config.robotMesh; })
        .def_property_readonly("environment_mesh", [](const Scene &s) { return s.data->config.worldMesh; })
        .def_property_readonly("robot_triangles", [](const Scene &s) { return s.data->scene.robot->triangleCount(); })
        .def_property_readonly("environment_triangles",
                               [](const Scene &s) { return s.data->scene.environment->triangleCount(); })
        .def("__repr__", [](const Scene &s) {
            return "<hybridcd.Scene robot='" + s.data->config.robotMesh + "' environment='" + s.data->config.worldMesh +
                   "'" + (s.data->config.planar ? " planar" : "") + ">";
        });

    py::class_<Problem, Scene, std::shared_ptr<Problem>>(m, "Problem", "An OMPL.app problem (.cfg) and its meshes.")
        .def_static("load", &loadProblemFile, py::arg("cfg_path"),
                    "Reads a .cfg and its meshes; raises hybridcd.InputError (a ValueError) naming the file and "
                    "line on bad input.")
        .def_property_readonly("path", [](const Problem &p) { return p.data->config.path; })
        .def_property_readonly("name", [](const Problem &p) { return p.data->config.name; })
        .def_property_readonly(
            "start",
            [](const Problem &p) {
                const LoadedProblem &d = *p.data;
                return configPoseColumns(d.config.start, d.config.planar, hcd::makeStateSpace(d));
            },
            "The start as a pose row (the state the planner is given).")
        .def_property_readonly(
            "goal",
            [](const Problem &p) {
                const LoadedProblem &d = *p.data;
                return configPoseColumns(d.config.goal, d.config.planar, hcd::makeStateSpace(d));
            },
            "The goal as a pose row.")
        .def_property_readonly(
            "volume",
            [](const Problem &p) {
                const auto &c = p.data->config;
                return py::make_tuple(volumeOf(c.volumeX), volumeOf(c.volumeY), volumeOf(c.volumeZ));
            },
            "The .cfg's volume: ((min, max) or None) for x, y and z.")
        .def_property_readonly(
            "bounds",
            [](const Problem &p) {
                const auto space = hcd::makeStateSpace(*p.data);
                const auto &bounds = p.data->config.planar ? space->as<ompl::base::SE2StateSpace>()->getBounds()
                                                           : space->as<ompl::base::SE3StateSpace>()->getBounds();
                return py::make_tuple(toArray(bounds.low), toArray(bounds.high));
            },
            "(low, high) position bounds of the planner's state space: the volume (or the "
            "environment's box) grown to hold the start and goal.")
        .def_property_readonly(
            "warnings", [](const Problem &p) { return p.data->config.warnings; },
            "Notes on keys of the .cfg that were ignored.")
        .def("__repr__", [](const Problem &p) {
            return "<hybridcd.Problem '" + p.data->config.name + "'" + (p.data->config.planar ? " planar" : "") + ">";
        });

    m.def("load_problem", &loadProblemFile, py::arg("cfg_path"), "Same as Problem.load.");

    py::class_<Checker, std::shared_ptr<Checker>>(m, "Checker",
                                                  "A collision checker over a scene; safe to use from many threads.")
        .def(py::init<std::shared_ptr<const Scene>, const std::string &, bool, std::optional<double>, double>(),
             py::arg("scene"), py::arg("name") = "obb", py::arg("surface_only") = false,
             py::arg("approximate_tolerance") = py::none(), py::arg("contact_tolerance") = 1e-6,
             "Builds the named checker (see checker_names()). surface_only: meshes are surfaces, as FCL sees "
             "them (else closed components are solids). approximate_tolerance: the LP checker's approximate "
             "mode. contact_tolerance: how closely check_motions(last_free=True) brackets the first contact, as "
             "a fraction of the motion.")
        .def_property_readonly("name", &Checker::name)
        .def_property_readonly("scene", &Checker::scene)
        .def("collides", &Checker::collides, py::arg("poses"),
             "Bool array: True where the robot at the pose touches the environment (as `hybridcd check`, "
             "whose 0 is True here). A row with NaN or infinity collides.")
        .def("clearance", &Checker::clearance, py::arg("poses"),
             "Float array, as `hybridcd clearance`: the distance to the environment when free, else minus the "
             "penetration estimate (0 when contained or for a non-finite row).")
        .def("check_motions", &Checker::checkMotions, py::arg("starts"), py::arg("goals"), py::arg("last_free") = false,
             "Continuous check of the motion from each start row to the goal row (OMPL's interpolation): bool "
             "array, True where the whole motion is collision-free (as `hybridcd check-motion --verdict-only`). "
             "With last_free=True, also a float array as `hybridcd check-motion`: 1 for free motions, else the "
             "fraction up to which the motion is proven free.")
        .def("__repr__", [](const Checker &c) { return "<hybridcd.Checker '" + c.name() + "'>"; });
}
