// ObservationStore: the compacted baseline (load, replace with the rows it holds deleted) and what the
// store keeps (see observation_store.hpp, store_baseline.hpp).
#include <sqlite3.h>

#include <cmath>
#include <cstring>

#include "mapper/core/observation_store.hpp"

namespace slam::mapper {
namespace {

constexpr size_t kTileBytes = sizeof(int16_t) * BaselineTile::kSide * BaselineTile::kSide;

}  // namespace

Result<int64_t> ObservationStore::scalar(const char* sql) {
  auto q = prepare(sql);
  if (!q) return q.error();
  const int rc = sqlite3_step(q->get());
  if (rc == SQLITE_DONE) return int64_t{0};
  if (rc != SQLITE_ROW) return db_error(sql);
  return static_cast<int64_t>(sqlite3_column_int64(q->get(), 0));
}

Result<std::optional<Baseline>> ObservationStore::load_baseline(const MapBox* region) {
  auto meta = prepare(
      "SELECT resolution, origin_x, origin_y, width, height, through_row, prior_pending FROM baseline "
      "WHERE id = 1");
  if (!meta) return meta.error();
  sqlite3_stmt* m = meta->get();
  const int rc = sqlite3_step(m);
  if (rc == SQLITE_DONE) return std::optional<Baseline>{};
  if (rc != SQLITE_ROW) return db_error("reading the baseline");
  Baseline b;
  b.geometry.resolution = sqlite3_column_double(m, 0);
  b.geometry.origin = {sqlite3_column_double(m, 1), sqlite3_column_double(m, 2)};
  b.geometry.width = static_cast<int32_t>(sqlite3_column_int64(m, 3));
  b.geometry.height = static_cast<int32_t>(sqlite3_column_int64(m, 4));
  b.through_row = sqlite3_column_int64(m, 5);
  b.prior_pending = sqlite3_column_int64(m, 6) != 0;
  if (!(b.geometry.resolution > 0.0) || b.geometry.width <= 0 || b.geometry.height <= 0)
    return Error{"observation store " + path_.string() + ": stored baseline is corrupt"};

  // Tiles in [tx0, tx1] x [ty0, ty1]: all, or those a region overlaps.
  int64_t tx0 = 0, ty0 = 0, tx1 = INT32_MAX, ty1 = INT32_MAX;
  if (region) {
    if (region->empty()) return std::optional<Baseline>{std::move(b)};
    const double side = b.geometry.resolution * BaselineTile::kSide;
    tx0 = static_cast<int64_t>(std::floor((region->x0 - b.geometry.origin.x) / side));
    ty0 = static_cast<int64_t>(std::floor((region->y0 - b.geometry.origin.y) / side));
    tx1 = static_cast<int64_t>(std::floor((region->x1 - b.geometry.origin.x) / side));
    ty1 = static_cast<int64_t>(std::floor((region->y1 - b.geometry.origin.y) / side));
  }
  auto q = prepare(
      "SELECT tx, ty, cells FROM baseline_tiles WHERE ty BETWEEN ? AND ? AND tx BETWEEN ? AND ? "
      "ORDER BY ty, tx");
  if (!q) return q.error();
  sqlite3_stmt* st = q->get();
  sqlite3_bind_int64(st, 1, ty0);
  sqlite3_bind_int64(st, 2, ty1);
  sqlite3_bind_int64(st, 3, tx0);
  sqlite3_bind_int64(st, 4, tx1);
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(st)) == SQLITE_ROW) {
    if (static_cast<size_t>(sqlite3_column_bytes(st, 2)) != kTileBytes)
      return Error{"observation store " + path_.string() + ": a baseline tile is corrupt"};
    BaselineTile& t = b.tiles.emplace_back();
    t.tx = static_cast<int32_t>(sqlite3_column_int64(st, 0));
    t.ty = static_cast<int32_t>(sqlite3_column_int64(st, 1));
    t.cells.resize(kTileBytes / sizeof(int16_t));
    std::memcpy(t.cells.data(), sqlite3_column_blob(st, 2), kTileBytes);
  }
  if (step != SQLITE_DONE) return db_error("reading the baseline tiles");
  return std::optional<Baseline>{std::move(b)};
}

