#pragma once
/// \file
/// A random-access view of objects held elsewhere, through pointers: what a round hands to the
/// fusion and the stacked update, so that the samples that arrived are used where they lie
/// instead of being copied into a contiguous array every step.

#include <cstddef>
#include <span>

namespace skyfuse {

template <typename T>
class IndirectView {
 public:
  explicit IndirectView(std::span<const T* const> items) : items_(items) {}
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  const T& operator[](std::size_t i) const { return *items_[i]; }

 private:
  std::span<const T* const> items_;
};

/// The same, each object seen through `project` (one part of a larger sample, say): the IMM's
/// peers fuse mode I's increments where they lie inside each station's contribution.
template <typename T, typename Project>
class ProjectedView {
 public:
  ProjectedView(std::span<const T* const> items, Project project)
      : items_(items), project_(project) {}
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  decltype(auto) operator[](std::size_t i) const { return project_(*items_[i]); }

 private:
  std::span<const T* const> items_;
  Project project_;
};

}  // namespace skyfuse
