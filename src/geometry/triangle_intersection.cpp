// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/triangle_intersection.h"

#include "hybridcd/geometry/exact_predicates.h"
#include "plane_side.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>

namespace hcd
{
namespace
{
// A projection onto a coordinate plane: drops axis `dropped`, keeps (u, v) in cyclic order.
struct Projection
{
    int u, v;
    explicit Projection(int dropped) : u((dropped + 1) % 3), v((dropped + 2) % 3) {}
};

int orient2dProjected(const Projection &pr, const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    return orient2d(a[pr.u], a[pr.v], b[pr.u], b[pr.v], c[pr.u], c[pr.v]);
}

// For r collinear with p, q (in the projection): is r within the closed segment pq?
bool withinSegmentBox(const Projection &pr, const Vec3 &p, const Vec3 &q, const Vec3 &r)
{
    return std::min(p[pr.u], q[pr.u]) <= r[pr.u] && r[pr.u] <= std::max(p[pr.u], q[pr.u]) &&
           std::min(p[pr.v], q[pr.v]) <= r[pr.v] && r[pr.v] <= std::max(p[pr.v], q[pr.v]);
}

bool segmentsIntersect2d(const Projection &pr, const Vec3 &p, const Vec3 &q, const Vec3 &r, const Vec3 &s)
{
    const int o1 = orient2dProjected(pr, p, q, r), o2 = orient2dProjected(pr, p, q, s);
    const int o3 = orient2dProjected(pr, r, s, p), o4 = orient2dProjected(pr, r, s, q);
    if (o1 * o2 < 0 && o3 * o4 < 0)
        return true;
    return (o1 == 0 && withinSegmentBox(pr, p, q, r)) || (o2 == 0 && withinSegmentBox(pr, p, q, s)) ||
           (o3 == 0 && withinSegmentBox(pr, r, s, p)) || (o4 == 0 && withinSegmentBox(pr, r, s, q));
}

// Closed point-in-triangle in the projection; the projected triangle must be non-degenerate.
bool pointInTriangle2d(const Projection &pr, const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    const int s = orient2dProjected(pr, a, b, c);
    return orient2dProjected(pr, a, b, p) * s >= 0 && orient2dProjected(pr, b, c, p) * s >= 0 &&
           orient2dProjected(pr, c, a, p) * s >= 0;
}

bool segmentIntersectsTriangle2d(const Projection &pr, const Vec3 &p, const Vec3 &q, const Vec3 &a, const Vec3 &b,
                                 const Vec3 &c)
{
    return pointInTriangle2d(pr, p, a, b, c) || segmentsIntersect2d(pr, p, q, a, b) ||
           segmentsIntersect2d(pr, p, q, b, c) || segmentsIntersect2d(pr, p, q, c, a);
}

// Whether some edge line of t (non-degenerate in the projection) has every vertex of o strictly on
// the side away from t: for two coplanar closed triangles the only way to be disjoint (separating
// axes: disjoint convex polygons have a strictly separating line parallel to an edge of one).
// `own` is orient2dProjected of t's corners in order.
bool separatedByAnEdge2d(const Projection &pr, const Vec3 *const t[3], int own, const Vec3 *const o[3])
{
    for (int i = 0; i < 3; ++i)
    {
        const Vec3 &p = *t[i], &q = *t[(i + 1) % 3];
        bool outside = true;
        for (int j = 0; j < 3 && outside; ++j)
        {
            const int side = orient2dProjected(pr, p, q, *o[j]);
            outside = side != 0 && side != own;
        }
        if (outside)
            return true;
    }
    return false;
}

// A coordinate plane onto which the non-degenerate triangle projects with non-zero area, so the
// projection is one-to-one on the triangle's plane. The largest normal component is tried first.
Projection faithfulProjection(const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    const Vec3 n = (b - a).cross(c - a).cwiseAbs();
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return n[i] > n[j]; });
    for (int axis : order)
        if (orient2dProjected(Projection(axis), a, b, c) != 0)
            return Projection(axis);
    return Projection(order[0]);  // unreachable for non-degenerate triangles
}

