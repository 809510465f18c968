// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/solid_components.h"

#include "hybridcd/geometry/exact_predicates.h"
#include "hybridcd/geometry/triangle_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

namespace hcd
{
namespace
{
using Triangle = TriangleMesh::Triangle;

// canonical[v] is the smallest index of a vertex at the same point as v, so that components and
// repeated faces are found even when the mesh was not welded.
std::vector<std::uint32_t> canonicalVertices(const TriangleMesh &mesh)
{
    const std::vector<Vec3> &v = mesh.vertices;
    std::vector<std::uint32_t> order(v.size());
    std::iota(order.begin(), order.end(), 0u);
    // NaN sorts after every number, so the order stays strict-weak (NaN vertices merge with none).
    const auto less = [](double a, double b) { return !std::isnan(a) && (std::isnan(b) || a < b); };
    std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
        for (int k = 0; k < 3; ++k)
        {
            if (less(v[i][k], v[j][k]))
                return true;
            if (less(v[j][k], v[i][k]))
                return false;
        }
        return i < j;
    });
    std::vector<std::uint32_t> canonical(v.size());
    for (std::size_t k = 0; k < order.size(); ++k)
        canonical[order[k]] = k > 0 && v[order[k]] == v[order[k - 1]] ? canonical[order[k - 1]] : order[k];
    return canonical;
}

struct UnionFind
{
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t x)
    {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];  // path halving
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b)
    {
        a = find(a);
        b = find(b);
        if (a != b)
            parent[std::max(a, b)] = std::min(a, b);
    }
};

// A face as its sorted canonical corners, the same for either orientation.
Triangle faceKey(const Triangle &t, const std::vector<std::uint32_t> &canonical)
{
    Triangle key{canonical[t[0]], canonical[t[1]], canonical[t[2]]};
    std::sort(key.begin(), key.end());
    return key;
}

// The triangles of `triangles` that do not repeat an earlier one's vertex set (the first of each
// group is kept), with their keys.
std::vector<std::pair<Triangle, std::uint32_t>> distinctFaces(const TriangleMesh &mesh,
                                                              const std::vector<std::uint32_t> &canonical,
                                                              const std::vector<std::uint32_t> &triangles)
{
    std::vector<std::pair<Triangle, std::uint32_t>> faces;
    faces.reserve(triangles.size());
    for (std::uint32_t t : triangles)
        faces.emplace_back(faceKey(mesh.triangles[t], canonical), t);
    std::sort(faces.begin(), faces.end());
    faces.erase(
        std::unique(faces.begin(), faces.end(), [](const auto &x, const auto &y) { return x.first == y.first; }),
        faces.end());
    return faces;
}

// The distinct faces of `triangles` whose reverse (the same corners in the other order) is not
// among them, with their keys, sorted by key: repeats in the same orientation count once.
std::vector<std::pair<Triangle, std::uint32_t>> unpairedFaces(const TriangleMesh &mesh,
                                                              const std::vector<std::uint32_t> &canonical,
                                                              const std::vector<std::uint32_t> &triangles)
{
    struct OrientedFace
    {
        Triangle key;
        bool even;  // the corners in an even permutation of the key's order
        std::uint32_t triangle;
    };
    std::vector<OrientedFace> faces;
    faces.reserve(triangles.size());
    for (std::uint32_t t : triangles)
    {
        const std::uint32_t a = canonical[mesh.triangles[t][0]], b = canonical[mesh.triangles[t][1]],
                            c = canonical[mesh.triangles[t][2]];
        // Rotated to start at the least corner, the order is even when the other two ascend.
        const bool even = a < b && a < c ? b < c : b < a && b < c ? c < a : a < b;
        faces.push_back({faceKey(mesh.triangles[t], canonical), even, t});
    }
    std::sort(faces.begin(), faces.end(), [](const OrientedFace &x, const OrientedFace &y) {
        return x.key != y.key ? x.key < y.key : x.even != y.even ? x.even < y.even : x.triangle < y.triangle;
    });
    std::vector<std::pair<Triangle, std::uint32_t>> out;
    for (std::size_t i = 0; i < faces.size();)
    {
        std::size_t j = i;
        bool bothOrientations = false;
        for (; j < faces.size() && faces[j].key == faces[i].key; ++j)
            bothOrientations = bothOrientations || faces[j].even != faces[i].even;
        if (!bothOrientations)
            out.emplace_back(faces[i].key, faces[i].triangle);
        i = j;
    }
    return out;
}

