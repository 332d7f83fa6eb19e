// groups.hpp - the course's groups, written by the student (stage 04):
// "Divide objects into groups; test group intersection, then object
// intersection."
//
// The items are the scene's primitives in scene order: each sphere, each
// single triangle, each triangle of each mesh (so a mesh of 69451 triangles
// is 69451 items, and a ray tests a few dozen of them instead of all). The
// groups are a binary tree of boxes over the items (a bounding volume
// hierarchy, Fundamentals of Computer Graphics, 4th ed., sec. 12.3.2,
// "Hierarchical Bounding Boxes"):
//  - build_groups (exercise): top down. A node's box encloses its items; a
//    node of more than leaf_size items is split at the median of its items'
//    centroids along the longest axis of the centroids' box (the
//    "equal counts" split of Physically Based Rendering, 3rd ed., sec. 4.3.1),
//    the first half of the items to the left child, the rest to the right.
//  - closest_hit_groups (exercise): a ray tests a node's box (hit_box_robust,
//    slab.hpp) and only then its children; the nearer child first, and a
//    child whose box starts beyond the closest hit so far (by more than the
//    slab test's rounding margin) is skipped (PBR 3rd ed., sec. 4.3.5,
//    front-to-back traversal).
// The result is the list's (closest_hit_list), hit for hit, ties included: at
// an equal t the item later in scene order wins.
//
// The library's fast path is a different structure (bvh.hpp: SAH, 8- or 4-wide
// nodes, packed leaves); this one is for reading. No other header includes
// this one, so editing the exercises rebuilds only stage-04 code.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <variant>
#include <vector>

#include <glm/common.hpp>

#include "../core/aabb.hpp"
#include "../core/hit_record.hpp"
#include "../scene/mesh.hpp"
#include "mesh_hit.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../scene/scene.hpp"
#include "shape_hit.hpp"
#include "slab.hpp"
#include "../core/vec.hpp"
#include "watertight.hpp"

namespace rt {

/// One primitive of a scene: shape `shape`, and for a mesh its triangle
/// `primitive` (0 for a sphere or a single triangle); its box and the centre
/// of that box.
struct group_item {
    std::uint32_t shape = 0;
    std::uint32_t primitive = 0;
    aabb box;
    vec3 centroid{0};
};

/// One node of the groups: the items order[first, first + count) lie under
/// it and box encloses all of them. A leaf has left == right == 0 (the root
/// is node 0, so no node has it as a child); an inner node has two children.
struct group_node {
    aabb box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::uint32_t left = 0;
    std::uint32_t right = 0;

    bool leaf() const { return left == 0 && right == 0; }
};

/// The groups over a list of items.
struct groups {
    std::vector<group_item> items;     ///< scene order (as group_items gives them)
    std::vector<std::uint32_t> order;  ///< item indices, each node's a contiguous run
    std::vector<group_node> nodes;     ///< nodes[0] is the root; none when there are no items
};

/// The scene's primitives as items, in scene order. A triangle's box is
/// exact (the min and max of its corners); a sphere's c -+ R is widened by
/// gamma_4 (|c| + R) per axis, because c -+ R is rounded and the box must not
/// cut the sphere (PBR 3rd ed., sec. 3.9.1, bounding rounded sums).
inline std::vector<group_item> group_items(const scene& s)
{
    std::vector<group_item> items;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const shape& item = s.shapes[i];
        group_item g;
        g.shape = std::uint32_t(i);
        if (const sphere* ball = std::get_if<sphere>(&item)) {
            const vec3 margin = gamma_n(4) * (glm::abs(ball->center) + vec3(ball->radius));
            g.box.lo = ball->center - vec3(ball->radius) - margin;
            g.box.hi = ball->center + vec3(ball->radius) + margin;
            g.centroid = g.box.center();
            items.push_back(g);
        } else if (const triangle* tri = std::get_if<triangle>(&item)) {
            g.box = bounds(*tri);
            g.centroid = g.box.center();
            items.push_back(g);
        } else {
            const mesh& m = std::get<mesh>(item);
            for (std::size_t k = 0; k < m.triangles.size(); ++k) {
                g.primitive = std::uint32_t(k);
                g.box = aabb{};
                for (std::uint32_t corner : m.triangles[k])
                    g.box.grow(m.positions[corner]);
                g.centroid = g.box.center();
                items.push_back(g);
            }
        }
    }
    return items;
}

/// The closest hit of one item in [tmin, tmax] by the library's robust
/// methods (rt::hit_sphere, the watertight triangle test), the record
/// complete: rec.shape and rec.primitive are the item's.
inline bool hit_group_item(const scene& s, const group_item& item, const ray& r, real tmin, real tmax,
                           hit_record& rec)
{
    const shape& target = s.shapes[item.shape];
    bool found = false;
    if (const mesh* m = std::get_if<mesh>(&target))
        found = detail::hit_mesh_triangle(*m, item.primitive, r, tmin, tmax, rec);
    else
        found = hit_shape(target, r, tmin, tmax, rec);
    if (found) {
        rec.shape = item.shape;
        rec.primitive = item.primitive;
    }
    return found;
}

