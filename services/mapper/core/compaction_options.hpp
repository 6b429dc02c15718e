#pragma once
// How the observation store stays bounded (compaction.hpp): --store-retention-days, --store-max-mb,
// --store-min-age-s, --store-compact-interval-s.
#include "common/core/result.hpp"

namespace slam::mapper {

struct CompactionOptions {
  double retention_days = 7.0;  // raw observations are kept this long (0: no compaction by age)
  double max_mb = 1024.0;       // store pages in use above this: compact down to min_age_s (0: no bound)
  double min_age_s = 3600.0;    // a keyframe first seen or moved more recently is never compacted
  double interval_s = 60.0;     // how often the mapper looks (a cheap check on the loop)
};

// Ok, or the bad key with the reason.
Status validate(const CompactionOptions& options);

}  // namespace slam::mapper
