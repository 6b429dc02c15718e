// SQLite persistence of observations, obstructions, grid config and prior. Points are stored as
// blobs of little-endian float64 pairs: exact, so a rebuild at the same config reproduces the grid.
// Reading observations back lives in observation_store_rows.cpp.
#include "mapper/core/observation_store.hpp"

#include <sqlite3.h>

#include <bit>

namespace slam::mapper {

static_assert(std::endian::native == std::endian::little,
              "point blobs are stored in host (little-endian) order");
static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 must be two packed doubles");

namespace {

// 1: observations without keyframe ids. 2: observations.keyframe, the keyframes table.
// 3: observations.robot_stamp_ns (the robot's own clock). 4: an index of observations by keyframe (a
// partial re-render reads the rows of the keyframes it redraws). 5: the compacted baseline (baseline,
// baseline_tiles).
constexpr int kSchemaVersion = 5;

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS observations(
  id INTEGER PRIMARY KEY,
  robot TEXT NOT NULL,
  seq INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  x REAL NOT NULL, y REAL NOT NULL, theta REAL NOT NULL, has_heading INTEGER NOT NULL,
  hits BLOB, misses BLOB, keyframe INTEGER NOT NULL DEFAULT 0, robot_stamp_ns INTEGER NOT NULL DEFAULT 0);
CREATE TABLE IF NOT EXISTS keyframes(
  id INTEGER PRIMARY KEY,
  robot TEXT NOT NULL,
  segment INTEGER NOT NULL,
  odom_x REAL NOT NULL, odom_y REAL NOT NULL, odom_theta REAL NOT NULL,
  correction_x REAL NOT NULL, correction_y REAL NOT NULL, correction_theta REAL NOT NULL);
CREATE TABLE IF NOT EXISTS obstructions(x REAL NOT NULL, y REAL NOT NULL, PRIMARY KEY(x, y));
CREATE TABLE IF NOT EXISTS config(key TEXT PRIMARY KEY, value REAL NOT NULL);
CREATE TABLE IF NOT EXISTS prior(
  id INTEGER PRIMARY KEY CHECK(id = 1),
  width INTEGER NOT NULL, height INTEGER NOT NULL, resolution REAL NOT NULL,
  origin_x REAL NOT NULL, origin_y REAL NOT NULL, origin_yaw REAL NOT NULL, cells BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS baseline(
  id INTEGER PRIMARY KEY CHECK(id = 1),
  resolution REAL NOT NULL, origin_x REAL NOT NULL, origin_y REAL NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, through_row INTEGER NOT NULL,
  prior_pending INTEGER NOT NULL DEFAULT 0);
CREATE TABLE IF NOT EXISTS baseline_tiles(
  ty INTEGER NOT NULL, tx INTEGER NOT NULL, cells BLOB NOT NULL, PRIMARY KEY(ty, tx));
)sql";

// After the columns older stores gain: (keyframe, rowid) entries, so one keyframe's rows are a range.
constexpr const char* kIndexes =
    "CREATE INDEX IF NOT EXISTS observations_keyframe ON observations(keyframe);";

// The config as key/value rows: adding a field later needs no schema change.
struct ConfigField {
  const char* key;
  double GridConfig::*d;
  int16_t LogOddsConfig::*i;
};
constexpr ConfigField kConfigFields[] = {
    {"resolution", &GridConfig::resolution, nullptr},
    {"origin_x", &GridConfig::origin_x, nullptr},
    {"origin_y", &GridConfig::origin_y, nullptr},
    {"width_m", &GridConfig::width_m, nullptr},
    {"height_m", &GridConfig::height_m, nullptr},
    {"inflation_radius", &GridConfig::inflation_radius, nullptr},
    {"max_extent_m", &GridConfig::max_extent_m, nullptr},
    {"grow_chunk_m", &GridConfig::grow_chunk_m, nullptr},
    {"max_range_m", &GridConfig::max_range_m, nullptr},
    {"log_odds.hit", nullptr, &LogOddsConfig::hit},
    {"log_odds.miss", nullptr, &LogOddsConfig::miss},
    {"log_odds.clamp_min", nullptr, &LogOddsConfig::clamp_min},
    {"log_odds.clamp_max", nullptr, &LogOddsConfig::clamp_max},
    {"log_odds.occupied_threshold", nullptr, &LogOddsConfig::occupied_threshold},
    {"log_odds.free_threshold", nullptr, &LogOddsConfig::free_threshold},
    {"log_odds.prior_occupied", nullptr, &LogOddsConfig::prior_occupied},
    {"log_odds.prior_free", nullptr, &LogOddsConfig::prior_free},
};

}  // namespace

void ObservationStore::DbClose::operator()(sqlite3* db) const {
  sqlite3_close_v2(db);
}
void ObservationStore::StmtFinalize::operator()(sqlite3_stmt* s) const {
  sqlite3_finalize(s);
}

Error ObservationStore::db_error(std::string_view what) const {
  return Error{"observation store " + path_.string() + ": " + std::string(what) + ": " +
               (db_ ? sqlite3_errmsg(db_.get()) : "no database")};
}

Status ObservationStore::exec(const char* sql) {
  char* msg = nullptr;
  if (sqlite3_exec(db_.get(), sql, nullptr, nullptr, &msg) == SQLITE_OK) return Status::ok();
  const std::string text = msg ? msg : sqlite3_errmsg(db_.get());
  sqlite3_free(msg);
  return Error{"observation store " + path_.string() + ": " + text};
}

Result<ObservationStore::Stmt> ObservationStore::prepare(const char* sql) {
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db_.get(), sql, -1, &stmt, nullptr) != SQLITE_OK) return db_error("prepare");
  return Stmt(stmt);
}

