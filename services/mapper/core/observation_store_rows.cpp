// ObservationStore: reading observations back: all of them in order (rebuilds), one robot's poses
// (trajectories), the rows of one keyframe and rows by id (partial re-renders), in one read transaction
// when asked (see observation_store.hpp).
#include <sqlite3.h>

#include <cstring>
#include <limits>

#include "mapper/core/observation_store.hpp"

namespace slam::mapper {
namespace {

// The columns visit_rows() reads, in its order; hits and misses follow as columns 10 and 11.
constexpr std::string_view kRowColumns =
    "id, robot, seq, stamp_ns, x, y, theta, has_heading, keyframe, robot_stamp_ns";

Status decode_points(const void* blob, int bytes, std::vector<Vec2>* out) {
  if (bytes < 0 || bytes % static_cast<int>(sizeof(Vec2)) != 0)
    return Error{"point blob size is not a multiple of 16"};
  out->resize(static_cast<size_t>(bytes) / sizeof(Vec2));
  if (bytes > 0) std::memcpy(out->data(), blob, static_cast<size_t>(bytes));
  return Status::ok();
}

}  // namespace

Status ObservationStore::for_each(const std::function<void(const ObservationRecord&)>& visit) {
  return for_each(visit, std::numeric_limits<int64_t>::max());
}

Status ObservationStore::for_each(const std::function<void(const ObservationRecord&)>& visit,
                                  int64_t through_row) {
  const std::string sql =
      "SELECT " + std::string(kRowColumns) + ", hits, misses FROM observations WHERE id <= ? ORDER BY id";
  auto q = prepare(sql.c_str());
  if (!q) return q.status();
  sqlite3_bind_int64(q->get(), 1, through_row);
  return visit_rows(q->get(), true, visit);
}

Status ObservationStore::rows_of(KeyframeId keyframe, int64_t first_row, int64_t last_row,
                                 const std::function<void(int64_t)>& visit) {
  if (!rows_of_) {
    auto q = prepare("SELECT id FROM observations WHERE keyframe = ? AND id BETWEEN ? AND ? ORDER BY id");
    if (!q) return q.status();
    rows_of_ = std::move(*q);
  }
  sqlite3_stmt* st = rows_of_.get();
  sqlite3_reset(st);
  sqlite3_bind_int64(st, 1, static_cast<sqlite3_int64>(keyframe));
  sqlite3_bind_int64(st, 2, first_row);
  sqlite3_bind_int64(st, 3, last_row);
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) visit(sqlite3_column_int64(st, 0));
  sqlite3_reset(st);
  if (rc != SQLITE_DONE) return db_error("reading the rows of keyframe " + std::to_string(keyframe));
  return Status::ok();
}

Status ObservationStore::for_each_row(std::span<const int64_t> rows,
                                      const std::function<void(const ObservationRecord&)>& visit) {
  if (!row_) {
    const std::string sql =
        "SELECT " + std::string(kRowColumns) + ", hits, misses FROM observations WHERE id = ?";
    auto q = prepare(sql.c_str());
    if (!q) return q.status();
    row_ = std::move(*q);
  }
  sqlite3_stmt* st = row_.get();
  for (const int64_t row : rows) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, row);
    const Status s = visit_rows(st, true, visit);
    sqlite3_reset(st);
    SLAM_TRY(s);
  }
  return Status::ok();
}

Status ObservationStore::read_together(const std::function<Status()>& reads) {
  if (in_batch_) return reads();
  SLAM_TRY(exec("BEGIN"));
  const Status s = reads();
  const Status end = exec("COMMIT");
  return s ? end : s;
}

int64_t ObservationStore::last_row() const {
  return static_cast<int64_t>(sqlite3_last_insert_rowid(db_.get()));
}

Status ObservationStore::for_each_pose(std::string_view robot_id,
                                       const std::function<void(const ObservationRecord&)>& visit) {
  const std::string sql =
      "SELECT " + std::string(kRowColumns) + " FROM observations WHERE robot = ? ORDER BY id";
  auto q = prepare(sql.c_str());
  if (!q) return q.status();
  sqlite3_bind_text(q->get(), 1, robot_id.data(), static_cast<int>(robot_id.size()), SQLITE_STATIC);
  return visit_rows(q->get(), false, visit);
}

Status ObservationStore::visit_rows(sqlite3_stmt* st, bool with_points,
                                    const std::function<void(const ObservationRecord&)>& visit) {
  ObservationRecord rec;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    rec.id = sqlite3_column_int64(st, 0);
    const auto* robot = reinterpret_cast<const char*>(sqlite3_column_text(st, 1));
    rec.robot_id = robot ? std::string_view(robot, static_cast<size_t>(sqlite3_column_bytes(st, 1))) : "";
    rec.seq = static_cast<uint64_t>(sqlite3_column_int64(st, 2));
    rec.stamp_ns = sqlite3_column_int64(st, 3);
    rec.obs.x = sqlite3_column_double(st, 4);
    rec.obs.y = sqlite3_column_double(st, 5);
    rec.obs.theta = sqlite3_column_double(st, 6);
    rec.obs.has_heading = sqlite3_column_int(st, 7) != 0;
    rec.keyframe_id = static_cast<KeyframeId>(sqlite3_column_int64(st, 8));
    rec.robot_stamp_ns = sqlite3_column_int64(st, 9);
    if (with_points) {
      const Status h = decode_points(sqlite3_column_blob(st, 10), sqlite3_column_bytes(st, 10), &hits_buf_);
      const Status m = decode_points(sqlite3_column_blob(st, 11), sqlite3_column_bytes(st, 11), &misses_buf_);
      if (!h || !m)
        return Error{"observation store " + path_.string() + ": row " + std::to_string(rec.id) + ": " +
                     (h ? m.message() : h.message())};
      rec.obs.hits = hits_buf_;
      rec.obs.misses = misses_buf_;
    }
    visit(rec);
  }
  if (rc != SQLITE_DONE) return db_error("reading observations");
  return Status::ok();
}

Result<int64_t> ObservationStore::count() {
  auto q = prepare("SELECT count(*) FROM observations");
  if (!q) return q.error();
  if (sqlite3_step(q->get()) != SQLITE_ROW) return db_error("count");
  return static_cast<int64_t>(sqlite3_column_int64(q->get(), 0));
}

}  // namespace slam::mapper
