#pragma once
// Which running instance of a service owns a key (a robot id), decided alike by every instance
// without talking: each keeps the live set of its peers from their heartbeats and picks the owner by
// rendezvous (highest-random-weight) hashing of the key over that set. When a peer dies, only its
// keys move (spread over the others); when one joins, it takes about 1/N of the keys from the
// others and nothing else moves. Plain and single-threaded: the caller locks; times are monotonic ns.
//
// The moment of change. Views differ for up to a heartbeat period (a peer hears a newcomer at its
// first heartbeat, the newcomer hears each peer at theirs), so the rules prefer a short gap to two
// owners at once:
//  - a key that leaves me (a peer joined) is dropped at once, when I hear the peer;
//  - a newcomer owns nothing for a warm-up (longer than a heartbeat period plus discovery), so by
//    the time it claims its share every peer has heard it and dropped that share;
//  - keys of a peer that went silent for peer_timeout move at once: a dead peer sends nothing. A peer
//    that was only slow (a stalled heartbeat thread) and comes back is a short window of two owners:
//    peer_timeout must stay several heartbeat periods long.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace slam {

// The weight of `instance` for `key`: a fixed 64-bit hash (the same on every host and build).
std::uint64_t rendezvous_weight(std::string_view instance, std::string_view key);

struct OwnershipConfig {
  std::int64_t peer_timeout_ns = 1'500'000'000;  // a peer unheard this long is gone
  std::int64_t warmup_ns = 2'000'000'000;        // after start, own nothing this long
};

class Ownership {
 public:
  // `self`: this instance's id (as in its heartbeats); `started_mono_ns`: when the warm-up began.
  Ownership(std::string self, std::int64_t started_mono_ns, OwnershipConfig config = {});

  // A heartbeat of a running peer (the own instance is ignored). True when the peer is new.
  bool heard(std::string_view instance, std::int64_t now_mono_ns);
  // A peer that said it is stopping leaves at once. True when it was live.
  bool left(std::string_view instance);
  // A peer's heartbeat: one saying it is stopping leaves, any other is heard.
  void observe(std::string_view instance, bool stopping, std::int64_t now_mono_ns) {
    if (stopping) {
      left(instance);
    } else {
      heard(instance, now_mono_ns);
    }
  }
  // Forgets peers silent for longer than peer_timeout; their ids go to `gone` (when given).
  // Returns how many left.
  std::size_t expire(std::int64_t now_mono_ns, std::vector<std::string>* gone = nullptr);

  // The owner of `key` among self and the peers heard within peer_timeout at `now_mono_ns` (one
  // past its timeout counts as gone even before expire() drops it); ties go to the greater id.
  const std::string& owner_of(std::string_view key, std::int64_t now_mono_ns) const;
  // True when this instance is warmed up and the owner of `key`.
  bool owns(std::string_view key, std::int64_t now_mono_ns) const;
  bool warmed_up(std::int64_t now_mono_ns) const {
    return now_mono_ns - started_mono_ns_ >= config_.warmup_ns;
  }

  const std::string& self() const { return self_; }
  // Live instances, self included, sorted.
  std::vector<std::string> live() const;
  std::size_t live_count() const { return peers_.size() + 1; }
  // Bumped whenever the live set changes.
  std::uint64_t version() const { return version_; }

 private:
  struct Peer {
    std::string id;
    std::int64_t last_heard_mono_ns = 0;
  };

  std::string self_;
  std::int64_t started_mono_ns_;
  OwnershipConfig config_;
  std::vector<Peer> peers_;  // a handful: linear search beats a map
  std::uint64_t version_ = 0;
};

}  // namespace slam