bool everyEdgeEven(const std::vector<std::pair<Triangle, std::uint32_t>> &faces)
{
    std::vector<Triangle> sorted;
    sorted.reserve(faces.size());
    for (const auto &f : faces)
        sorted.push_back(f.first);
    return everyEdgeUsedEvenly(sorted);
}

bool contains(const BoundingBox &box, const Vec3 &p)
{
    return box.min.x() <= p.x() && p.x() <= box.max.x() && box.min.y() <= p.y() && p.y() <= box.max.y() &&
           box.min.z() <= p.z() && p.z() <= box.max.z();
}

bool overlaps(const BoundingBox &a, const BoundingBox &b)
{
    return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() && b.min.y() <= a.max.y() &&
           a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

// Cells along one axis of a uniform grid. cell() is monotone in v (floating-point subtraction and
// scaling are), so an object binned by the cells of its interval's end points is listed in the
// cell of every point of that interval: binning is conservative without any epsilon.
struct GridAxis
{
    double origin = 0.0;
    double inverseWidth = 0.0;
    int cells = 1;

    GridAxis() = default;
    GridAxis(double lo, double hi, int n) : origin(lo), cells(n)
    {
        inverseWidth = hi > lo && n > 1 ? double(n) / (hi - lo) : 0.0;
        if (!std::isfinite(inverseWidth))
            inverseWidth = 0.0, cells = 1;
    }
    int cell(double v) const
    {
        const double f = (v - origin) * inverseWidth;
        if (!(f > 0.0))
            return 0;
        return f >= double(cells) ? cells - 1 : int(f);
    }
};

// Cells per axis for about `target` roughly cubic cells over the given extents (flat axes get one).
template <int N>
std::array<int, N> gridShape(const std::array<double, N> &extent, double target, int maxPerAxis)
{
    double volume = 1.0;
    int spanned = 0;
    for (double e : extent)
        if (e > 0.0 && std::isfinite(e))
            volume *= e, ++spanned;
    std::array<int, N> shape;
    shape.fill(1);
    if (spanned == 0)
        return shape;
    const double side = std::pow(volume / target, 1.0 / spanned);
    for (int i = 0; i < N; ++i)
        if (extent[i] > 0.0 && std::isfinite(extent[i]))
            shape[i] = int(std::clamp(std::ceil(extent[i] / side), 1.0, double(maxPerAxis)));
    return shape;
}

// A deduplicated triangle of a solid. yzSign is the sign of its normal's x component, i.e. the
// orientation of its projection onto the (y, z) plane, which the +x ray test needs.
struct SolidTriangle
{
    Vec3 a, b, c;
    int yzSign;
};

// One triangle listed in a (y, z) cell, with its box (the exact floating-point extremes of its
// corners) so most candidates are rejected without touching the corners.
struct CellEntry
{
    double xmax, ymin, ymax, zmin, zmax;
    std::uint32_t triangle;
};

enum class Hit
{
    None,       ///< the ray does not meet the triangle
    Crossing,   ///< the ray crosses the triangle's interior transversally
    Ambiguous,  ///< the ray meets an edge or vertex, or runs in the triangle's plane: try another
    Surface,    ///< the ray's origin lies on the closed triangle
};

// Parity of the crossings along one ray, and whether the ray's answer can be trusted.
struct RayCount
{
    bool odd = false;
    bool ambiguous = false;
    bool surface = false;

    void add(Hit hit)
    {
        surface = surface || hit == Hit::Surface;
        ambiguous = ambiguous || hit == Hit::Ambiguous;
        odd = odd != (hit == Hit::Crossing);
    }
};

// The ray from p towards +x against a triangle whose (y, z) box holds p's and whose x extent
// reaches p. Along the ray, orient3d(p, q, u, v) reduces exactly to orient2d of the (y, z)
// projections, so the edge tests are planar.
Hit xRayHit(const SolidTriangle &t, const Vec3 &p)
{
    const int o1 = orient2d(t.a.y(), t.a.z(), t.b.y(), t.b.z(), p.y(), p.z());
    const int o2 = orient2d(t.b.y(), t.b.z(), t.c.y(), t.c.z(), p.y(), p.z());
    const int o3 = orient2d(t.c.y(), t.c.z(), t.a.y(), t.a.z(), p.y(), p.z());
    if ((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0))
        return Hit::None;  // the line misses the triangle
    const int side = orient3d(t.a, t.b, t.c, p);
    if (t.yzSign == 0)
    {
        // The triangle is parallel to the ray: the line misses its plane or runs within it.
        if (side != 0)
            return Hit::None;
        return segmentIntersectsTriangle(p, p, t.a, t.b, t.c) ? Hit::Surface : Hit::Ambiguous;
    }
    // The projection is one-to-one on the plane, and p's projection lies in the closed triangle's.
    if (side == 0)
        return Hit::Surface;
    if (side * t.yzSign > 0)
        return Hit::None;  // the line meets the plane behind p
    return o1 == 0 || o2 == 0 || o3 == 0 ? Hit::Ambiguous : Hit::Crossing;
}

// The segment p -> q, with q outside the solid's bounds, against a triangle of the solid.
Hit segmentHit(const SolidTriangle &t, const Vec3 &p, const Vec3 &q)
{
    const int sideP = orient3d(t.a, t.b, t.c, p), sideQ = orient3d(t.a, t.b, t.c, q);
    if (sideP * sideQ > 0)
        return Hit::None;
    if (sideP == 0 && sideQ == 0)
        return segmentIntersectsTriangle(p, q, t.a, t.b, t.c) ? Hit::Ambiguous : Hit::None;
    if (sideP == 0)
        return segmentIntersectsTriangle(p, p, t.a, t.b, t.c) ? Hit::Surface : Hit::None;
    if (sideQ == 0)
        return Hit::None;  // q is outside the bounds, so outside the triangle
    // The segment crosses the plane; where, relative to the edges, the Pluecker signs tell.
    const int o1 = orient3d(p, q, t.a, t.b), o2 = orient3d(p, q, t.b, t.c), o3 = orient3d(p, q, t.c, t.a);
    if ((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0))
        return Hit::None;
    return o1 == 0 || o2 == 0 || o3 == 0 ? Hit::Ambiguous : Hit::Crossing;
}

// Deterministic directions with no special relation to axis-aligned or other structured geometry.
Vec3 genericDirection(std::uint64_t k)
{
    std::uint64_t state = 0x9e3779b97f4a7c15ULL * (k + 1);
    const auto next = [&state] {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;  // in [-1, 1)
    };
    for (;;)
    {
        const Vec3 d(next(), next(), next());
        const double n = d.norm();
        if (n > 0.25 && n <= 1.0)
            return d / n;
    }
}

// A closed component indexed for rays towards +x: a uniform grid over its (y, z) extent lists the
// triangles whose (y, z) box meets each cell, sorted by decreasing x maximum so that a query
// stops at the first triangle lying wholly behind the ray's origin.
struct Solid
{
    std::uint32_t component = 0;
    BoundingBox bounds;
    std::vector<SolidTriangle> triangles;
    std::vector<BoundingBox> triangleBounds;
    GridAxis y, z;
    std::vector<std::uint32_t> cellStart;
    std::vector<CellEntry> entries;

    Solid(const TriangleMesh &mesh, std::uint32_t componentIndex, const MeshComponent &component,
          const std::vector<std::pair<Triangle, std::uint32_t>> &faces)
        : component(componentIndex),
          bounds(component.bounds)
    {
        triangles.reserve(faces.size());
        triangleBounds.reserve(faces.size());
        for (const auto &f : faces)
        {
            const Vec3 &a = mesh.corner(f.second, 0), &b = mesh.corner(f.second, 1), &c = mesh.corner(f.second, 2);
            triangles.push_back({a, b, c, orient2d(a.y(), a.z(), b.y(), b.z(), c.y(), c.z())});
            BoundingBox box;
            box.extend(a);
            box.extend(b);
            box.extend(c);
            triangleBounds.push_back(box);
        }

        // About two triangles' worth of cells each: large triangles then span few cells, and a
        // cell holds few small ones.
        const Vec3 extent = bounds.max - bounds.min;
        const auto shape = gridShape<2>({extent.y(), extent.z()}, std::max(1.0, 0.5 * double(triangles.size())), 1024);
        y = GridAxis(bounds.min.y(), bounds.max.y(), shape[0]);
        z = GridAxis(bounds.min.z(), bounds.max.z(), shape[1]);

        const std::size_t cells = std::size_t(y.cells) * std::size_t(z.cells);
        std::vector<std::uint32_t> count(cells + 1, 0);
        forEachCell([&](std::size_t cell, std::uint32_t) { ++count[cell + 1]; });
        std::partial_sum(count.begin(), count.end(), count.begin());
        cellStart = count;
        entries.resize(cellStart.back());
        forEachCell([&](std::size_t cell, std::uint32_t t) {
            const BoundingBox &box = triangleBounds[t];
            entries[count[cell]++] = {box.max.x(), box.min.y(), box.max.y(), box.min.z(), box.max.z(), t};
        });
        for (std::size_t cell = 0; cell < cells; ++cell)
            std::sort(entries.begin() + cellStart[cell], entries.begin() + cellStart[cell + 1],
                      [](const CellEntry &u, const CellEntry &v) {
                          return u.xmax != v.xmax ? u.xmax > v.xmax : u.triangle < v.triangle;
                      });
    }

    template <typename F>
    void forEachCell(F &&visit) const
    {
        for (std::uint32_t t = 0; t < triangles.size(); ++t)
        {
            const BoundingBox &box = triangleBounds[t];
            const int y0 = y.cell(box.min.y()), y1 = y.cell(box.max.y());
            const int z0 = z.cell(box.min.z()), z1 = z.cell(box.max.z());
            for (int i = y0; i <= y1; ++i)
                for (int j = z0; j <= z1; ++j)
                    visit(std::size_t(i) * std::size_t(z.cells) + std::size_t(j), t);
        }
    }

    bool contains(const Vec3 &p) const
    {
        if (!hcd::contains(bounds, p))
            return false;
        // Every triangle that holds p or crosses the +x ray is listed in p's cell with xmax >= p.x,
        // so one pass both detects p on the surface and counts crossings.
        const std::size_t cell = std::size_t(y.cell(p.y())) * std::size_t(z.cells) + std::size_t(z.cell(p.z()));
        RayCount count;
        for (std::uint32_t k = cellStart[cell], end = cellStart[cell + 1]; k < end && !count.surface; ++k)
        {
            const CellEntry &e = entries[k];
            if (e.xmax < p.x())
                break;
            if (p.y() < e.ymin || p.y() > e.ymax || p.z() < e.zmin || p.z() > e.zmax)
                continue;
            count.add(xRayHit(triangles[e.triangle], p));
        }
        if (count.surface)
            return true;
        return count.ambiguous ? containsByGenericRays(p) : count.odd;
    }

    // The rare fallback when the +x ray grazes an edge or runs in a face's plane: rays in generic
    // directions, tested against every triangle whose box meets the segment's box.
    bool containsByGenericRays(const Vec3 &p) const
    {
        // p lies in the bounds, so any point farther from it than the diagonal lies outside.
        const double reach = 2.0 * (bounds.max - bounds.min).norm() + 1.0;
        bool odd = false;
        for (std::uint64_t attempt = 0; attempt < 64; ++attempt)
        {
            const Vec3 q = p + reach * genericDirection(attempt);
            BoundingBox segment;
            segment.extend(p);
            segment.extend(q);
            RayCount count;
            for (std::size_t t = 0; t < triangles.size() && !count.ambiguous && !count.surface; ++t)
                if (overlaps(segment, triangleBounds[t]))
                    count.add(segmentHit(triangles[t], p, q));
            if (count.surface)
                return true;
            odd = count.odd;
            if (!count.ambiguous)
                return odd;
        }
        // Unreachable in practice: a point off the surface has only finitely many lines through
        // edges and vertices, and generic directions miss them.
        return odd;
    }
};
}  // namespace