/// Builds the groups over `items` (exercise): g.items = items, g.order a
/// permutation of 0 .. n-1, g.nodes[0] the root over all of them. A node of
/// at most leaf_size items is a leaf; a larger one is split at the median:
/// along the axis where its items' centroids spread the most, its count / 2
/// items of smallest centroid go to the left child, the others to the right.
/// Every box is the union of its items' boxes. No items: no nodes.
/// leaf_size must be at least 1.
inline groups build_groups(std::vector<group_item> items, std::size_t leaf_size = 4)
{
    // RT_EXERCISE_BEGIN(stage04: build the groups)
    // Hint: keep a stack of nodes still to split; a node holds its run
    //   order[first, first + count). std::nth_element puts the median in place.
    groups g;
    g.items = std::move(items);
    g.order.resize(g.items.size());
    for (std::size_t i = 0; i < g.order.size(); ++i)
        g.order[i] = std::uint32_t(i);
    if (g.items.empty())
        return g;
    if (leaf_size < 1)
        leaf_size = 1;
    g.nodes.push_back(group_node{aabb{}, 0, std::uint32_t(g.items.size()), 0, 0});
    std::vector<std::uint32_t> to_do{0};
    while (!to_do.empty()) {
        const std::uint32_t index = to_do.back();
        to_do.pop_back();
        const std::uint32_t first = g.nodes[index].first, count = g.nodes[index].count;
        aabb box, centroids;
        for (std::uint32_t k = first; k < first + count; ++k) {
            box.grow(g.items[g.order[k]].box);
            centroids.grow(g.items[g.order[k]].centroid);
        }
        g.nodes[index].box = box;
        if (count <= leaf_size)
            continue;
        const vec3 spread = centroids.extent();
        const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
        const std::uint32_t half = count / 2;
        std::nth_element(g.order.begin() + first, g.order.begin() + first + half, g.order.begin() + first + count,
                         [&](std::uint32_t a, std::uint32_t b) {
                             return g.items[a].centroid[axis] < g.items[b].centroid[axis];
                         });
        const auto left = std::uint32_t(g.nodes.size());
        g.nodes.push_back(group_node{aabb{}, first, half, 0, 0});
        g.nodes.push_back(group_node{aabb{}, first + half, count - half, 0, 0});
        g.nodes[index].left = left;
        g.nodes[index].right = left + 1;
        to_do.push_back(left);
        to_do.push_back(left + 1);
    }
    return g;
    // RT_EXERCISE_END
}

/// The closest hit of the ray in [tmin, tmax] over the items of `g`
/// (exercise), as closest_hit_list gives it over the scene: the smallest t,
/// and at an equal t the item later in scene order (the larger index into
/// g.items). hit_item(i, r, tmin, tmax, rec) tests item i and fills the
/// record (hit_group_item with the scene, say). A node's box is tested with
/// hit_box_robust before anything under it; the nearer child is visited
/// first, and a child whose box starts beyond the closest hit so far is not
/// visited at all: beyond by more than rounding, t_enter > closest *
/// slab_robust_far_factor. (A box's entry and a hit's t are computed by
/// different formulas, each rounded: where the box's face holds the hit,
/// equal in exact arithmetic, the entry can come out a little above the hit,
/// and `t_enter > closest` would skip the box that holds the later item of a
/// tie.) On a miss the record is left untouched.
template <class HitItem>
bool closest_hit_groups(const groups& g, const ray& r, real tmin, real tmax, hit_record& rec, HitItem&& hit_item)
{
    // RT_EXERCISE_BEGIN(stage04: closest hit over the groups)
    // Hint: a stack of (node, where the ray enters its box); pop, skip it when
    //   that t is beyond the closest hit so far by more than rounding,
    //   `t_enter > closest * slab_robust_far_factor`; push the farther child first.
    if (g.nodes.empty())
        return false;
    real t_root = 0;
    if (!hit_box_robust(g.nodes[0].box, r, tmin, tmax, t_root))
        return false;
    bool found = false;
    std::uint32_t best_item = 0;
    real closest = tmax;
    std::vector<std::pair<std::uint32_t, real>> to_visit{{0, t_root}};
    while (!to_visit.empty()) {
        const auto [index, t_enter] = to_visit.back();
        to_visit.pop_back();
        if (t_enter > closest * slab_robust_far_factor)
            continue; // a nearer hit was found after this node was pushed (the factor: as in the slab test)
        const group_node& node = g.nodes[index];
        if (node.leaf()) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                const std::uint32_t item = g.order[k];
                hit_record candidate;
                if (!hit_item(item, r, tmin, closest, candidate))
                    continue;
                if (!found || candidate.t < closest || item > best_item) { // a tie: the later item
                    found = true;
                    best_item = item;
                    closest = candidate.t;
                    rec = candidate;
                }
            }
            continue;
        }
        real t_left = 0, t_right = 0;
        const bool left = hit_box_robust(g.nodes[node.left].box, r, tmin, closest, t_left);
        const bool right = hit_box_robust(g.nodes[node.right].box, r, tmin, closest, t_right);
        if (left && right) {
            if (t_left <= t_right) { // the nearer one on top of the stack
                to_visit.push_back({node.right, t_right});
                to_visit.push_back({node.left, t_left});
            } else {
                to_visit.push_back({node.left, t_left});
                to_visit.push_back({node.right, t_right});
            }
        } else if (left) {
            to_visit.push_back({node.left, t_left});
        } else if (right) {
            to_visit.push_back({node.right, t_right});
        }
    }
    return found;
    // RT_EXERCISE_END
}

} // namespace rt
