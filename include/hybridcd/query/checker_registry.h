// SPDX-License-Identifier: BSD-3-Clause
// Builds checkers by the names users pass to `--checker`.
#pragma once

#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/solid_semantics_checker.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hcd
{
/// Names accepted by makeChecker, in the order they are listed to users.
std::vector<std::string> checkerNames();

/// How a checker is asked to behave.
struct CheckerOptions
{
    /// Solid (default): closed components are solids (SolidSemanticsChecker). Checkers registered
    /// as surface-only (FCL) keep their own semantics.
    ContactSemantics semantics = ContactSemantics::Solid;
    /// For the LP checker: negative for exact mode, else the concavity up to which a convex piece's
    /// LP answer decides alone (approximate mode, conservative by at most this distance).
    double approximateTolerance = -1.0;
};

/// Builds the named checker over `scene`; throws std::invalid_argument listing the valid names
/// when `name` is unknown.
std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              const CheckerOptions &options = {});

/// Shorthand for a checker with the given semantics and default options otherwise.
inline std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                                     ContactSemantics semantics)
{
    CheckerOptions options;
    options.semantics = semantics;
    return makeChecker(name, scene, options);
}

/// Lets optional layers (such as the FCL adapter) add checkers by name.
using CheckerFactory = std::function<std::unique_ptr<CollisionChecker>(const CollisionScene &, const CheckerOptions &)>;
/// `surfaceOnly` marks checkers whose own semantics are kept (for comparisons with other tools).
void registerChecker(const std::string &name, CheckerFactory factory, bool surfaceOnly = false);
}  // namespace hcd