namespace
{
using FaceList = std::vector<std::pair<Triangle, std::uint32_t>>;

// Whether a component's distinct faces (sorted by key) close (every edge used by an even number of
// them, as everyEdgeUsedEvenly), and if so its shells, into `shells`: faces joined across every edge
// that exactly two of them share. Two closed surfaces that meet only at vertices, or at edges that
// more than two faces share (a cube with a tetrahedron inside touching one of its corners), come
// apart; each holds a solid, and parity over their union would count a point inside both as
// outside. `shells` gets the shells when every one of them is closed, else none (the component
// then stays one solid, decided by parity as before). One sort of the edges serves both.
bool closedShells(const FaceList &faces, std::vector<FaceList> &shells)
{
    shells.clear();
    struct EdgeUse
    {
        std::uint32_t a, b, face;
        bool operator<(const EdgeUse &o) const { return a != o.a ? a < o.a : b != o.b ? b < o.b : face < o.face; }
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * faces.size());
    for (std::uint32_t f = 0; f < faces.size(); ++f)
    {
        const Triangle &t = faces[f].first;  // sorted corners
        uses.push_back({t[0], t[1], f});
        uses.push_back({t[1], t[2], f});
        uses.push_back({t[0], t[2], f});
    }
    if (uses.empty())
        return false;
    std::sort(uses.begin(), uses.end());
    // The end of the run of uses of the edge uses[i] starts.
    const auto edgeEnd = [&](std::size_t i) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b)
            ++j;
        return j;
    };
    UnionFind joined(faces.size());
    for (std::size_t i = 0; i < uses.size();)
    {
        const std::size_t j = edgeEnd(i);
        if ((j - i) % 2 != 0)
            return false;  // open
        if (j - i == 2)
            joined.unite(uses[i].face, uses[i + 1].face);
        i = j;
    }
    std::vector<std::int64_t> shellOfRoot(faces.size(), -1);
    std::vector<FaceList> out;
    for (std::uint32_t f = 0; f < faces.size(); ++f)
    {
        std::int64_t &slot = shellOfRoot[joined.find(f)];
        if (slot < 0)
        {
            slot = std::int64_t(out.size());
            out.emplace_back();
        }
        out[std::size_t(slot)].push_back(faces[f]);  // still sorted by key
    }
    if (out.size() < 2)
        return true;
    // Every shell closed: an edge that joined two faces lies within one shell, so only the edges
    // used by four faces or more can be used an odd number of times by some shell.
    std::vector<std::int64_t> shellsAtEdge;
    for (std::size_t i = 0; i < uses.size();)
    {
        const std::size_t j = edgeEnd(i);
        if (j - i > 2)
        {
            shellsAtEdge.clear();
            for (std::size_t k = i; k < j; ++k)
                shellsAtEdge.push_back(shellOfRoot[joined.find(uses[k].face)]);
            std::sort(shellsAtEdge.begin(), shellsAtEdge.end());
            for (std::size_t k = 0; k < shellsAtEdge.size();)
            {
                std::size_t l = k;
                while (l < shellsAtEdge.size() && shellsAtEdge[l] == shellsAtEdge[k])
                    ++l;
                if ((l - k) % 2 != 0)
                    return true;  // a shell left open: the component stays one solid
                k = l;
            }
        }
        i = j;
    }
    shells = std::move(out);
    return true;
}