Result<int64_t> ObservationStore::compact(const Baseline& baseline) {
  SLAM_TRY(flush());
  SLAM_TRY(exec("BEGIN IMMEDIATE"));
  const auto fail = [&](Error e) -> Result<int64_t> {
    (void)exec("ROLLBACK");
    return e;
  };
  if (Status s = exec("DELETE FROM baseline; DELETE FROM baseline_tiles"); !s) return fail(s.error());
  auto meta = prepare(
      "INSERT INTO baseline(id, resolution, origin_x, origin_y, width, height, through_row, prior_pending) "
      "VALUES(1, ?, ?, ?, ?, ?, ?, 0)");
  if (!meta) return fail(meta.error());
  sqlite3_stmt* m = meta->get();
  sqlite3_bind_double(m, 1, baseline.geometry.resolution);
  sqlite3_bind_double(m, 2, baseline.geometry.origin.x);
  sqlite3_bind_double(m, 3, baseline.geometry.origin.y);
  sqlite3_bind_int64(m, 4, baseline.geometry.width);
  sqlite3_bind_int64(m, 5, baseline.geometry.height);
  sqlite3_bind_int64(m, 6, baseline.through_row);
  if (sqlite3_step(m) != SQLITE_DONE) return fail(db_error("save the baseline"));
  auto tile = prepare("INSERT INTO baseline_tiles(ty, tx, cells) VALUES(?, ?, ?)");
  if (!tile) return fail(tile.error());
  sqlite3_stmt* t = tile->get();
  for (const BaselineTile& bt : baseline.tiles) {
    sqlite3_reset(t);
    sqlite3_bind_int64(t, 1, bt.ty);
    sqlite3_bind_int64(t, 2, bt.tx);
    sqlite3_bind_blob(t, 3, bt.cells.data(), static_cast<int>(kTileBytes), SQLITE_STATIC);
    if (sqlite3_step(t) != SQLITE_DONE) return fail(db_error("save a baseline tile"));
  }
  auto del = prepare("DELETE FROM observations WHERE id <= ?");
  if (!del) return fail(del.error());
  sqlite3_bind_int64(del->get(), 1, baseline.through_row);
  if (sqlite3_step(del->get()) != SQLITE_DONE) return fail(db_error("delete compacted observations"));
  const int64_t deleted = sqlite3_changes64(db_.get());
  if (Status s = exec("COMMIT"); !s) return fail(s.error());
  return deleted;
}

Result<int64_t> ObservationStore::used_bytes() {
  auto pages = scalar("PRAGMA page_count");
  if (!pages) return pages.error();
  auto free_pages = scalar("PRAGMA freelist_count");
  if (!free_pages) return free_pages.error();
  auto size = scalar("PRAGMA page_size");
  if (!size) return size.error();
  return (*pages - *free_pages) * *size;
}

Result<StoreStats> ObservationStore::stats() {
  StoreStats s;
  const auto get = [&](const char* sql, int64_t& out) -> Status {
    auto v = scalar(sql);
    if (!v) return v.error();
    out = *v;
    return Status::ok();
  };
  const auto reads = [&]() -> Status {
    SLAM_TRY(get("SELECT COUNT(*) FROM observations", s.rows));
    SLAM_TRY(get("SELECT COUNT(*) FROM keyframes", s.keyframes));
    SLAM_TRY(get("SELECT COUNT(*) FROM (SELECT DISTINCT keyframe FROM observations WHERE keyframe != 0)",
                 s.raw_keyframes));
    SLAM_TRY(get("SELECT COUNT(*) FROM baseline_tiles", s.compacted_tiles));
    SLAM_TRY(get("SELECT through_row FROM baseline WHERE id = 1", s.compacted_through));
    SLAM_TRY(get("SELECT stamp_ns FROM observations ORDER BY id LIMIT 1", s.oldest_stamp_ns));
    SLAM_TRY(get("SELECT stamp_ns FROM observations ORDER BY id DESC LIMIT 1", s.newest_stamp_ns));
    auto used = used_bytes();
    if (!used) return used.error();
    s.bytes = *used;
    int64_t pages = 0, page_size = 0;
    SLAM_TRY(get("PRAGMA page_count", pages));
    SLAM_TRY(get("PRAGMA page_size", page_size));
    s.file_bytes = pages * page_size;
    return Status::ok();
  };
  SLAM_TRY(read_together(reads));
  return s;
}

}  // namespace slam::mapper