Result<ObservationStore> ObservationStore::open(const std::filesystem::path& path, StoreOptions options) {
  if (options.batch_size < 1) return Error{"observation store: batch_size must be >= 1"};
  ObservationStore store;
  store.path_ = path;
  store.options_ = options;
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &raw,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX, nullptr);
  store.db_.reset(raw);
  if (rc != SQLITE_OK) return store.db_error("cannot open");
  sqlite3_busy_timeout(raw, 2000);
  // The first statements read the header: a corrupt file or a non-database fails here.
  if (Status s = store.exec("PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;"); !s) return s.error();
  auto version = store.prepare("PRAGMA user_version");
  if (!version) return version.error();
  if (sqlite3_step(version->get()) != SQLITE_ROW) return store.db_error("cannot read schema version");
  const int found = sqlite3_column_int(version->get(), 0);
  if (found > kSchemaVersion)
    return Error{"observation store " + path.string() + ": schema version " + std::to_string(found) +
                 " is newer than this program's " + std::to_string(kSchemaVersion)};
  // A store of this version is only read here: opening it must not wait for the write lock, which
  // the mapper's own connection holds while a batch is open (the re-render worker opens the store
  // while the map loop keeps appending). One transaction: a migration half done would leave a store
  // neither version can read.
  if (found != kSchemaVersion) {
    if (Status s = store.exec("BEGIN"); !s) return s.error();
    Status schema = store.exec(kSchema);
    // A store older than the column gets it, 0 for its rows (CREATE TABLE IF NOT EXISTS left its table
    // alone); schema 0 is a new, empty store.
    if (schema && found == 1)
      schema = store.exec("ALTER TABLE observations ADD COLUMN keyframe INTEGER NOT NULL DEFAULT 0");
    if (schema && (found == 1 || found == 2))
      schema = store.exec("ALTER TABLE observations ADD COLUMN robot_stamp_ns INTEGER NOT NULL DEFAULT 0");
    if (schema) schema = store.exec(kIndexes);
    if (schema) schema = store.exec(("PRAGMA user_version=" + std::to_string(kSchemaVersion)).c_str());
    if (schema) schema = store.exec("COMMIT");
    if (!schema) {
      (void)store.exec("ROLLBACK");
      return schema.error();
    }
  }
  auto insert = store.prepare(
      "INSERT INTO observations(robot, seq, stamp_ns, x, y, theta, has_heading, hits, misses, keyframe, "
      "robot_stamp_ns) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  if (!insert) return insert.error();
  store.insert_ = std::move(*insert);
  auto upsert = store.prepare(
      "INSERT OR REPLACE INTO keyframes(id, robot, segment, odom_x, odom_y, odom_theta, correction_x, "
      "correction_y, correction_theta) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?)");
  if (!upsert) return upsert.error();
  store.upsert_keyframe_ = std::move(*upsert);
  return store;
}