// The components of `mesh` given its canonical vertices; `closedFaces`, if given, receives the
// distinct faces of each component (empty for open ones), which the closedness test sorts anyway.
std::vector<MeshComponent> componentsOf(const TriangleMesh &mesh, const std::vector<std::uint32_t> &canonical,
                                        std::vector<FaceList> *closedFaces)
{
    UnionFind sets(mesh.vertices.size());
    for (const Triangle &t : mesh.triangles)
    {
        sets.unite(canonical[t[0]], canonical[t[1]]);
        sets.unite(canonical[t[0]], canonical[t[2]]);
    }
    std::vector<std::int64_t> componentOfRoot(mesh.vertices.size(), -1);
    std::vector<MeshComponent> components;
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i)
    {
        std::int64_t &slot = componentOfRoot[sets.find(canonical[mesh.triangles[i][0]])];
        if (slot < 0)
        {
            slot = std::int64_t(components.size());
            components.emplace_back();
        }
        MeshComponent &c = components[std::size_t(slot)];
        c.triangles.push_back(i);
        for (int k = 0; k < 3; ++k)
            c.bounds.extend(mesh.corner(i, k));
    }
    // Closed components that split into closed shells become those shells, each a solid.
    std::vector<MeshComponent> split;
    std::vector<FaceList> splitFaces;
    for (MeshComponent &component : components)
    {
        FaceList faces = distinctFaces(mesh, canonical, component.triangles);
        std::vector<FaceList> shells;
        component.closed = closedShells(faces, shells);
        if (!component.closed)
        {
            // Solids that share a face (two boxes side by side, each closed) hold it twice, once in
            // each orientation. Taken as one double-sided face (as OMPL.app's meshes store every
            // face twice), it leaves the component open. Counted twice, as the two solids' own, it
            // cancels in parity: the faces without their reverse then bound the union of the
            // solids. So when those close, they are the component's solid; the paired faces are
            // surfaces within it (an open double-sided sheet has no unpaired face at all).
            FaceList unpaired = unpairedFaces(mesh, canonical, component.triangles);
            if (unpaired.size() < faces.size() && everyEdgeEven(unpaired))
            {
                faces = std::move(unpaired);
                component.closed = true;  // one solid, by parity over the unpaired faces
            }
        }
        if (shells.size() <= 1)
        {
            splitFaces.push_back(component.closed ? std::move(faces) : FaceList());
            split.push_back(std::move(component));
            continue;
        }
        // Each triangle goes to the shell of its face (a repeated face to the shell of the one kept).
        std::vector<std::pair<Triangle, std::uint32_t>> shellOfFace;
        for (std::uint32_t s = 0; s < shells.size(); ++s)
            for (const auto &f : shells[s])
                shellOfFace.emplace_back(f.first, s);
        std::sort(shellOfFace.begin(), shellOfFace.end());
        std::vector<MeshComponent> parts(shells.size());
        for (std::uint32_t t : component.triangles)
        {
            const Triangle key = faceKey(mesh.triangles[t], canonical);
            const auto it = std::lower_bound(shellOfFace.begin(), shellOfFace.end(), std::make_pair(key, 0u));
            MeshComponent &part = parts[it->second];
            part.triangles.push_back(t);
            for (int k = 0; k < 3; ++k)
                part.bounds.extend(mesh.corner(t, k));
        }
        for (std::size_t s = 0; s < shells.size(); ++s)
        {
            parts[s].closed = true;
            split.push_back(std::move(parts[s]));
            splitFaces.push_back(std::move(shells[s]));
        }
    }
    // Ordered by their smallest triangle index, as meshComponents() promises.
    std::vector<std::size_t> order(split.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return split[a].triangles.front() < split[b].triangles.front(); });
    components.clear();
    if (closedFaces)
        closedFaces->clear();
    for (std::size_t k : order)
    {
        components.push_back(std::move(split[k]));
        if (closedFaces)
            closedFaces->push_back(std::move(splitFaces[k]));
    }
    return components;
}
}  // namespace