// Segment pq against a non-degenerate triangle, given the exact sides of p and q w.r.t. its plane.
bool segmentCrossesTriangle(const Vec3 &p, const Vec3 &q, int sideP, int sideQ, const Vec3 &a, const Vec3 &b,
                            const Vec3 &c)
{
    if (sideP * sideQ > 0)
        return false;
    if (sideP == 0 && sideQ == 0)
        return segmentIntersectsTriangle2d(faithfulProjection(a, b, c), p, q, a, b, c);
    // The line pq is not in the plane and the segment reaches it: the crossing point lies in the
    // closed triangle iff the line passes no edge strictly on opposite sides (Pluecker test).
    const int o1 = orient3d(p, q, a, b), o2 = orient3d(p, q, b, c), o3 = orient3d(p, q, c, a);
    const bool anyPositive = o1 > 0 || o2 > 0 || o3 > 0;
    const bool anyNegative = o1 < 0 || o2 < 0 || o3 < 0;
    return !(anyPositive && anyNegative);
}
// Whether an edge of x (its corners' exact sides sx of y's plane) meets the non-degenerate
// triangle y: segmentCrossesTriangle for each edge, with each vertex on the plane tested once. An
// edge with one end on the plane meets it only there, so that end's test decides it; an edge in
// the plane meets y iff an end lies in y or it crosses an edge of y; an edge with ends strictly on
// opposite sides takes the line test.
bool edgesMeetTriangle(const Vec3 *const x[3], const int sx[3], const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    bool projected = false;
    Projection pr(0);
    const auto projection = [&]() -> const Projection & {
        if (!projected)
            pr = faithfulProjection(a, b, c);
        projected = true;
        return pr;
    };
    for (int i = 0; i < 3; ++i)
        if (sx[i] == 0 && pointInTriangle2d(projection(), *x[i], a, b, c))
            return true;
    for (int i = 0; i < 3; ++i)
    {
        const int j = (i + 1) % 3;
        const Vec3 &p = *x[i], &q = *x[j];
        if (sx[i] == 0 && sx[j] == 0)
        {
            if (segmentsIntersect2d(projection(), p, q, a, b) || segmentsIntersect2d(projection(), p, q, b, c) ||
                segmentsIntersect2d(projection(), p, q, c, a))
                return true;
        }
        else if (sx[i] * sx[j] < 0 && segmentCrossesTriangle(p, q, sx[i], sx[j], a, b, c))
            return true;
    }
    return false;
}

// Two triangles each of which has one vertex strictly on one side of the other's plane and two
// strictly on the other (sa: a's sides of b's plane, orient3d(b0, b1, b2, a_i); sb: b's of a's).
// Devillers and Guigue, "Faster triangle-triangle intersection tests" (2002): with each triangle
// turned so that its lone vertex comes first, and the other triangle's order reversed where that
// vertex is on the negative side, the two triangles' segments on the common line of their planes
// overlap iff two orientations are not positive. Exact, as orient3d() is.
bool straddlingTrianglesIntersect(const Vec3 *const a[3], const int sa[3], const Vec3 *const b[3], const int sb[3])
{
    // The lone vertex: the one whose side differs from the other two.
    const auto lone = [](const int s[3]) { return s[0] == s[1] ? 2 : (s[0] == s[2] ? 1 : 0); };
    const int la = lone(sa), lb = lone(sb);
    const Vec3 *p1 = a[la], *q1 = a[(la + 1) % 3], *r1 = a[(la + 2) % 3];
    const Vec3 *p2 = b[lb], *q2 = b[(lb + 1) % 3], *r2 = b[(lb + 2) % 3];
    if (sa[la] < 0)
        std::swap(q2, r2);
    if (sb[lb] < 0)
        std::swap(q1, r1);
    return orient3d(*q1, *q2, *p2, *p1) <= 0 && orient3d(*p1, *r2, *p2, *r1) <= 0;
}