ObservationStore::~ObservationStore() {
  if (db_ && in_batch_) (void)flush();
}

Status ObservationStore::begin_batch() {
  if (in_batch_) return Status::ok();
  if (Status s = exec("BEGIN"); !s) return s;
  in_batch_ = true;
  return Status::ok();
}

Status ObservationStore::append(std::string_view robot_id, uint64_t seq, int64_t stamp_ns,
                                KeyframeId keyframe_id, const ObservationView& obs, int64_t robot_stamp_ns) {
  SLAM_TRY(begin_batch());
  sqlite3_stmt* st = insert_.get();
  sqlite3_reset(st);
  sqlite3_bind_text(st, 1, robot_id.data(), static_cast<int>(robot_id.size()), SQLITE_STATIC);
  sqlite3_bind_int64(st, 2, static_cast<sqlite3_int64>(seq));
  sqlite3_bind_int64(st, 3, stamp_ns);
  sqlite3_bind_double(st, 4, obs.x);
  sqlite3_bind_double(st, 5, obs.y);
  sqlite3_bind_double(st, 6, obs.theta);
  sqlite3_bind_int(st, 7, obs.has_heading ? 1 : 0);
  sqlite3_bind_blob(st, 8, obs.hits.data(), static_cast<int>(obs.hits.size_bytes()), SQLITE_STATIC);
  sqlite3_bind_blob(st, 9, obs.misses.data(), static_cast<int>(obs.misses.size_bytes()), SQLITE_STATIC);
  sqlite3_bind_int64(st, 10, static_cast<sqlite3_int64>(keyframe_id));
  sqlite3_bind_int64(st, 11, robot_stamp_ns);
  const int rc = sqlite3_step(st);
  sqlite3_reset(st);
  sqlite3_clear_bindings(st);
  if (rc != SQLITE_DONE) return db_error("append");
  if (++pending_ >= options_.batch_size) return flush();
  return Status::ok();
}

Status ObservationStore::save_keyframes(std::span<const Keyframe> keyframes) {
  if (keyframes.empty()) return Status::ok();
  SLAM_TRY(begin_batch());
  sqlite3_stmt* st = upsert_keyframe_.get();
  for (const Keyframe& k : keyframes) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, static_cast<sqlite3_int64>(k.id));
    sqlite3_bind_text(st, 2, k.robot_id.data(), static_cast<int>(k.robot_id.size()), SQLITE_STATIC);
    sqlite3_bind_int64(st, 3, k.segment);
    sqlite3_bind_double(st, 4, k.odom.x);
    sqlite3_bind_double(st, 5, k.odom.y);
    sqlite3_bind_double(st, 6, k.odom.theta);
    sqlite3_bind_double(st, 7, k.map_from_odom.x);
    sqlite3_bind_double(st, 8, k.map_from_odom.y);
    sqlite3_bind_double(st, 9, k.map_from_odom.theta);
    const int rc = sqlite3_step(st);
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
    if (rc != SQLITE_DONE) return db_error("save keyframe " + std::to_string(k.id));
  }
  return Status::ok();
}

Result<std::vector<Keyframe>> ObservationStore::keyframes() {
  auto q = prepare(
      "SELECT id, robot, segment, odom_x, odom_y, odom_theta, correction_x, correction_y, correction_theta "
      "FROM keyframes ORDER BY id");
  if (!q) return q.error();
  sqlite3_stmt* st = q->get();
  std::vector<Keyframe> out;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    Keyframe k;
    k.id = static_cast<KeyframeId>(sqlite3_column_int64(st, 0));
    const auto* robot = reinterpret_cast<const char*>(sqlite3_column_text(st, 1));
    k.robot_id = robot ? robot : "";
    k.segment = static_cast<uint32_t>(sqlite3_column_int64(st, 2));
    k.odom = {sqlite3_column_double(st, 3), sqlite3_column_double(st, 4), sqlite3_column_double(st, 5)};
    k.map_from_odom = {sqlite3_column_double(st, 6), sqlite3_column_double(st, 7),
                       sqlite3_column_double(st, 8)};
    out.push_back(std::move(k));
  }
  if (rc != SQLITE_DONE) return db_error("reading keyframes");
  return out;
}