std::vector<MeshComponent> meshComponents(const TriangleMesh &mesh)
{
    return componentsOf(mesh, canonicalVertices(mesh), nullptr);
}

struct SolidQuery::Index
{
    std::vector<MeshComponent> components;
    std::vector<Solid> solids;
    std::vector<std::int64_t> solidOfComponent;  // -1 for open components

    // A uniform 3D grid over the solids' joint bounds lists the solids whose bounds meet each cell.
    BoundingBox bounds;
    GridAxis x, y, z;
    std::vector<std::uint32_t> cellStart;
    std::vector<std::uint32_t> cellSolids;

    std::size_t cellIndex(int i, int j, int k) const
    {
        return (std::size_t(i) * std::size_t(y.cells) + std::size_t(j)) * std::size_t(z.cells) + std::size_t(k);
    }

    template <typename F>
    void forEachCell(F &&visit) const
    {
        for (std::uint32_t s = 0; s < solids.size(); ++s)
        {
            const BoundingBox &box = solids[s].bounds;
            for (int i = x.cell(box.min.x()); i <= x.cell(box.max.x()); ++i)
                for (int j = y.cell(box.min.y()); j <= y.cell(box.max.y()); ++j)
                    for (int k = z.cell(box.min.z()); k <= z.cell(box.max.z()); ++k)
                        visit(cellIndex(i, j, k), s);
        }
    }