// A point with a NaN or infinite coordinate: it has no position, so nothing can be shown to miss it.
bool anyNonFinite(std::initializer_list<const Vec3 *> points)
{
    for (const Vec3 *p : points)
        if (!p->allFinite())
            return true;
    return false;
}
}  // namespace

bool isDegenerateTriangle(const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    return orient2dProjected(Projection(0), a, b, c) == 0 && orient2dProjected(Projection(1), a, b, c) == 0 &&
           orient2dProjected(Projection(2), a, b, c) == 0;
}

bool segmentsIntersect(const Vec3 &p, const Vec3 &q, const Vec3 &r, const Vec3 &s)
{
    if (orient3d(p, q, r, s) != 0)
        return false;
    if (anyNonFinite({&p, &q, &r, &s}))
        return true;  // orient3d gives 0 for non-finite input: such a pair is never called apart
    // Coplanar: some coordinate projection is one-to-one on the common plane (or line), and no
    // projection can separate segments that meet, so they meet iff they meet in all three.
    return segmentsIntersect2d(Projection(0), p, q, r, s) && segmentsIntersect2d(Projection(1), p, q, r, s) &&
           segmentsIntersect2d(Projection(2), p, q, r, s);
}

bool segmentIntersectsTriangle(const Vec3 &p, const Vec3 &q, const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    if (anyNonFinite({&p, &q, &a, &b, &c}))
        return true;
    if (isDegenerateTriangle(a, b, c))
        return segmentsIntersect(p, q, a, b) || segmentsIntersect(p, q, b, c) || segmentsIntersect(p, q, c, a);
    return segmentCrossesTriangle(p, q, orient3d(a, b, c, p), orient3d(a, b, c, q), a, b, c);
}

