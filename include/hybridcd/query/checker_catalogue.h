// SPDX-License-Identifier: BSD-3-Clause
// The checkers an application offers by name (`--checker`), as a value it builds and passes on.
#pragma once

#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/solid_semantics_checker.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hcd
{
/// How a checker is asked to behave.
struct CheckerOptions
{
    /// Solid (default): closed components are solids (SolidSemanticsChecker). Entries marked
    /// `keepsOwnSemantics` (FCL) ignore this.
    ContactSemantics semantics = ContactSemantics::Solid;
    /// Unset: exact mode. Set to T >= 0: approximate mode, where a checker may report contact when
    /// the meshes are up to T apart (never misses one). Only entries with `approximate` accept it.
    std::optional<double> approximateTolerance;
    /// A clearance grid of the environment and a sphere cover of the robot answer first where they
    /// can prove the answer (GridFirstChecker); entries marked `reference` never get it.
    bool clearanceGrid = true;
};

/// Makes one checker over a scene; the options were already checked against the entry.
using CheckerFactory = std::function<std::unique_ptr<CollisionChecker>(const CollisionScene &, const CheckerOptions &)>;

/// One named checker of a catalogue.
struct CheckerEntry
{
    std::string name;
    /// One line for help texts.
    std::string description;
    CheckerFactory factory;
    /// Its own contact semantics are kept (for comparisons with other tools): never wrapped in
    /// SolidSemanticsChecker.
    bool keepsOwnSemantics = false;
    /// Accepts CheckerOptions::approximateTolerance; other entries refuse it.
    bool approximate = false;
    /// A reference the others are tested against (bruteforce): built as it is, no grid first.
    bool reference = false;
};

/// An ordered list of named checkers. Applications start from builtIn() and add the optional
/// layers they link (e.g. fclCheckerEntry()); nothing is registered globally.
class CheckerCatalogue
{
public:
    /// The core checkers: obb, ellipsoid, hybrid, hybrid-ellipsoid-first, bruteforce, lp.
    static CheckerCatalogue builtIn();

    /// Appends `entry`; throws std::invalid_argument when its name is empty or already taken.
    void add(CheckerEntry entry);

    /// In the order they were added, which is the order shown to users.
    const std::vector<CheckerEntry> &entries() const { return entries_; }
    std::vector<std::string> names() const;
    /// nullptr when there is no entry of that name.
    const CheckerEntry *find(const std::string &name) const;

    /// Throws std::invalid_argument when `name` is unknown (listing the valid names) or when the
    /// entry refuses `options` (approximate mode). Lets callers fail before any loading.
    void check(const std::string &name, const CheckerOptions &options = {}) const;

    /// Builds the named checker over `scene`, after check().
    std::unique_ptr<CollisionChecker> make(const std::string &name, const CollisionScene &scene,
                                           const CheckerOptions &options = {}) const;

private:
    std::vector<CheckerEntry> entries_;
};

/// CheckerCatalogue::builtIn().make(...): the one-line way to a core checker.
std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              const CheckerOptions &options = {});

/// Shorthand for a core checker with the given semantics and default options otherwise.
inline std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                                     ContactSemantics semantics)
{
    CheckerOptions options;
    options.semantics = semantics;
    return makeChecker(name, scene, options);
}
}  // namespace hcd