    void buildSolidGrid()
    {
        for (const Solid &s : solids)
        {
            bounds.extend(s.bounds.min);
            bounds.extend(s.bounds.max);
        }
        if (solids.empty())
            return;
        const Vec3 extent = bounds.max - bounds.min;
        const auto shape = gridShape<3>({extent.x(), extent.y(), extent.z()}, 4.0 * double(solids.size()), 64);
        x = GridAxis(bounds.min.x(), bounds.max.x(), shape[0]);
        y = GridAxis(bounds.min.y(), bounds.max.y(), shape[1]);
        z = GridAxis(bounds.min.z(), bounds.max.z(), shape[2]);
        std::vector<std::uint32_t> count(std::size_t(x.cells) * std::size_t(y.cells) * std::size_t(z.cells) + 1, 0);
        forEachCell([&](std::size_t cell, std::uint32_t) { ++count[cell + 1]; });
        std::partial_sum(count.begin(), count.end(), count.begin());
        cellStart = count;
        cellSolids.resize(cellStart.back());
        forEachCell([&](std::size_t cell, std::uint32_t s) { cellSolids[count[cell]++] = s; });  // ascending s
    }
};

SolidQuery::SolidQuery(std::shared_ptr<const TriangleMesh> mesh) : mesh_(std::move(mesh))
{
    if (!mesh_)
        throw std::invalid_argument("SolidQuery: null mesh");
    auto index = std::make_shared<Index>();
    // The canonical vertices and each closed component's distinct faces are found once, for both
    // the components and their solids.
    std::vector<FaceList> closedFaces;
    index->components = componentsOf(*mesh_, canonicalVertices(*mesh_), &closedFaces);
    index->solidOfComponent.assign(index->components.size(), -1);
    for (std::uint32_t c = 0; c < index->components.size(); ++c)
    {
        const MeshComponent &component = index->components[c];
        if (!component.closed)
            continue;
        index->solidOfComponent[c] = std::int64_t(index->solids.size());
        index->solids.emplace_back(*mesh_, c, component, closedFaces[c]);
        FaceList().swap(closedFaces[c]);  // the solid keeps its own copy of what it needs
    }
    index->buildSolidGrid();
    index_ = std::move(index);
}

