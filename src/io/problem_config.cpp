// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/problem_config.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace hcd
{
namespace
{
std::string trim(const std::string &s)
{
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
        return {};
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

struct Entry
{
    std::string value;
    int line;
};

class Parser
{
public:
    explicit Parser(std::string path) : path_(std::move(path)) {}

    double number(const std::string &key, const Entry &e) const
    {
        // strtod, not stod: stod refuses subnormal numbers (it throws on ERANGE). Decimal numbers
        // only: strtod would also read hexadecimal ("0x1" as 1).
        const char *begin = e.value.c_str();
        char *end = nullptr;
        const double v = std::strtod(begin, &end);
        const std::string number = trim(std::string(begin, std::size_t(end - begin)));
        if (end != begin && trim(std::string(end, e.value.size() - std::size_t(end - begin))).empty() &&
            std::isfinite(v) && number.find_first_not_of("0123456789+-.eE") == std::string::npos)
        {
            if (std::fabs(v) > kLargestInputMagnitude)
                throw InputError(path_, e.line,
                                 "'" + key + "' needs a number of magnitude at most 1e100, got '" + e.value + "'");
            return v;
        }
        throw InputError(path_, e.line, "'" + key + "' needs a finite number, got '" + e.value + "'");
    }

    const std::string &path() const { return path_; }

private:
    std::string path_;
};

bool isSceneKey(const std::string &key);

// Every key OMPL.app's .cfg files use (all of its shipped problems), so that none of them warns.
bool isKnownProblemKey(const std::string &key)
{
    static const std::set<std::string> known = [] {
        std::set<std::string> k = {"name", "robot", "world", "control", "objective", "objective.threshold", "sampler"};
        for (const char *pose : {"start", "goal"})
            for (const char *field : {"x", "y", "z", "theta", "axis.x", "axis.y", "axis.z"})
                k.insert(std::string(pose) + "." + field);
        for (const char *bound : {"min", "max"})
            for (const char *axis : {"x", "y", "z"})
                k.insert(std::string("volume.") + bound + "." + axis);
        return k;
    }();
    return known.count(key) > 0 || isSceneKey(key);
}

// Keys of scene problems: robot.K, start.K.*, goal.K.*, obstacle.K, obstacle.K.* (K a whole number)
// and allowed_collisions. `index` gets K and `field` what follows it ("" for robot.K / obstacle.K).
bool splitIndexedKey(const std::string &key, const std::string &head, int &index, std::string &field)
{
    if (key.compare(0, head.size() + 1, head + ".") != 0)
        return false;
    std::size_t i = head.size() + 1, digits = 0;
    while (i + digits < key.size() && std::isdigit(static_cast<unsigned char>(key[i + digits])))
        ++digits;
    if (digits == 0 || digits > 6)
        return false;
    index = std::stoi(key.substr(i, digits));
    const std::size_t rest = i + digits;
    if (rest == key.size())
    {
        field.clear();
        return true;
    }
    if (key[rest] != '.')
        return false;
    field = key.substr(rest + 1);
    return !field.empty();
}

bool isPoseField(const std::string &field)
{
    static const std::set<std::string> fields = {"x", "y", "z", "theta", "axis.x", "axis.y", "axis.z"};
    return fields.count(field) > 0;
}

bool isSceneKey(const std::string &key)
{
    if (key == "allowed_collisions")
        return true;
    int index = 0;
    std::string field;
    if (splitIndexedKey(key, "robot", index, field))
        return field.empty() && index >= 2;
    if (splitIndexedKey(key, "start", index, field) || splitIndexedKey(key, "goal", index, field))
        return index >= 2 && isPoseField(field);
    if (splitIndexedKey(key, "obstacle", index, field))
        return field.empty() || isPoseField(field);
    return false;
}

// [benchmark] keys: the limits hybridcd reads and OMPL.app's front-end options it does not need.
bool isKnownBenchmarkKey(const std::string &key)
{
    static const std::set<std::string> known = {"time_limit", "mem_limit", "run_count", "output", "save_paths"};
    return known.count(key) > 0;
}

// Length of the UTF-8 sequence starting at line[i], or 0 when it is not valid UTF-8.
std::size_t utf8Length(const std::string &line, std::size_t i)
{
    const unsigned char c = static_cast<unsigned char>(line[i]);
    const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    if (n == 0 || i + n > line.size())
        return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(line[i + k]) >> 6) != 0x2)
            return 0;
    return n;
}

// Text holds no control characters other than tab and carriage return, and is valid UTF-8
// (which includes ASCII); anything else means a binary file was given (an image, a mesh, an
// archive), which deserves a clear message rather than "expected 'key = value'" and garbage.
void rejectBinary(const std::string &line, const std::string &path, int lineNo)
{
    for (std::size_t i = 0; i < line.size();)
    {
        const unsigned char c = static_cast<unsigned char>(line[i]);
        const std::size_t n = utf8Length(line, i);
        if (n == 0 || (c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
            throw InputError(path, lineNo,
                             "binary data (byte " + std::to_string(int(c)) + " in column " + std::to_string(i + 1) +
                                 "); a problem file is an OMPL.app .cfg text file");
        i += n;
    }
}
}  // namespace

ProblemConfig readProblemConfig(const std::string &path)
{
    return parseProblemConfig(readInputFile(path, "problem file (.cfg)", kMaxProblemFileBytes), path);
}

ProblemConfig parseProblemConfig(std::string_view text, const std::string &path)
{
    std::istringstream in{std::string(text)};
    ProblemConfig cfg;
    cfg.path = path;
    Parser parser(path);
    std::map<std::string, Entry> problem, benchmark;
    std::string section;
    std::string raw;
    int lineNo = 0;
    while (std::getline(in, raw))
    {
        ++lineNo;
        if (lineNo == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0)
            raw.erase(0, 3);  // a UTF-8 byte-order mark, as some editors write
        rejectBinary(raw, path, lineNo);
        const std::string line = trim(raw);
        if (line.empty() || line[0] == '#' || line[0] == ';')
            continue;
        if (line.front() == '[')
        {
            if (line.back() != ']')
                throw InputError(path, lineNo, "malformed section header '" + line + "'");
            section = lower(trim(line.substr(1, line.size() - 2)));
            if (section != "problem" && section != "benchmark" && section != "planner")
                throw InputError(path, lineNo,
                                 "unknown section [" + section + "]; expected [problem], [benchmark] or [planner]");
            continue;
        }
        const auto eq = line.find('=');
        if (eq == std::string::npos)
            throw InputError(path, lineNo, "expected 'key = value', got '" + line + "'");
        const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
        if (key.empty())
            throw InputError(path, lineNo, "empty key before '='");
        if (section.empty())
            throw InputError(path, lineNo, "'" + key + "' appears before any [section]");

        if (section == "problem" || section == "benchmark")
        {
            auto &entries = section == "problem" ? problem : benchmark;
            const auto [previous, inserted] = entries.emplace(key, Entry{value, lineNo});
            if (!inserted)
                throw InputError(path, lineNo,
                                 "duplicate key '" + key + "' in [" + section + "] (first set on line " +
                                     std::to_string(previous->second.line) + ")");
            if (!(section == "problem" ? isKnownProblemKey(key) : isKnownBenchmarkKey(key)))
                cfg.warnings.push_back(path + ":" + std::to_string(lineNo) + ": unknown key '" + key + "' in [" +
                                       section + "] ignored");
        }
        else
        {
            // "type=" declares a planner; "type.name=" and "type.param=" refine the latest of that type.
            const auto dot = key.find('.');
            if (dot == std::string::npos)
            {
                if (!value.empty())
                    throw InputError(path, lineNo,
                                     "planner declaration '" + key + "=' takes no value, got '" + value + "'");
                cfg.planners.push_back({lower(key), "", {}});
                continue;
            }
            const std::string type = lower(key.substr(0, dot)), param = key.substr(dot + 1);
            auto it = std::find_if(cfg.planners.rbegin(), cfg.planners.rend(),
                                   [&](const PlannerRequest &r) { return r.type == type; });
            if (it == cfg.planners.rend())
                throw InputError(path, lineNo,
                                 "setting for planner '" + type + "' before a '" + type + "=' line declares it");
            // A setting repeated for the same planner is a mistake: the last one would silently win.
            const bool repeated = param == "name" ? !it->displayName.empty()
                                                  : std::any_of(it->parameters.begin(), it->parameters.end(),
                                                                [&](const auto &p) { return p.first == param; });
            if (repeated)
                throw InputError(path, lineNo, "duplicate setting '" + key + "' for the same '" + type + "=' planner");
            if (param == "name")
                it->displayName = value;
            else
                it->parameters.emplace_back(param, value);
        }
    }

    auto get = [&](const std::string &key) -> const Entry * {
        auto it = problem.find(key);
        return it == problem.end() ? nullptr : &it->second;
    };
    auto require = [&](const std::string &key) -> const Entry & {
        const Entry *e = get(key);
        if (!e)
            throw InputError(path, 0, "[problem] section lacks the required key '" + key + "'");
        return *e;
    };
    auto numberOr = [&](const std::string &key, double fallback) {
        const Entry *e = get(key);
        return e ? parser.number(key, *e) : fallback;
    };

    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    auto resolve = [&](const std::string &mesh) {
        const std::filesystem::path p(mesh);
        return (p.is_absolute() ? p : folder / p).lexically_normal().string();
    };
    const Entry &robot = require("robot");
    cfg.robotMesh = resolve(robot.value);
    cfg.robotLine = robot.line;
    if (const Entry *world = get("world"); world && !world->value.empty())
    {
        cfg.worldMesh = resolve(world->value);
        cfg.worldLine = world->line;
    }
    cfg.name = get("name") ? get("name")->value : std::filesystem::path(path).stem().string();
    cfg.planar = get("start.z") == nullptr;
    if (const Entry *c = get("control"))
    {
        // OMPL.app plans an unknown model geometrically without a word; here it is an error.
        const std::string model = lower(c->value);
        const bool planarModel = model == "kinematic_car" || model == "dynamic_car";
        if (!planarModel && model != "blimp" && model != "quadrotor")
            throw InputError(path, c->line,
                             "unknown control model '" + c->value +
                                 "'; expected kinematic_car, dynamic_car (planar), blimp or quadrotor (3D)");
        if (planarModel != cfg.planar)
            throw InputError(path, c->line,
                             "control = " + model + " is a " + (planarModel ? "planar" : "3D") +
                                 " vehicle, but this is a " +
                                 (cfg.planar ? "planar problem (no start.z)" : "3D problem"));
        cfg.control = model;
        cfg.controlLine = c->line;
    }

    auto readPose = [&](const std::string &prefix, ConfigPose &pose) {
        (prefix == "start" ? cfg.startLine : cfg.goalLine) = require(prefix + ".x").line;
        pose.x = parser.number(prefix + ".x", require(prefix + ".x"));
        pose.y = parser.number(prefix + ".y", require(prefix + ".y"));
        pose.theta = numberOr(prefix + ".theta", 0.0);
        if (!cfg.planar)
        {
            pose.z = parser.number(prefix + ".z", require(prefix + ".z"));
            pose.axisX = numberOr(prefix + ".axis.x", 1.0);
            pose.axisY = numberOr(prefix + ".axis.y", 0.0);
            pose.axisZ = numberOr(prefix + ".axis.z", 0.0);
            // A zero axis has no direction: the rotation would silently be the identity.
            if (pose.theta != 0.0 && pose.axisX == 0.0 && pose.axisY == 0.0 && pose.axisZ == 0.0)
            {
                const Entry *at = get(prefix + ".axis.x") ? get(prefix + ".axis.x") : get(prefix + ".theta");
                throw InputError(path, at->line,
                                 prefix + ".axis is zero; a rotation of " + prefix + ".theta needs a non-zero axis");
            }
        }
    };
    readPose("start", cfg.start);
    readPose("goal", cfg.goal);

    // Scene problems: more robots, obstacles, allowed pairs (README, "Scenes of many bodies").
    auto shapeOf = [&](const std::string &key, const Entry &e) {
        ShapeSpec spec;
        spec.line = e.line;
        std::istringstream words(e.value);
        std::string first;
        words >> first;
        first = lower(first);
        static const std::map<std::string, std::size_t> parameterCount = {
            {"sphere", 1}, {"box", 3},       {"capsule", 2},  {"cylinder", 2},
            {"cone", 2},   {"ellipsoid", 3}, {"halfspace", 4}};
        if (first == "mesh" || first == "convex")
        {
            std::string file;
            std::getline(words, file);
            file = trim(file);
            if (file.empty())
                throw InputError(path, e.line, "'" + key + " = " + first + "' needs a mesh file after it");
            spec.kind = first;
            spec.file = resolve(file);
            return spec;
        }
        const auto count = parameterCount.find(first);
        if (count == parameterCount.end())
        {
            // A plain file name, as OMPL.app's `robot = FILE`.
            spec.kind = "mesh";
            spec.file = resolve(e.value);
            return spec;
        }
        spec.kind = first;
        std::string word;
        while (words >> word)
            spec.parameters.push_back(parser.number(key, Entry{word, e.line}));
        if (spec.parameters.size() != count->second)
            throw InputError(path, e.line,
                             "'" + key + " = " + first + "' takes " + std::to_string(count->second) + " number" +
                                 (count->second == 1 ? "" : "s") + ", got " + std::to_string(spec.parameters.size()));
        if (first == "halfspace")
        {
            if (spec.parameters[0] == 0.0 && spec.parameters[1] == 0.0 && spec.parameters[2] == 0.0)
                throw InputError(path, e.line, "'" + key + " = halfspace' needs a non-zero normal");
        }
        else
            for (double v : spec.parameters)
                if (!(v > 0.0))
                    throw InputError(path, e.line,
                                     "'" + key + " = " + first + "' needs positive dimensions, got '" + e.value + "'");
        // Shape keeps the limits (magnitudes whose squares and products stay finite and normal).
        try
        {
            primitiveShapeOfSpec(spec);
        }
        catch (const std::invalid_argument &x)
        {
            throw InputError(path, e.line, "'" + key + " = " + e.value + "': " + x.what());
        }
        return spec;
    };
    std::map<int, const Entry *> robotEntries, obstacleEntries;
    for (const auto &[key, e] : problem)
    {
        int index = 0;
        std::string field;
        if (splitIndexedKey(key, "robot", index, field) && field.empty() && index >= 2)
            robotEntries[index] = &e;
        else if (splitIndexedKey(key, "obstacle", index, field) && field.empty())
            obstacleEntries[index] = &e;
    }
    for (const auto &[key, e] : problem)
    {
        int index = 0;
        std::string field;
        const bool poseOfRobot =
            (splitIndexedKey(key, "start", index, field) || splitIndexedKey(key, "goal", index, field)) && index >= 2 &&
            isPoseField(field);
        if (poseOfRobot && !robotEntries.count(index))
            throw InputError(path, e.line,
                             "'" + key + "' is given, but no 'robot." + std::to_string(index) + " = ...' line");
        if (splitIndexedKey(key, "obstacle", index, field) && isPoseField(field) && !obstacleEntries.count(index))
            throw InputError(path, e.line,
                             "'" + key + "' is given, but no 'obstacle." + std::to_string(index) + " = ...' line");
    }
    // A pose under `prefix` (start.2, obstacle.3): required keys as for the first robot's start.
    auto readPoseAt = [&](const std::string &prefix, ConfigPose &pose, bool required, int fallbackLine) {
        auto field = [&](const std::string &name, double fallback, bool needed) {
            const Entry *e = get(prefix + "." + name);
            if (!e && needed)
                throw InputError(path, fallbackLine,
                                 "[problem] section lacks the required key '" + prefix + "." + name + "'");
            return e ? parser.number(prefix + "." + name, *e) : fallback;
        };
        const Entry *first = get(prefix + ".x");
        pose.x = field("x", 0.0, required);
        pose.y = field("y", 0.0, required);
        pose.theta = field("theta", 0.0, false);
        if (cfg.planar)
        {
            if (const Entry *z = get(prefix + ".z"))
                throw InputError(path, z->line, "'" + prefix + ".z' in a planar problem (the first start has no z)");
        }
        else
        {
            pose.z = field("z", 0.0, required);
            pose.axisX = field("axis.x", 1.0, false);
            pose.axisY = field("axis.y", 0.0, false);
            pose.axisZ = field("axis.z", 0.0, false);
            if (pose.theta != 0.0 && pose.axisX == 0.0 && pose.axisY == 0.0 && pose.axisZ == 0.0)
                throw InputError(path, fallbackLine,
                                 prefix + ".axis is zero; a rotation of " + prefix + ".theta needs a non-zero axis");
        }
        return first ? first->line : fallbackLine;
    };
    for (const auto &[index, e] : robotEntries)
    {
        RobotSpec robot;
        robot.label = "robot." + std::to_string(index);
        robot.shape = shapeOf(robot.label, *e);
        if (robot.shape.kind == "halfspace")
            throw InputError(path, e->line, "'" + robot.label + "' cannot be a halfspace (it has no extent to move)");
        robot.startLine = readPoseAt("start." + std::to_string(index), robot.start, true, e->line);
        robot.goalLine = readPoseAt("goal." + std::to_string(index), robot.goal, true, e->line);
        cfg.extraRobots.push_back(std::move(robot));
    }
    for (const auto &[index, e] : obstacleEntries)
    {
        ObstacleSpec obstacle;
        obstacle.label = "obstacle." + std::to_string(index);
        obstacle.shape = shapeOf(obstacle.label, *e);
        readPoseAt(obstacle.label, obstacle.pose, false, e->line);
        cfg.obstacles.push_back(std::move(obstacle));
    }
    if (const Entry *allowed = get("allowed_collisions"))
    {
        cfg.allowedCollisionsLine = allowed->line;
        std::set<std::string> labels = {"robot", "robot.1"};
        if (!cfg.worldMesh.empty())
            labels.insert("world");
        for (const RobotSpec &r : cfg.extraRobots)
            labels.insert(r.label);
        for (const ObstacleSpec &o : cfg.obstacles)
            labels.insert(o.label);
        std::string list = allowed->value;
        std::replace(list.begin(), list.end(), ',', ';');
        std::istringstream pairs(list);
        std::string pair;
        while (std::getline(pairs, pair, ';'))
        {
            if (trim(pair).empty())
                continue;
            std::istringstream names(pair);
            std::string a, b, extra;
            names >> a >> b >> extra;
            if (b.empty() || !extra.empty())
                throw InputError(path, allowed->line,
                                 "allowed_collisions takes pairs of body names separated by ';', got '" + trim(pair) +
                                     "'");
            for (const std::string &name : {a, b})
                if (!labels.count(name))
                    throw InputError(path, allowed->line,
                                     "allowed_collisions names '" + name +
                                         "', which is no body of this problem (robot, robot.K, world, obstacle.K)");
            cfg.allowedCollisions.emplace_back(a == "robot.1" ? "robot" : a, b == "robot.1" ? "robot" : b);
        }
    }

    if (cfg.isScene() && !cfg.control.empty())
        throw InputError(path, cfg.controlLine,
                         "control = " + cfg.control +
                             " plans one vehicle; a scene problem (robot.K or obstacle.K) is planned geometrically");

    auto readRange = [&](const std::string &axis) -> std::optional<std::pair<double, double>> {
        const Entry *lo = get("volume.min." + axis), *hi = get("volume.max." + axis);
        if (!lo && !hi)
            return std::nullopt;
        if (!lo || !hi)
            throw InputError(path, (lo ? lo : hi)->line, "volume." + axis + " needs both min and max");
        const double a = parser.number("volume.min." + axis, *lo), b = parser.number("volume.max." + axis, *hi);
        if (a > b)
            throw InputError(path, lo->line, "volume.min." + axis + " exceeds volume.max." + axis);
        // OMPL samples in and measures the volume by its width, finite since both ends are within
        // kLargestInputMagnitude.
        return std::make_pair(a, b);
    };
    cfg.volumeX = readRange("x");
    cfg.volumeY = readRange("y");
    cfg.volumeZ = readRange("z");

    if (const Entry *o = get("objective"))
    {
        const std::string obj = lower(o->value);
        if (obj != "length" && obj != "max min clearance" && obj != "mechanical work")
            throw InputError(path, o->line,
                             "unknown objective '" + o->value +
                                 "'; expected length, max min clearance or mechanical work");
        cfg.objective = obj;
    }
    if (const Entry *t = get("objective.threshold"))
        cfg.objectiveThreshold = parser.number("objective.threshold", *t);
    if (const Entry *s = get("sampler"))
    {
        const std::string sampler = lower(s->value);
        static const char *known[] = {"uniform", "gaussian", "obstacle_based", "max_clearance", "bridge_test"};
        if (std::find(std::begin(known), std::end(known), sampler) == std::end(known))
            throw InputError(path, s->line,
                             "unknown sampler '" + s->value +
                                 "'; expected uniform, gaussian, obstacle_based, max_clearance or bridge_test");
        cfg.sampler = sampler;
    }

    for (const auto &[key, e] : benchmark)
    {
        if (key == "time_limit" || key == "mem_limit")
        {
            const double limit = parser.number(key, e);
            if (limit <= 0.0)
                throw InputError(path, e.line, key + " needs a positive number, got '" + e.value + "'");
            if (key == "time_limit" && limit > kMaxTimeLimitSeconds)
                throw InputError(path, e.line,
                                 std::string("time_limit needs at most ") + kMaxTimeLimitText + ", got '" + e.value +
                                     "'");
            (key == "time_limit" ? cfg.benchmark.timeLimit : cfg.benchmark.memoryLimit) = limit;
        }
        else if (key == "run_count")
        {
            const double runs = parser.number(key, e);
            // Above the largest unsigned, the conversion would be undefined (found by fuzzing:
            // tests/fuzz_corpus/cfg/regression_huge_run_count.cfg).
            if (runs < 1 || runs != std::floor(runs) || runs > double(std::numeric_limits<unsigned>::max()))
                throw InputError(path, e.line, "run_count needs a positive whole number, got '" + e.value + "'");
            cfg.benchmark.runCount = unsigned(runs);
        }
        // Other keys (output, save_paths, ...) are OMPL.app front-end options we do not need.
    }
    return cfg;
}
Shape primitiveShapeOfSpec(const ShapeSpec &spec)
{
    const std::vector<double> &p = spec.parameters;
    if (spec.kind == "sphere")
        return Shape::sphere(p.at(0));
    if (spec.kind == "box")
        return Shape::box(0.5 * Vec3(p.at(0), p.at(1), p.at(2)));
    if (spec.kind == "capsule")
        return Shape::capsule(p.at(0), 0.5 * p.at(1));
    if (spec.kind == "cylinder")
        return Shape::cylinder(p.at(0), 0.5 * p.at(1));
    if (spec.kind == "cone")
        return Shape::cone(p.at(0), 0.5 * p.at(1));
    if (spec.kind == "ellipsoid")
        return Shape::ellipsoid(Vec3(p.at(0), p.at(1), p.at(2)));
    if (spec.kind == "halfspace")
        return Shape::halfspace(Vec3(p.at(0), p.at(1), p.at(2)), p.at(3));
    throw std::invalid_argument("not a primitive shape: '" + spec.kind + "'");
}

}  // namespace hcd
