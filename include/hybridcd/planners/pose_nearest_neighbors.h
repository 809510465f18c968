// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include "hybridcd/planners/pose_metric.h"
#include "hybridcd/query/traversal_stack.h"

#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace hcd
{

/// OMPL's nearest-neighbour interface over poses of SE(2) or SE(3), answered exactly: a k-d tree
/// over the poses' coordinates (PoseCoordinates) whose boxes bound OMPL's distance from below
/// (PoseMetric::lowerBound), so a search measures with the planner's own distance function only
/// the elements a box cannot rule out. nearest, nearestK and nearestR return what a search of
/// every element returns (NearestNeighborsLinear; ties aside), sorted by distance. Not thread-safe,
/// like OMPL's NearestNeighborsGNATNoThreadSafety, which the single-threaded planners use.
template <typename T>
class PoseNearestNeighbors : public ompl::NearestNeighbors<T>
{
public:
    /// stateOf gives an element's state, which must belong to the space metric was made from.
    using StateOf = std::function<const ompl::base::State *(const T &)>;

    PoseNearestNeighbors(PoseMetric metric, StateOf stateOf) : metric_(metric), stateOf_(std::move(stateOf)) {}

    bool reportsSortedResults() const override { return true; }

    void clear() override
    {
        elements_.clear();
        coordinates_.clear();
        nodes_.clear();
        unbounded_.clear();
        builtSize_ = 0;
    }

    void add(const T &data) override
    {
        const auto index = static_cast<std::uint32_t>(elements_.size());
        elements_.push_back(data);
        coordinates_.push_back(metric_.coordinates(stateOf_(data)));
        if (!boundable(coordinates_.back()))
        {
            unbounded_.push_back(index);
            return;
        }
        const std::size_t bounded = elements_.size() - unbounded_.size();
        // Rebuilt whenever the count doubles, so that a tree grown one pose at a time stays
        // balanced; each rebuild costs O(n log n), all of them together O(n log n).
        if (nodes_.empty() || bounded >= 2 * builtSize_)
            rebuild();
        else
            insert(index);
    }

    /// O(n log n): the tree is rebuilt. RRTConnect and RRT never remove.
    bool remove(const T &data) override
    {
        const auto it = std::find(elements_.begin(), elements_.end(), data);
        if (it == elements_.end())
            return false;
        const auto position = it - elements_.begin();
        elements_.erase(it);
        coordinates_.erase(coordinates_.begin() + position);
        rebuild();
        return true;
    }

    T nearest(const T &data) const override
    {
        if (elements_.empty())
            throw ompl::Exception("No elements found in nearest neighbors data structure");
        OneNeighbour best;
        search(data, 1, std::numeric_limits<double>::infinity(), best);
        // Every distance NaN: the first element, as NearestNeighborsLinear returns.
        return best.empty() ? elements_.front() : elements_[best.front().second];
    }

    void nearestK(const T &data, std::size_t k, std::vector<T> &nbh) const override
    {
        nbh.clear();
        if (k == 0 || elements_.empty())
            return;
        Neighbours best;
        search(data, k, std::numeric_limits<double>::infinity(), best);
        report(best, nbh);
    }

    void nearestR(const T &data, double radius, std::vector<T> &nbh) const override
    {
        nbh.clear();
        if (elements_.empty() || !(radius >= 0.0))
            return;
        Neighbours within;
        search(data, elements_.size(), radius, within);
        report(within, nbh);
    }

    std::size_t size() const override { return elements_.size(); }

    /// The elements in the order they were added.
    void list(std::vector<T> &data) const override { data = elements_; }

private:
    static constexpr std::size_t kLeafCapacity = 16;
    // (distance, element index); kept as a max-heap on distance during a search.
    using Neighbours = std::vector<std::pair<double, std::uint32_t>>;

    // A box over the coordinates of every pose below it: the exact bounds of its poses, so that a
    // box's lower bound holds for each of them.
    struct Node
    {
        std::array<double, 7> low{};
        std::array<double, 7> high{};
        int firstChild = -1;  // the two children are nodes_[firstChild] and nodes_[firstChild + 1]; -1: a leaf
        int splitDimension = 0;
        double splitValue = 0.0;
        std::vector<std::uint32_t> items;           // a leaf's elements
        std::vector<std::array<double, 7>> points;  // their coordinates, side by side for the search
    };

    // Poses the boxes may hold; the others (a value not finite, a quaternion off unit norm, a yaw
    // outside [-pi, pi]) are measured on every search instead.
    static bool boundable(const PoseCoordinates &p) { return p.finite && p.rotationBoundable; }

    double coordinate(std::uint32_t index, int dimension) const { return coordinates_[index].values[dimension]; }

    void enclose(Node &node, std::uint32_t index) const
    {
        for (int d = 0; d < metric_.dimensions(); ++d)
        {
            node.low[d] = std::min(node.low[d], coordinate(index, d));
            node.high[d] = std::max(node.high[d], coordinate(index, d));
        }
    }

    void fitBox(Node &node, const std::uint32_t *first, const std::uint32_t *last) const
    {
        node.low.fill(std::numeric_limits<double>::infinity());
        node.high.fill(-std::numeric_limits<double>::infinity());
        for (const std::uint32_t *it = first; it != last; ++it)
            enclose(node, *it);
    }

    // The dimension of widest weighted spread over the box, or -1 if every pose in it is the same.
    int widestDimension(const Node &node) const
    {
        int widest = -1;
        double spread = 0.0;
        for (int d = 0; d < metric_.dimensions(); ++d)
        {
            const double s = (node.high[d] - node.low[d]) * metric_.spreadWeight(d);
            if (s > spread)
            {
                spread = s;
                widest = d;
            }
        }
        return widest;
    }

    // Fills nodes_[nodeIndex] over the elements [first, last): a leaf, or a split at the median.
    void build(int nodeIndex, std::uint32_t *first, std::uint32_t *last)
    {
        fitBox(nodes_[nodeIndex], first, last);
        const int dimension = widestDimension(nodes_[nodeIndex]);
        if (static_cast<std::size_t>(last - first) <= kLeafCapacity || dimension < 0)
        {
            Node &leaf = nodes_[nodeIndex];
            leaf.items.assign(first, last);
            leaf.points.clear();
            for (const std::uint32_t index : leaf.items)
                leaf.points.push_back(coordinates_[index].values);
            return;
        }
        std::uint32_t *middle = first + (last - first) / 2;
        std::nth_element(first, middle, last, [&](std::uint32_t a, std::uint32_t b) {
            return coordinate(a, dimension) < coordinate(b, dimension);
        });
        const int children = static_cast<int>(nodes_.size());
        nodes_.emplace_back();
        nodes_.emplace_back();
        nodes_[nodeIndex].firstChild = children;
        nodes_[nodeIndex].splitDimension = dimension;
        nodes_[nodeIndex].splitValue = coordinate(*middle, dimension);
        build(children, first, middle);
        build(children + 1, middle, last);
    }

    void rebuild()
    {
        nodes_.clear();
        unbounded_.clear();
        std::vector<std::uint32_t> bounded;
        bounded.reserve(elements_.size());
        for (std::uint32_t i = 0; i < elements_.size(); ++i)
            (boundable(coordinates_[i]) ? bounded : unbounded_).push_back(i);
        builtSize_ = bounded.size();
        if (bounded.empty())
            return;
        nodes_.reserve(4 * bounded.size() / kLeafCapacity + 1);
        nodes_.emplace_back();
        build(0, bounded.data(), bounded.data() + bounded.size());
    }

    // Down to a leaf, widening the boxes passed; a leaf over capacity is split at its median.
    void insert(std::uint32_t index)
    {
        int n = 0;
        while (true)
        {
            enclose(nodes_[n], index);
            if (nodes_[n].firstChild < 0)
                break;
            const Node &node = nodes_[n];
            n = node.firstChild + (coordinate(index, node.splitDimension) < node.splitValue ? 0 : 1);
        }
        nodes_[n].items.push_back(index);
        nodes_[n].points.push_back(coordinates_[index].values);
        // A leaf of identical poses cannot be split: it grows instead.
        if (nodes_[n].items.size() > kLeafCapacity && widestDimension(nodes_[n]) >= 0)
        {
            std::vector<std::uint32_t> items = std::move(nodes_[n].items);
            nodes_[n].items.clear();
            nodes_[n].points.clear();
            build(n, items.data(), items.data() + items.size());
        }
    }

    // Collects into best (a max-heap) the up-to-k elements nearest to data within radius.
    // What a search for one neighbour keeps, held in place: no allocation per search.
    struct OneNeighbour
    {
        std::pair<double, std::uint32_t> entry;
        bool held = false;
        bool empty() const { return !held; }
        std::size_t size() const { return held ? 1 : 0; }
        void clear() { held = false; }
        std::pair<double, std::uint32_t> *begin() { return &entry; }
        std::pair<double, std::uint32_t> *end() { return &entry + size(); }
        const std::pair<double, std::uint32_t> &front() const { return entry; }
        std::pair<double, std::uint32_t> &back() { return entry; }
        void emplace_back(double d, std::uint32_t index)
        {
            entry = {d, index};
            held = true;
        }
    };

    // Best: Neighbours, or OneNeighbour when k is 1.
    template <class Best>
    void search(const T &data, std::size_t k, double radius, Best &best) const
    {
        best.clear();
        const PoseCoordinates query = metric_.coordinates(stateOf_(data));
        const auto byDistance = [](const std::pair<double, std::uint32_t> &a,
                                   const std::pair<double, std::uint32_t> &b) { return a.first < b.first; };
        // The distance an element must not exceed to enter best.
        const auto bar = [&] { return best.size() < k ? radius : std::min(radius, best.front().first); };
        const auto consider = [&](std::uint32_t index) {
            const double d = this->distFun_(data, elements_[index]);
            if (!(d <= radius))
                return;
            if (best.size() < k)
            {
                best.emplace_back(d, index);
                std::push_heap(best.begin(), best.end(), byDistance);
            }
            else if (d < best.front().first)
            {
                std::pop_heap(best.begin(), best.end(), byDistance);
                best.back() = {d, index};
                std::push_heap(best.begin(), best.end(), byDistance);
            }
        };
        for (std::uint32_t index : unbounded_)
            consider(index);
        if (nodes_.empty())
            return;
        // A query the boxes cannot bound is measured against every pose. A yaw outside
        // [-pi, pi] is one: OMPL's wrapped difference may then even be negative.
        if (!boundable(query))
        {
            for (std::uint32_t i = 0; i < elements_.size(); ++i)
                if (boundable(coordinates_[i]))
                    consider(i);
            return;
        }
        // A box's bound, its rotation's part left out while that part could not decide
        // (PoseMetric::lowerBoundBelow); such a bound is completed before a lower bar prunes by it.
        struct Bounded
        {
            double bound;
            int node;
            bool rotationLeftOut;
        };
        const auto boundOf = [&](int n) {
            Bounded b{0.0, n, false};
            b.bound =
                metric_.lowerBoundBelow(query, nodes_[n].low.data(), nodes_[n].high.data(), bar(), b.rotationLeftOut);
            return b;
        };
        const auto beyondBar = [&](Bounded &b) {
            const double limit = bar();
            if (b.bound > limit)
                return true;
            if (b.rotationLeftOut && b.bound + metric_.largestRotationPart() >= limit)
            {
                b.bound = metric_.lowerBound(query, nodes_[b.node].low.data(), nodes_[b.node].high.data(), limit);
                b.rotationLeftOut = false;
                return b.bound > limit;
            }
            return false;
        };
        // Depth first, the nearer child first; a box whose bound exceeds the bar holds nothing
        // that could enter best.
        // Depth first, at most one waiting box per level: the stack's fixed storage holds them all
        // but in a degenerate tree, and a search allocates nothing.
        BasicTraversalStack<Bounded> stack;
        stack.push(boundOf(0));
        while (!stack.empty())
        {
            Bounded top = stack.pop();
            if (beyondBar(top))
                continue;
            const Node &node = nodes_[top.node];
            if (node.firstChild < 0)
            {
                // A pose's own coordinates bound its distance as a box does: measured only if
                // the bound leaves it a chance (the bound costs a fraction of OMPL's distance).
                // Most poses of a leaf are ruled out by their translation alone, without the
                // rotation's part.
                for (std::size_t i = 0; i < node.items.size(); ++i)
                {
                    if (metric_.translationBeyond(query, node.points[i], bar()))
                        continue;
                    double pointBound;
                    metric_.pointLowerBounds(query, &node.points[i], 1, &pointBound);
                    if (!(pointBound > bar()))
                        consider(node.items[i]);
                }
                continue;
            }
            // The first child's poses lie at or below the split value, the second's at or above it
            // (build and insert keep them so): a child whose side of the split is beyond the bar by
            // the query's gap to the split alone is left out without reading its box (at most one
            // is: the query lies on one side).
            const double toSplit = query.values[std::size_t(node.splitDimension)] - node.splitValue;
            const bool firstOut = metric_.coordinateGapBeyond(node.splitDimension, toSplit, bar());
            if (firstOut || metric_.coordinateGapBeyond(node.splitDimension, -toSplit, bar()))
            {
                Bounded only = boundOf(firstOut ? node.firstChild + 1 : node.firstChild);
                if (!beyondBar(only))
                    stack.push(only);
                continue;
            }
            Bounded first = boundOf(node.firstChild);
            Bounded second = boundOf(node.firstChild + 1);
            // The nearer child on top (by translation alone where both bounds left their
            // rotation out); a child already beyond the bar is left out.
            const bool firstNearer = first.bound <= second.bound;
            Bounded &near = firstNearer ? first : second;
            Bounded &far = firstNearer ? second : first;
            if (!beyondBar(far))
                stack.push(far);
            if (!beyondBar(near))
                stack.push(near);
        }
    }

    // best in increasing distance (equal distances in the order the elements were added).
    void report(Neighbours &best, std::vector<T> &nbh) const
    {
        std::sort(best.begin(), best.end());
        nbh.reserve(best.size());
        for (const auto &entry : best)
            nbh.push_back(elements_[entry.second]);
    }

    PoseMetric metric_;
    StateOf stateOf_;
    std::vector<T> elements_;
    std::vector<PoseCoordinates> coordinates_;
    std::vector<Node> nodes_;
    // The elements that are not boundable(): measured on every search.
    std::vector<std::uint32_t> unbounded_;
    // The number of bounded elements at the last rebuild.
    std::size_t builtSize_ = 0;
};

}  // namespace hcd
