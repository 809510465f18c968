// SPDX-License-Identifier: BSD-3-Clause
// A picture of a planning problem: the environment, the robot at its start and goal and at poses
// along a path, the path itself, and optionally bounding volumes around the robot.
//
// Composition (why each object has its own depth layer): the environment is drawn first, opaque;
// every robot placement is then drawn on its own layer and blended over it, fully where it is in
// front and faintly where walls hide it, so that a robot inside a building still shows through.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/render/camera.h"
#include "hybridcd/render/image.h"

#include <optional>
#include <vector>

namespace hcd::render
{
/// The colours of a picture (public so that tests and callers can tell objects apart).
struct Palette
{
    Rgb background{1.0, 1.0, 1.0};
    Rgb environment{0.78, 0.78, 0.78};  ///< grey: every environment pixel has r = g = b
    Rgb start{0.20, 0.65, 0.25};        ///< green
    Rgb goal{0.85, 0.20, 0.15};         ///< red
    Rgb volumes{0.95, 0.75, 0.10};      ///< amber
    Rgb pathLine{0.10, 0.10, 0.45};     ///< dark blue
};

/// One placement of the robot and how it is drawn.
struct RobotPlacement
{
    RigidTransform worldFromRobot;
    Rgb colour;
    double opacity = 1.0;        ///< where the robot is in front of the environment
    double hiddenOpacity = 0.3;  ///< where the environment hides it
    /// Drawn instead of the request's robot when set, placed by worldFromRobot: a scene's robots
    /// at one state, as one world-frame mesh (with the identity placement).
    const TriangleMesh *mesh = nullptr;
};

struct PictureRequest
{
    const TriangleMesh *environment = nullptr;  ///< world frame; may be null or empty
    const TriangleMesh *robot = nullptr;        ///< robot frame; required
    std::vector<RobotPlacement> placements;     ///< drawn in order; opaque ones hide later ones behind them
    /// Robot origins along the path (world frame), joined by a line; empty for none.
    std::vector<Vec3> pathLine;
    /// Further lines drawn as pathLine is (the other robots of a scene), each on its own.
    std::vector<std::vector<Vec3>> morePathLines;
    /// Bounding volumes drawn semi-transparent over everything else, in the world frame.
    const TriangleMesh *volumes = nullptr;
    View view = View::Isometric;
    int width = 800;
    int height = 600;
    /// Each pixel is the mean of supersample^2 samples (anti-aliasing); 1 for none.
    int supersample = 2;
    Palette palette;
};

/// Renders the request. Deterministic: the same request gives the same pixels. The camera is
/// fitted to the environment and every robot placement (and volume), with a 4% border.
/// Throws std::invalid_argument for a missing robot or a size outside 16..8192 pixels.
Image renderPicture(const PictureRequest &request);

/// The camera renderPicture uses for `request` at its final size (for tests mapping points to pixels).
Camera pictureCamera(const PictureRequest &request);

/// `count` poses spread evenly along a path by the distance its robot origin travels (by state
/// index when it does not move), interpolated between neighbouring states (linear in position,
/// spherical in rotation). The first is the path's first state and the last its last one; an empty
/// path gives none and a single state gives that state `count` times.
std::vector<RigidTransform> samplePath(const std::vector<RigidTransform> &path, std::size_t count);

/// The start-to-goal colour ramp at t in [0, 1].
Rgb rampColour(const Palette &palette, double t);
}  // namespace hcd::render
