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

/// Builds the named checker over `scene`; throws std::invalid_argument listing the valid names
/// when `name` is unknown. With ContactSemantics::Solid (the default) closed components are solids
/// (SolidSemanticsChecker); checkers registered as surface-only (FCL) keep their own semantics.
std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              ContactSemantics semantics = ContactSemantics::Solid);

/// Lets optional layers (such as the FCL adapter) add checkers by name.
using CheckerFactory = std::function<std::unique_ptr<CollisionChecker>(const CollisionScene &)>;
/// `surfaceOnly` marks checkers whose own semantics are kept (for comparisons with other tools).
void registerChecker(const std::string &name, CheckerFactory factory, bool surfaceOnly = false);
}  // namespace hcd