Status ObservationStore::flush() {
  if (!in_batch_) return Status::ok();
  if (Status s = exec("COMMIT"); !s) return s;
  in_batch_ = false;
  pending_ = 0;
  return Status::ok();
}

Result<int64_t> ObservationStore::delete_robot(std::string_view robot_id) {
  if (Status s = flush(); !s) return s.error();
  auto q = prepare("DELETE FROM observations WHERE robot = ?");
  if (!q) return q.error();
  auto k = prepare("DELETE FROM keyframes WHERE robot = ?");
  if (!k) return k.error();
  SLAM_TRY(exec("BEGIN"));
  sqlite3_bind_text(q->get(), 1, robot_id.data(), static_cast<int>(robot_id.size()), SQLITE_STATIC);
  const bool deleted = sqlite3_step(q->get()) == SQLITE_DONE;
  const auto observations = static_cast<int64_t>(sqlite3_changes(db_.get()));
  sqlite3_bind_text(k->get(), 1, robot_id.data(), static_cast<int>(robot_id.size()), SQLITE_STATIC);
  if (!deleted || sqlite3_step(k->get()) != SQLITE_DONE) {
    const Error e = db_error("delete robot");
    (void)exec("ROLLBACK");
    return e;
  }
  SLAM_TRY(exec("COMMIT"));
  return observations;
}

Status ObservationStore::add_obstruction(Vec2 p) {
  if (Status s = flush(); !s) return s;
  auto q = prepare("INSERT OR IGNORE INTO obstructions(x, y) VALUES(?, ?)");
  if (!q) return q.status();
  sqlite3_bind_double(q->get(), 1, p.x);
  sqlite3_bind_double(q->get(), 2, p.y);
  if (sqlite3_step(q->get()) != SQLITE_DONE) return db_error("add obstruction");
  return Status::ok();
}

Status ObservationStore::remove_obstruction(Vec2 p) {
  if (Status s = flush(); !s) return s;
  auto q = prepare("DELETE FROM obstructions WHERE x = ? AND y = ?");
  if (!q) return q.status();
  sqlite3_bind_double(q->get(), 1, p.x);
  sqlite3_bind_double(q->get(), 2, p.y);
  if (sqlite3_step(q->get()) != SQLITE_DONE) return db_error("remove obstruction");
  return Status::ok();
}

Status ObservationStore::clear_obstructions() {
  if (Status s = flush(); !s) return s;
  return exec("DELETE FROM obstructions");
}

Result<std::vector<Vec2>> ObservationStore::obstructions() {
  auto q = prepare("SELECT x, y FROM obstructions ORDER BY rowid");
  if (!q) return q.error();
  std::vector<Vec2> out;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(q->get())) == SQLITE_ROW)
    out.push_back({sqlite3_column_double(q->get(), 0), sqlite3_column_double(q->get(), 1)});
  if (rc != SQLITE_DONE) return db_error("reading obstructions");
  return out;
}

Status ObservationStore::save_config(const GridConfig& config) {
  if (Status s = flush(); !s) return s;
  auto q = prepare("INSERT OR REPLACE INTO config(key, value) VALUES(?, ?)");
  if (!q) return q.status();
  if (Status s = exec("BEGIN"); !s) return s;
  const auto put = [&](const char* key, double value) {
    sqlite3_reset(q->get());
    sqlite3_bind_text(q->get(), 1, key, -1, SQLITE_STATIC);
    sqlite3_bind_double(q->get(), 2, value);
    return sqlite3_step(q->get()) == SQLITE_DONE;
  };
  bool ok = put("legacy_mode", config.legacy_mode ? 1.0 : 0.0);
  for (const ConfigField& f : kConfigFields)
    ok = ok && put(f.key, f.d ? config.*f.d : static_cast<double>(config.log_odds.*f.i));
  if (!ok) {
    const Error e = db_error("save config");
    (void)exec("ROLLBACK");
    return e;
  }
  return exec("COMMIT");
}

