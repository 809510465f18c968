// SPDX-License-Identifier: BSD-3-Clause
// Reads OMPL.app problem files (.cfg): [problem], [benchmark] and [planner] sections.
#pragma once

#include "hybridcd/geometry/shape.h"
#include "hybridcd/io/planner_request.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hcd
{
/// A start or goal as written in a .cfg. 3D: position and `theta` radians about `axis`;
/// planar: x, y and theta (yaw).
struct ConfigPose
{
    double x = 0.0, y = 0.0, z = 0.0;
    double theta = 0.0;
    double axisX = 1.0, axisY = 0.0, axisZ = 0.0;
};

/// The geometry of a scene body as a .cfg names it (README, "Scenes of many bodies"): a mesh file,
/// the convex hull of a mesh file's vertices, or a primitive with its dimensions in the problem's
/// length units, centred at the body's origin with its axis along the body's z.
struct ShapeSpec
{
    /// "mesh", "convex", "sphere", "box", "capsule", "cylinder", "cone", "ellipsoid" or "halfspace".
    std::string kind;
    /// sphere: radius; box: side lengths x y z; capsule, cylinder: radius and length of the axis
    /// (a capsule's length without its caps); cone: base radius and height; ellipsoid: semi-axes
    /// x y z; halfspace: normal x y z and offset d (the solid n . p <= d). Empty for files.
    std::vector<double> parameters;
    std::string file;  ///< mesh and convex: the mesh file, resolved relative to the .cfg's folder
    int line = 0;      ///< the .cfg line that names it
};

/// The primitive a spec names (kind sphere ... halfspace; not mesh or convex), in the body's frame.
/// Throws std::invalid_argument, from Shape, for dimensions it refuses (README, "Scenes of many
/// bodies": magnitudes 1e-100 to 1e100); the .cfg reader turns that into an InputError with the line.
Shape primitiveShapeOfSpec(const ShapeSpec &spec);

/// Robot 2, 3, ... of a scene problem (`robot.K`, `start.K.*`, `goal.K.*`).
struct RobotSpec
{
    std::string label;  ///< "robot.K"
    ShapeSpec shape;
    ConfigPose start, goal;
    int startLine = 0, goalLine = 0;
};

/// A static obstacle of a scene problem (`obstacle.K` and its pose `obstacle.K.x` ...).
struct ObstacleSpec
{
    std::string label;  ///< "obstacle.K"
    ShapeSpec shape;
    ConfigPose pose;  ///< world-from-obstacle, as a start is written (identity when not given)
};

/// The largest problem file read: 16 MiB (OMPL.app's are under 2 KB). Larger files are refused.
constexpr std::uintmax_t kMaxProblemFileBytes = std::uintmax_t(16) << 20;

/// The longest time limit accepted, in seconds (about 31 years): OMPL counts time in nanoseconds
/// of the system clock, and a limit near 1e10 s overflows them into an immediate timeout. Applies
/// to [benchmark] time_limit and to the command line's --time.
constexpr double kMaxTimeLimitSeconds = 1e9;
/// kMaxTimeLimitSeconds as error messages give it.
inline constexpr char kMaxTimeLimitText[] = "1e9 seconds (about 31 years)";

struct BenchmarkSettings
{
    double timeLimit = 10.0;      ///< seconds per run
    double memoryLimit = 1000.0;  ///< MB per run
    unsigned runCount = 10;
};

struct ProblemConfig
{
    std::string path;       ///< the .cfg file as given
    std::string name;       ///< [problem] name, or the file stem
    std::string robotMesh;  ///< resolved relative to the .cfg's folder
    std::string worldMesh;  ///< resolved; empty when the problem has no environment
    int robotLine = 0;      ///< lines of the robot/world keys, for error messages
    int worldLine = 0;
    int startLine = 0;  ///< lines of start.x and goal.x, for messages about the start or goal
    int goalLine = 0;
    bool planar = false;  ///< SE2 when the start has no z, as OMPL.app decides
    /// The vehicle of a kinodynamic problem: kinematic_car or dynamic_car (planar), blimp or
    /// quadrotor (3D); empty for a geometric problem. Any other value is an InputError.
    std::string control;
    int controlLine = 0;
    ConfigPose start, goal;
    std::optional<std::pair<double, double>> volumeX, volumeY, volumeZ;  ///< (min, max) when given
    std::string objective;  ///< "length", "max min clearance", "mechanical work" or empty
    std::optional<double> objectiveThreshold;
    std::string sampler;  ///< valid-state sampler: uniform, gaussian, obstacle_based, max_clearance, bridge_test
    BenchmarkSettings benchmark;
    /// Scene problems: robots after the first, in order of K, and static obstacles besides the world
    /// mesh. Both empty for OMPL.app's problems of one robot and one environment.
    std::vector<RobotSpec> extraRobots;
    std::vector<ObstacleSpec> obstacles;
    /// Body pairs never checked against each other (`allowed_collisions = robot.2 obstacle.1; ...`),
    /// by label: "robot" (or "robot.1"), "robot.K", "world", "obstacle.K".
    std::vector<std::pair<std::string, std::string>> allowedCollisions;
    int allowedCollisionsLine = 0;
    /// True for a problem with several robots or with obstacles of its own: it is checked and planned
    /// as a scene of many bodies.
    bool isScene() const { return !extraRobots.empty() || !obstacles.empty(); }
    /// Number of robots (1 + extraRobots).
    std::size_t robotCount() const { return 1 + extraRobots.size(); }
    std::vector<PlannerRequest> planners;  ///< in file order
    /// "FILE:LINE: ..." notes on keys that were ignored (unknown to OMPL.app and hybridcd); the
    /// caller decides how to show them.
    std::vector<std::string> warnings;
};

/// Parses `path`. Throws InputError("FILE:LINE: ...") for unreadable files, folders, files that are
/// not regular files or are above kMaxProblemFileBytes (readInputFile, atomic_file.h), binary data,
/// malformed lines, bad numbers, a key set twice in a section (or a planner setting given twice
/// for the same planner), parameters of a planner that was never declared, non-positive benchmark
/// limits or a time_limit above kMaxTimeLimitSeconds, a volume whose width overflows, a rotation axis of zero length,
/// an unknown `control` model or one that does not match the problem's dimension, and missing required keys. Unknown
/// keys are not errors: each adds a line to ProblemConfig::warnings.
ProblemConfig readProblemConfig(const std::string &path);

/// Parses the text of a .cfg as readProblemConfig does a file. `path` is where the text came from:
/// errors name it, the problem name defaults to its stem, and mesh paths are resolved against its
/// folder (nothing is opened). Throws InputError as readProblemConfig does.
ProblemConfig parseProblemConfig(std::string_view text, const std::string &path);
}  // namespace hcd
