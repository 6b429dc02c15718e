#include "common/core/ownership.hpp"

#include <algorithm>

namespace slam {

namespace {

// FNV-1a, then the splitmix64 finaliser: FNV alone mixes the last bytes poorly, and nearby robot
// ids ("r1", "r2") must not give correlated weights.
std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes) {
  for (const char c : bytes) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t rendezvous_weight(std::string_view instance, std::string_view key) {
  std::uint64_t h = fnv1a(0xcbf29ce484222325ULL, instance);
  h = fnv1a(h ^ 0xff, key);  // a separator: ("ab", "c") and ("a", "bc") differ
  return mix(h);
}

Ownership::Ownership(std::string self, std::int64_t started_mono_ns, OwnershipConfig config)
    : self_(std::move(self)), started_mono_ns_(started_mono_ns), config_(config) {}

bool Ownership::heard(std::string_view instance, std::int64_t now_mono_ns) {
  if (instance == self_) return false;
  for (Peer& p : peers_) {
    if (p.id == instance) {
      p.last_heard_mono_ns = std::max(p.last_heard_mono_ns, now_mono_ns);
      return false;
    }
  }
  peers_.push_back({std::string(instance), now_mono_ns});
  ++version_;
  return true;
}

bool Ownership::left(std::string_view instance) {
  const auto it = std::find_if(peers_.begin(), peers_.end(), [&](const Peer& p) { return p.id == instance; });
  if (it == peers_.end()) return false;
  peers_.erase(it);
  ++version_;
  return true;
}

std::size_t Ownership::expire(std::int64_t now_mono_ns, std::vector<std::string>* gone) {
  const auto silent = [&](const Peer& p) {
    return now_mono_ns - p.last_heard_mono_ns > config_.peer_timeout_ns;
  };
  std::size_t count = 0;
  for (const Peer& p : peers_) {
    if (!silent(p)) continue;
    ++count;
    if (gone) gone->push_back(p.id);
  }
  if (count == 0) return 0;
  std::erase_if(peers_, silent);
  ++version_;
  return count;
}

const std::string& Ownership::owner_of(std::string_view key, std::int64_t now_mono_ns) const {
  const std::string* best = &self_;
  std::uint64_t best_weight = rendezvous_weight(self_, key);
  for (const Peer& p : peers_) {
    if (now_mono_ns - p.last_heard_mono_ns > config_.peer_timeout_ns) continue;
    const std::uint64_t w = rendezvous_weight(p.id, key);
    if (w > best_weight || (w == best_weight && p.id > *best)) {
      best = &p.id;
      best_weight = w;
    }
  }
  return *best;
}

bool Ownership::owns(std::string_view key, std::int64_t now_mono_ns) const {
  return warmed_up(now_mono_ns) && &owner_of(key, now_mono_ns) == &self_;
}

std::vector<std::string> Ownership::live() const {
  std::vector<std::string> ids{self_};
  for (const Peer& p : peers_) ids.push_back(p.id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace slam
