#pragma once
// A nearest-neighbour structure for OMPL planners in the plane: items are kept in square buckets over
// the planning area and searched ring by ring outward. In 2-D this answers the planners' k-nearest
// queries several times faster than OMPL's default GNAT, which spends most of its time computing
// distances through the state space's virtual interface (docs/performance.md, planner).
#include <ompl/datastructures/NearestNeighbors.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::planner {

template <class T>
class BucketNearestNeighbors : public ompl::NearestNeighbors<T> {
 public:
  using Position = std::function<Vec2(const T&)>;

  // Buckets of `bucket_side` metres over [origin, origin + extent]; items outside are clamped into
  // the edge buckets. `position` gives an item's coordinates (the planner's Euclidean metric).
  BucketNearestNeighbors(Vec2 origin, Vec2 extent, double bucket_side, Position position)
      : origin_(origin),
        side_(bucket_side),
        columns_(std::max(1, static_cast<int>(std::ceil(extent.x / bucket_side)))),
        rows_(std::max(1, static_cast<int>(std::ceil(extent.y / bucket_side)))),
        buckets_(static_cast<size_t>(columns_) * static_cast<size_t>(rows_)),
        position_(std::move(position)) {}

  bool reportsSortedResults() const override { return true; }
  void clear() override {
    for (auto& b : buckets_) b.clear();
    size_ = 0;
  }
  void add(const T& data) override {
    buckets_[bucket_of(position_(data))].push_back(Entry{position_(data), data});
    ++size_;
  }
  bool remove(const T& data) override {
    auto& bucket = buckets_[bucket_of(position_(data))];
    const auto it =
        std::find_if(bucket.begin(), bucket.end(), [&](const Entry& e) { return e.data == data; });
    if (it == bucket.end()) return false;
    bucket.erase(it);
    --size_;
    return true;
  }
  T nearest(const T& data) const override {
    std::vector<T> one;
    nearestK(data, 1, one);
    return one.empty() ? T{} : one.front();
  }
  // The k nearest items, nearest first (the item itself included when stored, as OMPL's do).
  void nearestK(const T& data, std::size_t k, std::vector<T>& nbh) const override {
    nbh.clear();
    if (k == 0 || size_ == 0) return;
    const Vec2 p = position_(data);
    const auto [cx, cy] = cell_of(p);
    found_.clear();
    const int max_ring = std::max(columns_, rows_);
    double kth = 0.0;  // squared distance of the k-th nearest found so far, once k are found
    for (int ring = 0; ring <= max_ring; ++ring) {
      // Items in rings from `ring` on are at least this far (the query's distance to its bucket's
      // edge, plus the rings in between).
      if (found_.size() >= k && ring > 0) {
        const double reach = (ring - 1) * side_ + edge_distance(p, cx, cy);
        if (reach * reach > kth) break;
      }
      const size_t before = found_.size();
      visit_ring(cx, cy, ring,
                 [&](const Entry& e) { found_.emplace_back(distance2(p, e.position), e.data); });
      if (found_.size() >= k && found_.size() != before) {
        std::nth_element(found_.begin(), found_.begin() + static_cast<std::ptrdiff_t>(k - 1), found_.end(),
                         by_distance);
        found_.resize(k);
        kth = found_[k - 1].first;
      }
    }
    std::sort(found_.begin(), found_.end(), by_distance);
    for (const auto& f : found_) nbh.push_back(f.second);
  }
  // Items within `radius`, nearest first.
  void nearestR(const T& data, double radius, std::vector<T>& nbh) const override {
    nbh.clear();
    const Vec2 p = position_(data);
    const auto [cx, cy] = cell_of(p);
    const int rings = static_cast<int>(std::ceil(radius / side_));
    found_.clear();
    for (int ring = 0; ring <= rings; ++ring) {
      visit_ring(cx, cy, ring, [&](const Entry& e) {
        const double d2 = distance2(p, e.position);
        if (d2 <= radius * radius) found_.emplace_back(d2, e.data);
      });
    }
    std::sort(found_.begin(), found_.end(), by_distance);
    for (const auto& f : found_) nbh.push_back(f.second);
  }
  std::size_t size() const override { return size_; }
  void list(std::vector<T>& data) const override {
    data.clear();
    for (const auto& b : buckets_)
      for (const Entry& e : b) data.push_back(e.data);
  }

 private:
  struct Entry {
    Vec2 position;
    T data;
  };
  static bool by_distance(const std::pair<double, T>& a, const std::pair<double, T>& b) {
    return a.first < b.first;
  }
  static double distance2(Vec2 a, Vec2 b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }

  std::pair<int, int> cell_of(Vec2 p) const {
    const int x = static_cast<int>(std::floor((p.x - origin_.x) / side_));
    const int y = static_cast<int>(std::floor((p.y - origin_.y) / side_));
    return {std::clamp(x, 0, columns_ - 1), std::clamp(y, 0, rows_ - 1)};
  }
  size_t bucket_of(Vec2 p) const {
    const auto [x, y] = cell_of(p);
    return static_cast<size_t>(y) * static_cast<size_t>(columns_) + static_cast<size_t>(x);
  }
  // Distance from p to the nearest edge of its bucket (cx, cy): how far ring 1 is at least.
  double edge_distance(Vec2 p, int cx, int cy) const {
    const double x0 = origin_.x + cx * side_;
    const double y0 = origin_.y + cy * side_;
    const double d = std::min({p.x - x0, x0 + side_ - p.x, p.y - y0, y0 + side_ - p.y});
    return std::max(0.0, d);
  }
  template <class Visit>
  void visit_ring(int cx, int cy, int ring, Visit&& visit) const {
    const auto bucket = [&](int x, int y) {
      if (x < 0 || y < 0 || x >= columns_ || y >= rows_) return;
      for (const Entry& e :
           buckets_[static_cast<size_t>(y) * static_cast<size_t>(columns_) + static_cast<size_t>(x)])
        visit(e);
    };
    if (ring == 0) {
      bucket(cx, cy);
      return;
    }
    for (int x = cx - ring; x <= cx + ring; ++x) {
      bucket(x, cy - ring);
      bucket(x, cy + ring);
    }
    for (int y = cy - ring + 1; y <= cy + ring - 1; ++y) {
      bucket(cx - ring, y);
      bucket(cx + ring, y);
    }
  }

  Vec2 origin_;
  double side_;
  int columns_;
  int rows_;
  std::vector<std::vector<Entry>> buckets_;
  Position position_;
  std::size_t size_ = 0;
  mutable std::vector<std::pair<double, T>> found_;  // query scratch (planners query from one thread)
};

}  // namespace slam::planner
