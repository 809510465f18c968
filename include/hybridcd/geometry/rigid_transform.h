// SPDX-License-Identifier: BSD-3-Clause
// Rigid transforms: the pose of a body as a rotation followed by a translation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hcd
{
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// A rigid transform x -> rotation * x + translation. Names of variables that hold one say which
/// frames it maps between, e.g. `worldFromRobot` maps robot-frame points to world coordinates.
struct RigidTransform
{
    Mat3 rotation = Mat3::Identity();
    Vec3 translation = Vec3::Zero();

    static RigidTransform identity() { return {}; }

    /// SE3 pose as OMPL.app builds it: translation (x, y, z) times the unit quaternion (w, x, y, z).
    /// The quaternion is normalised here so that slightly denormalised input stays rigid; any finite
    /// non-zero quaternion gives a rotation, however large or small its components, and the zero
    /// quaternion gives the identity.
    static RigidTransform fromTranslationQuaternion(const Vec3 &t, double qw, double qx, double qy, double qz);

    /// The quaternion (w, x, y, z) scaled to unit norm, rescaled first when the squares of its
    /// components over- or underflow; the zero quaternion gives the identity, and non-finite
    /// components are returned as they are. fromTranslationQuaternion rotates by this quaternion.
    static Eigen::Quaterniond unitQuaternion(double qw, double qx, double qy, double qz);

    /// SE2 pose as OMPL.app builds it: translation (x, y, 0) times a rotation by yaw about +z.
    static RigidTransform fromPlanarPose(double x, double y, double yaw);

    /// Rotation by `angle` radians about `axis` (need not be unit length, any finite non-zero length
    /// works; a zero axis means no rotation).
    static RigidTransform fromAxisAngle(const Vec3 &t, const Vec3 &axis, double angle);

    /// Applies the transform to a point. Every checker maps robot vertices through this one
    /// function, so that all of them see bit-identical world coordinates.
    /// Written out (each row's products added left to right, then the translation) so that it
    /// inlines wherever it is called: the compiler left Eigen's product as a call in the hot loops.
    Vec3 apply(const Vec3 &p) const
    {
        const Mat3 &r = rotation;
        return {r(0, 0) * p.x() + r(0, 1) * p.y() + r(0, 2) * p.z() + translation.x(),
                r(1, 0) * p.x() + r(1, 1) * p.y() + r(1, 2) * p.z() + translation.y(),
                r(2, 0) * p.x() + r(2, 1) * p.y() + r(2, 2) * p.z() + translation.z()};
    }

    RigidTransform operator*(const RigidTransform &other) const
    {
        return {rotation * other.rotation, rotation * other.translation + translation};
    }

    RigidTransform inverse() const
    {
        Mat3 rt = rotation.transpose();
        return {rt, -(rt * translation)};
    }

    /// True when every entry is a finite number (NaN or infinite poses are rejected by callers).
    bool isFinite() const { return rotation.allFinite() && translation.allFinite(); }
};
}  // namespace hcd
