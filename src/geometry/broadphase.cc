// SPDX-License-Identifier: Apache-2.0
// Incremental sweep and prune: insertion sort of three endpoint lists with pair events.
#include "mrh/geometry/broadphase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/assert.h"

namespace mrh::geometry {
namespace {

// Where a box with a NaN bound goes: a point at the far corner of double range, which overlaps
// no real box, so one blown-up body neither poisons the sort nor becomes everyone's neighbor.
constexpr double kParked = std::numeric_limits<double>::max();

bool HasNaN(const Aabb& box) {
  return box.min.array().isNaN().any() || box.max.array().isNaN().any();
}

Aabb Sanitized(const Aabb& box) {
  if (!HasNaN(box)) return box;
  return Aabb{Vec3::Constant(kParked), Vec3::Constant(kParked)};
}

// Endpoint order: by value, and at equal values a min before a max, so that boxes that only
// touch count as overlapping, as Aabb::Overlaps (closed intervals) says.
template <typename E>
bool Before(const E& a, const E& b) {
  return a.value < b.value || (a.value == b.value && !a.is_max && b.is_max);
}

}  // namespace

int SweepAndPrune::Add(const Aabb& box) {
  const int handle = size();
  const bool is_unbounded = !HasNaN(box) && !box.bounded();
  boxes_.push_back(Sanitized(box));
  unbounded_.push_back(is_unbounded);
  if (is_unbounded) unbounded_handles_.push_back(handle);
  slots_.push_back({});
  overlaps_.emplace_back();
  needs_rebuild_ = true;
  return handle;
}

void SweepAndPrune::SetBox(int handle, const Aabb& box) noexcept {
  MRH_ASSERT(handle >= 0 && handle < size());
  const auto h = static_cast<std::size_t>(handle);
  if (unbounded_[h]) return;
  boxes_[h] = Sanitized(box);
  if (needs_rebuild_) return;
  // Only the values change here; Update() moves the endpoints to their new places.
  for (int axis = 0; axis < 3; ++axis) {
    auto& list = axes_[axis];
    list[static_cast<std::size_t>(slots_[h][static_cast<std::size_t>(2 * axis)])].value =
        boxes_[h].min[axis];
    list[static_cast<std::size_t>(slots_[h][static_cast<std::size_t>(2 * axis + 1)])].value =
        boxes_[h].max[axis];
  }
}

std::int64_t SweepAndPrune::Update() {
  if (needs_rebuild_) {
    Rebuild();
    return 0;
  }
  std::int64_t swaps = 0;
  for (int axis = 0; axis < 3; ++axis) swaps += SortAxis(axis);
  return swaps;
}

// Insertion sort from the previous order. Each swap exchanges two adjacent endpoints whose order
// was wrong, and each pair of endpoints is swapped at most once, so a min moving left past a max
// means that pair's intervals now overlap on this axis (the pair overlaps if the other two axes
// agree, checked on the new boxes), and a max moving left past a min means they no longer do.
// A pair whose overlap changed has such an event on at least one axis, so the pair set ends
// exact whatever the order in which the axes are processed.
std::int64_t SweepAndPrune::SortAxis(int axis) {
  std::vector<Endpoint>& list = axes_[axis];
  std::int64_t swaps = 0;
  const auto slot = [axis](const Endpoint& e) {
    return static_cast<std::size_t>(2 * axis + (e.is_max ? 1 : 0));
  };
  for (std::size_t i = 1; i < list.size(); ++i) {
    const Endpoint e = list[i];
    std::size_t j = i;
    while (j > 0 && Before(e, list[j - 1])) {
      const Endpoint& f = list[j - 1];
      if (e.is_max != f.is_max) {
        MRH_ASSERT(e.handle != f.handle);
        if (e.is_max) {
          RemovePair(e.handle, f.handle);
        } else if (boxes_[static_cast<std::size_t>(e.handle)].Overlaps(
                       boxes_[static_cast<std::size_t>(f.handle)]) &&
                   !HasPair(e.handle, f.handle)) {
          AddPair(e.handle, f.handle);
        }
      }
      list[j] = f;
      slots_[static_cast<std::size_t>(f.handle)][slot(f)] = static_cast<int>(j);
      --j;
      ++swaps;
    }
    list[j] = e;
    slots_[static_cast<std::size_t>(e.handle)][slot(e)] = static_cast<int>(j);
  }
  return swaps;
}

// From scratch: sort the three lists, then one sweep along x with an active set finds every pair.
void SweepAndPrune::Rebuild() {
  for (auto& list : overlaps_) list.clear();
  num_pairs_ = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<Endpoint>& list = axes_[axis];
    list.clear();
    for (int h = 0; h < size(); ++h) {
      if (unbounded(h)) continue;
      list.push_back(Endpoint{box(h).min[axis], h, false});
      list.push_back(Endpoint{box(h).max[axis], h, true});
    }
    std::stable_sort(list.begin(), list.end(), Before<Endpoint>);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const auto s = static_cast<std::size_t>(2 * axis + (list[i].is_max ? 1 : 0));
      slots_[static_cast<std::size_t>(list[i].handle)][s] = static_cast<int>(i);
    }
  }
  std::vector<int> active;
  std::vector<int> position(boxes_.size(), -1);
  for (const Endpoint& e : axes_[0]) {
    if (!e.is_max) {
      for (const int other : active) {
        if (box(e.handle).Overlaps(box(other))) AddPair(e.handle, other);
      }
      position[static_cast<std::size_t>(e.handle)] = static_cast<int>(active.size());
      active.push_back(e.handle);
    } else {
      const auto at = static_cast<std::size_t>(position[static_cast<std::size_t>(e.handle)]);
      active[at] = active.back();
      position[static_cast<std::size_t>(active[at])] = static_cast<int>(at);
      active.pop_back();
    }
  }
  needs_rebuild_ = false;
}