std::size_t SolidQuery::closedComponentCount() const { return index_->solids.size(); }

const std::vector<MeshComponent> &SolidQuery::components() const { return index_->components; }

int SolidQuery::solidContaining(const Vec3 &p) const
{
    const Index &index = *index_;
    if (index.solids.empty() || !contains(index.bounds, p))
        return -1;
    const std::size_t cell = index.cellIndex(index.x.cell(p.x()), index.y.cell(p.y()), index.z.cell(p.z()));
    for (std::uint32_t k = index.cellStart[cell]; k < index.cellStart[cell + 1]; ++k)
    {
        const Solid &solid = index.solids[index.cellSolids[k]];
        if (solid.contains(p))
            return int(solid.component);
    }
    return -1;
}

bool SolidQuery::withinSolidBounds(const Vec3 &p) const
{
    const Index &index = *index_;
    if (index.solids.empty() || !contains(index.bounds, p))
        return false;
    const std::size_t cell = index.cellIndex(index.x.cell(p.x()), index.y.cell(p.y()), index.z.cell(p.z()));
    for (std::uint32_t k = index.cellStart[cell]; k < index.cellStart[cell + 1]; ++k)
        if (contains(index.solids[index.cellSolids[k]].bounds, p))
            return true;
    return false;
}

bool SolidQuery::insideComponent(std::size_t component, const Vec3 &p) const
{
    const std::int64_t solid = index_->solidOfComponent.at(component);
    return solid >= 0 && index_->solids[std::size_t(solid)].contains(p);
}

