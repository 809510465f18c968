// SPDX-License-Identifier: BSD-3-Clause
// CollisionScene now lives in the geometry layer (io builds it without depending on the checkers);
// this header forwards there for existing includes.
#pragma once

#include "hybridcd/geometry/collision_scene.h"