void SweepAndPrune::AddPair(int a, int b) {
  overlaps_[static_cast<std::size_t>(a)].push_back(b);
  overlaps_[static_cast<std::size_t>(b)].push_back(a);
  ++num_pairs_;
}

void SweepAndPrune::RemovePair(int a, int b) {
  const auto erase = [this](int from, int value) {
    std::vector<int>& list = overlaps_[static_cast<std::size_t>(from)];
    const auto it = std::find(list.begin(), list.end(), value);
    if (it == list.end()) return false;
    *it = list.back();
    list.pop_back();
    return true;
  };
  if (erase(a, b)) {
    erase(b, a);
    --num_pairs_;
  }
}

bool SweepAndPrune::HasPair(int a, int b) const {
  const std::vector<int>& la = overlaps_[static_cast<std::size_t>(a)];
  const std::vector<int>& lb = overlaps_[static_cast<std::size_t>(b)];
  if (la.size() <= lb.size()) return std::find(la.begin(), la.end(), b) != la.end();
  return std::find(lb.begin(), lb.end(), a) != lb.end();
}

std::span<const int> SweepAndPrune::overlaps(int handle) const {
  return overlaps_[static_cast<std::size_t>(handle)];
}

void SweepAndPrune::QueryOverlapping(std::span<const int> group, std::vector<int>* out) const {
  out->clear();
  const auto in_group = [group](int h) {
    return std::find(group.begin(), group.end(), h) != group.end();
  };
  const bool everything = std::any_of(group.begin(), group.end(), [this](int h) {
    return unbounded(h);
  });
  if (everything) {
    for (int h = 0; h < size(); ++h) {
      if (!in_group(h)) out->push_back(h);
    }
    return;
  }
  for (const int g : group) {
    for (const int h : overlaps(g)) {
      if (!in_group(h)) out->push_back(h);
    }
  }
  for (const int h : unbounded_handles_) {
    if (!in_group(h)) out->push_back(h);
  }
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

}  // namespace mrh::geometry