double SolidQuery::solidVolumeFraction(std::size_t samples, std::uint64_t seed) const
{
    const BoundingBox box = mesh_->bounds();
    if (samples == 0 || box.empty())
        return 0.0;
    std::mt19937_64 rng(seed);
    // 53 random bits per coordinate, so the points are the same with every standard library.
    const auto unit = [&rng] { return double(rng() >> 11) * 0x1.0p-53; };
    std::size_t inside = 0;
    for (std::size_t i = 0; i < samples; ++i)
    {
        const double u = unit(), v = unit(), w = unit();
        const Vec3 p(box.min.x() + u * (box.max.x() - box.min.x()), box.min.y() + v * (box.max.y() - box.min.y()),
                     box.min.z() + w * (box.max.z() - box.min.z()));
        inside += insideAnySolid(p) ? 1 : 0;
    }
    return double(inside) / double(samples);
}
std::vector<Vec3> firstVertexOfEachComponent(const SolidQuery &solids)
{
    std::vector<Vec3> out;
    for (const MeshComponent &c : solids.components())
        if (!c.triangles.empty())
            out.push_back(solids.mesh().corner(c.triangles.front(), 0));
    return out;
}

std::vector<std::vector<Vec3>> verticesSpreadOverEachComponent(const SolidQuery &solids, std::size_t perComponent)
{
    std::vector<std::vector<Vec3>> out;
    for (const MeshComponent &c : solids.components())
    {
        if (c.triangles.empty())
            continue;
        std::vector<Vec3> probes;
        const std::size_t count = c.triangles.size(), step = std::max<std::size_t>(1, count / perComponent);
        for (std::size_t i = 0; i < count && probes.size() < perComponent; i += step)
            probes.push_back(solids.mesh().corner(c.triangles[i], 0));
        out.push_back(std::move(probes));
    }
    return out;
}
}  // namespace hcd