bool trianglesIntersect(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    // Plane rejection first: it settles the vast majority of pairs in floating point. The signs the
    // filter certifies are orient3d()'s; only the others take the predicate's own path.
    int sb[3], sa[3];
    const PlaneOrientationFilter planeA(a0, a1, a2);
    if (filteredSides(planeA, b0, b1, b2, sb))
        return false;
    const PlaneOrientationFilter planeB(b0, b1, b2);
    if (filteredSides(planeB, a0, a1, a2, sa))
        return false;
    const Vec3 *b[3] = {&b0, &b1, &b2}, *a[3] = {&a0, &a1, &a2};
    // A sign the filter left open is orient3d()'s; four points sharing one coordinate exactly are
    // coplanar (what orient3d() concludes after its own filter fails again), the common case of
    // robots and walls of one height.
    const auto sideOf = [](const Vec3 &p0, const Vec3 &p1, const Vec3 &p2, const Vec3 &q) {
        for (int k = 0; k < 3; ++k)
            if (p0[k] == q[k] && p1[k] == q[k] && p2[k] == q[k])
                return 0;
        return orient3d(p0, p1, p2, q);
    };
    for (int i = 0; i < 3; ++i)
        if (sb[i] == 0)
            sb[i] = sideOf(a0, a1, a2, *b[i]);
    const int sb0 = sb[0], sb1 = sb[1], sb2 = sb[2];
    if ((sb0 > 0 && sb1 > 0 && sb2 > 0) || (sb0 < 0 && sb1 < 0 && sb2 < 0))
        return false;
    for (int i = 0; i < 3; ++i)
        if (sa[i] == 0)
            sa[i] = sideOf(b0, b1, b2, *a[i]);
    const int sa0 = sa[0], sa1 = sa[1], sa2 = sa[2];
    if ((sa0 > 0 && sa1 > 0 && sa2 > 0) || (sa0 < 0 && sa1 < 0 && sa2 < 0))
        return false;

    // A degenerate triangle has every point on "its plane", so degeneracy is only possible (and
    // only worth the predicates to decide) when all of the other triangle's signs are zero.
    const bool allSbZero = sb0 == 0 && sb1 == 0 && sb2 == 0;
    const bool allSaZero = sa0 == 0 && sa1 == 0 && sa2 == 0;
    const bool degenerateA = allSbZero && isDegenerateTriangle(a0, a1, a2);
    const bool degenerateB = allSaZero && isDegenerateTriangle(b0, b1, b2);
    if (degenerateA || degenerateB)
    {
        // A degenerate triangle is the union of its edges.
        if (degenerateA && degenerateB)
        {
            const Vec3 *ea[3][2] = {{&a0, &a1}, {&a1, &a2}, {&a2, &a0}};
            const Vec3 *eb[3][2] = {{&b0, &b1}, {&b1, &b2}, {&b2, &b0}};
            for (auto &x : ea)
                for (auto &y : eb)
                    if (segmentsIntersect(*x[0], *x[1], *y[0], *y[1]))
                        return true;
            return false;
        }
        if (degenerateA)
            return segmentIntersectsTriangle(a0, a1, b0, b1, b2) || segmentIntersectsTriangle(a1, a2, b0, b1, b2) ||
                   segmentIntersectsTriangle(a2, a0, b0, b1, b2);
        return segmentIntersectsTriangle(b0, b1, a0, a1, a2) || segmentIntersectsTriangle(b1, b2, a0, a1, a2) ||
               segmentIntersectsTriangle(b2, b0, a0, a1, a2);
    }

    // Every sign against one triangle's plane zero: the triangles are coplanar (for finite input the
    // other's signs are then all zero too), or that triangle has a vertex that is not finite, which
    // leaves it no plane to measure against.
    if (allSbZero || allSaZero)
    {
        // Non-finite input lands here or above: report it as touching.
        if (anyNonFinite({&a0, &a1, &a2, &b0, &b1, &b2}))
            return true;
        // Coplanar: they meet iff no edge line of either separates them. Neither is degenerate
        // (above) and the projection is one to one on the common plane, so both project with
        // non-zero area: neither orientation is 0.
        const Projection pr = faithfulProjection(a0, a1, a2);
        const int ownA = orient2dProjected(pr, a0, a1, a2), ownB = orient2dProjected(pr, b0, b1, b2);
        return !separatedByAnEdge2d(pr, a, ownA, b) && !separatedByAnEdge2d(pr, b, ownB, a);
    }

    // Each triangle strictly straddles the other's plane (no vertex on it), the common case:
    // Devillers and Guigue's test, two orientations instead of the edges' up to twelve.
    if (sa0 != 0 && sa1 != 0 && sa2 != 0 && sb0 != 0 && sb1 != 0 && sb2 != 0)
        return straddlingTrianglesIntersect(a, sa, b, sb);

    // Left: some vertex on the other's plane. They meet iff an edge of one triangle meets the other.
    // Where one triangle has no two vertices strictly on opposite sides of the other's plane (nor
    // all on it, above), it meets that plane only in its vertices on it (one, or the edge between
    // two), so its own edges' test decides alone: the common case of prisms on one floor, whose
    // side faces stand on the others' bottom faces.
    const auto straddles = [](const int s[3]) {
        return (s[0] > 0 || s[1] > 0 || s[2] > 0) && (s[0] < 0 || s[1] < 0 || s[2] < 0);
    };
    if (!straddles(sa))
        return edgesMeetTriangle(a, sa, b0, b1, b2);
    if (!straddles(sb))
        return edgesMeetTriangle(b, sb, a0, a1, a2);
    return edgesMeetTriangle(a, sa, b0, b1, b2) || edgesMeetTriangle(b, sb, a0, a1, a2);
}
}  // namespace hcd