Result<std::optional<GridConfig>> ObservationStore::load_config() {
  auto q = prepare("SELECT key, value FROM config");
  if (!q) return q.error();
  GridConfig config;
  bool any = false;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(q->get())) == SQLITE_ROW) {
    any = true;
    const auto* k = reinterpret_cast<const char*>(sqlite3_column_text(q->get(), 0));
    const std::string_view key = k ? k : "";
    const double value = sqlite3_column_double(q->get(), 1);
    if (key == "legacy_mode") config.legacy_mode = value != 0.0;
    for (const ConfigField& f : kConfigFields) {
      if (key != f.key) continue;
      if (f.d)
        config.*f.d = value;
      else if (value >= INT16_MIN && value <= INT16_MAX)
        config.log_odds.*f.i = static_cast<int16_t>(value);
      else
        return Error{"observation store " + path_.string() + ": stored config " + std::string(key) +
                     " out of range"};
    }
  }
  if (rc != SQLITE_DONE) return db_error("reading config");
  if (!any) return std::optional<GridConfig>{};
  if (Status s = validate(config); !s)
    return Error{"observation store " + path_.string() + ": stored config invalid: " + s.message()};
  return std::optional<GridConfig>{config};
}

Status ObservationStore::save_prior(const MapImage& image) {
  if (image.cells.size() != size_t{image.width} * image.height)
    return Error{"prior map: cell count mismatch"};
  if (Status s = flush(); !s) return s;
  auto q = prepare(
      "INSERT OR REPLACE INTO prior(id, width, height, resolution, origin_x, origin_y, origin_yaw, cells) "
      "VALUES(1, ?, ?, ?, ?, ?, ?, ?)");
  if (!q) return q.status();
  sqlite3_stmt* st = q->get();
  sqlite3_bind_int64(st, 1, image.width);
  sqlite3_bind_int64(st, 2, image.height);
  sqlite3_bind_double(st, 3, image.resolution);
  sqlite3_bind_double(st, 4, image.origin_x);
  sqlite3_bind_double(st, 5, image.origin_y);
  sqlite3_bind_double(st, 6, image.origin_yaw);
  sqlite3_bind_blob64(st, 7, image.cells.data(), image.cells.size(), SQLITE_STATIC);
  if (sqlite3_step(st) != SQLITE_DONE) return db_error("save prior");
  // A baseline holds the prior it was compacted over; a rebuild applies a newer one over it.
  return exec("UPDATE baseline SET prior_pending = 1");
}

Status ObservationStore::clear_prior() {
  if (Status s = flush(); !s) return s;
  return exec("DELETE FROM prior; UPDATE baseline SET prior_pending = 0");
}

Result<std::optional<MapImage>> ObservationStore::load_prior() {
  auto q = prepare(
      "SELECT width, height, resolution, origin_x, origin_y, origin_yaw, cells FROM prior WHERE id = 1");
  if (!q) return q.error();
  sqlite3_stmt* st = q->get();
  const int rc = sqlite3_step(st);
  if (rc == SQLITE_DONE) return std::optional<MapImage>{};
  if (rc != SQLITE_ROW) return db_error("reading prior");
  MapImage image;
  const int64_t w = sqlite3_column_int64(st, 0);
  const int64_t h = sqlite3_column_int64(st, 1);
  const int bytes = sqlite3_column_bytes(st, 6);
  if (w <= 0 || h <= 0 || w * h != bytes)
    return Error{"observation store " + path_.string() + ": stored prior is corrupt"};
  image.width = static_cast<uint32_t>(w);
  image.height = static_cast<uint32_t>(h);
  image.resolution = sqlite3_column_double(st, 2);
  image.origin_x = sqlite3_column_double(st, 3);
  image.origin_y = sqlite3_column_double(st, 4);
  image.origin_yaw = sqlite3_column_double(st, 5);
  const auto* blob = static_cast<const uint8_t*>(sqlite3_column_blob(st, 6));
  image.cells.assign(blob, blob + bytes);
  return std::optional<MapImage>{std::move(image)};
}

}  // namespace slam::mapper
