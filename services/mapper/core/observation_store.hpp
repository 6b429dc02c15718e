#pragma once
// Every observation the mapper has integrated, raw (the robot's odometry frame) with its keyframe id,
// the keyframes with their corrections, the manual obstructions, the grid config and an imported
// prior: everything a restart or a rebuild needs.
// SQLite in WAL mode; appends are batched into explicit transactions (commit every batch_size rows
// or on flush()), because one transaction per message would cap ingest at disk-sync speed.
//
// Rebuild reads rows straight from SQLite (one prepared statement, blobs decoded into reused
// buffers), so RAM stays proportional to the grid, never to the number of stored observations.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/store_baseline.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace slam::mapper {

struct StoreOptions {
  int batch_size = 512;  // appends per transaction
};

// What the store keeps (slamctl store stats).
struct StoreStats {
  int64_t rows = 0;               // raw observations
  int64_t keyframes = 0;          // keyframes with a stored correction
  int64_t raw_keyframes = 0;      // keyframes that still have raw observations
  int64_t compacted_tiles = 0;    // baseline tiles (32 x 32 cells of log-odds)
  int64_t compacted_through = 0;  // the baseline holds every observation up to this row (0: none)
  int64_t bytes = 0;              // pages in use (the file keeps freed pages for reuse)
  int64_t file_bytes = 0;         // the database file (its WAL aside)
  int64_t oldest_stamp_ns = 0;    // the oldest raw observation's gateway stamp (0: none)
  int64_t newest_stamp_ns = 0;
};

// One stored row as iteration presents it; the views are valid during the callback only.
struct ObservationRecord {
  int64_t id = 0;  // insertion order
  std::string_view robot_id;
  uint64_t seq = 0;
  int64_t stamp_ns = 0;        // gateway receive time
  int64_t robot_stamp_ns = 0;  // the robot's own clock; 0: the robot sent none
  KeyframeId keyframe_id = 0;  // 0: none
  ObservationView obs;         // odometry frame
};

class ObservationStore {
 public:
  // Opens or creates the database; a store written by schema 1 gains the keyframe column (0 for its
  // rows) and the keyframes table, one written by schema 1 or 2 the robot_stamp_ns column (0), one
  // written by schema 1 to 3 the index by keyframe (built once, at the first open). Errors
  // name the path: cannot open, not a database (corrupt), written by a newer schema.
  static Result<ObservationStore> open(const std::filesystem::path& path, StoreOptions options = {});

  ObservationStore(ObservationStore&&) noexcept = default;
  // No move assignment: replacing a store with an open batch would drop it silently.
  ObservationStore& operator=(ObservationStore&&) = delete;
  ~ObservationStore();  // commits pending appends

  // `obs` in the robot's odometry frame; keyframe_id 0 when it belongs to none, robot_stamp_ns 0 when
  // the robot sent no stamp.
  Status append(std::string_view robot_id, uint64_t seq, int64_t stamp_ns, KeyframeId keyframe_id,
                const ObservationView& obs, int64_t robot_stamp_ns = 0);
  // Inserts or replaces keyframes (by id) in the open batch, as appends are: upsert a keyframe before
  // appending the observations that reference it and it is committed no later than they are.
  Status save_keyframes(std::span<const Keyframe> keyframes);
  Status flush();  // commits the open batch, if any

  // The row id of the last append (valid right after a successful append()).
  int64_t last_row() const;

  // Every observation in insertion order (pending appends included); the second, those up to row
  // `through_row` only.
  Status for_each(const std::function<void(const ObservationRecord&)>& visit);
  Status for_each(const std::function<void(const ObservationRecord&)>& visit, int64_t through_row);
  // The row ids of `keyframe`'s observations within [first_row, last_row], ascending (an index
  // range: cheap whatever the store's size).
  Status rows_of(KeyframeId keyframe, int64_t first_row, int64_t last_row,
                 const std::function<void(int64_t)>& visit);
  // The observations of `rows` (ascending ids), in that order; ids that do not exist are skipped.
  Status for_each_row(std::span<const int64_t> rows,
                      const std::function<void(const ObservationRecord&)>& visit);
  // Runs `reads` in one read transaction (in the open batch's, if any): many small queries then take
  // the file lock once and keep the page cache, instead of once per query.
  Status read_together(const std::function<Status()>& reads);
  // One robot's observations in insertion order, without their points (obs.hits and obs.misses
  // empty): its poses, cheaply.
  Status for_each_pose(std::string_view robot_id, const std::function<void(const ObservationRecord&)>& visit);
  Result<int64_t> count();
  // Every keyframe, by id.
  Result<std::vector<Keyframe>> keyframes();
  // Deletes one robot's observations and keyframes; returns how many observations.
  Result<int64_t> delete_robot(std::string_view robot_id);

  Status add_obstruction(Vec2 p);
  Status remove_obstruction(Vec2 p);
  Status clear_obstructions();
  Result<std::vector<Vec2>> obstructions();

  Status save_config(const GridConfig& config);
  Result<std::optional<GridConfig>> load_config();  // nullopt when never saved

  Status save_prior(const MapImage& image);
  Status clear_prior();
  Result<std::optional<MapImage>> load_prior();

  // observation_store_compaction.cpp. The compacted baseline (nullopt: never compacted); with
  // `region` (map frame), only its tiles that overlap it.
  Result<std::optional<Baseline>> load_baseline(const MapBox* region = nullptr);
  // Replaces the baseline with `baseline` and deletes the rows up to its through_row, in one
  // transaction (the open batch is committed first). Returns the rows deleted.
  Result<int64_t> compact(const Baseline& baseline);
  Result<StoreStats> stats();
  // Bytes of the pages in use: what --store-max-mb bounds (cheap: two pragmas).
  Result<int64_t> used_bytes();

  const std::filesystem::path& path() const { return path_; }

 private:
  struct DbClose {
    void operator()(sqlite3* db) const;
  };
  struct StmtFinalize {
    void operator()(sqlite3_stmt* s) const;
  };
  using Db = std::unique_ptr<sqlite3, DbClose>;
  using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinalize>;

  ObservationStore() = default;
  Status exec(const char* sql);
  Result<Stmt> prepare(const char* sql);
  Result<int64_t> scalar(const char* sql);  // the first column of the first row (0 when none or NULL)
  Error db_error(std::string_view what) const;
  Status begin_batch();
  // Steps `st` (columns as kRowColumns, then hits and misses when `with_points`) and visits each row.
  Status visit_rows(sqlite3_stmt* st, bool with_points,
                    const std::function<void(const ObservationRecord&)>& visit);

  std::filesystem::path path_;
  StoreOptions options_;
  Db db_;
  Stmt insert_;
  Stmt upsert_keyframe_;
  Stmt rows_of_;  // prepared on first use
  Stmt row_;
  bool in_batch_ = false;
  int pending_ = 0;
  std::vector<Vec2> hits_buf_;
  std::vector<Vec2> misses_buf_;
};

}  // namespace slam::mapper
