// SPDX-License-Identifier: BSD-3-Clause
// One planner as a .cfg [planner] section asks for it (plain data; the catalogue builds it).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hcd
{
/// A planner type such as "rrtconnect", an optional display name (from "type.name=..."), and
/// "param=value" settings in file order.
struct PlannerRequest
{
    /// Planner type, matched case-insensitively against plannerNames().
    std::string type;
    /// Name given to the planner through Planner::setName; empty keeps the planner's own name.
    std::string displayName;
    /// OMPL parameter names and values, applied in this order.
    std::vector<std::pair<std::string, std::string>> parameters;
};
}  // namespace hcd
