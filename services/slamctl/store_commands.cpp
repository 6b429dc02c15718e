// slamctl store stats (see store_commands.hpp).
#include "slamctl/store_commands.hpp"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>

#include "slamctl/session_io.hpp"

namespace slam::ctl {
namespace {

struct StoreArgs {
  std::string what;
  std::string path = "run/data/map.db";
};

std::string utc(int64_t stamp_ns) {
  const std::time_t t = static_cast<std::time_t>(stamp_ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", &tm);
  return buf;
}

int cmd_store(const StoreArgs& a) {
  std::error_code ec;
  if (!std::filesystem::exists(a.path, ec)) return fail("no store at " + a.path + " (the mapper's --store)");
  auto store = mapper::ObservationStore::open(a.path);
  if (!store) return fail(store.message());
  auto stats = store->stats();
  if (!stats) return fail(stats.message());
  std::fputs(describe_store(a.path, *stats).c_str(), stdout);
  return kExitOk;
}

}  // namespace

std::string describe_store(const std::string& path, const mapper::StoreStats& s) {
  char buf[1024];
  const double mb = 1024.0 * 1024.0;
  std::string oldest = "none";
  if (s.rows > 0) {
    const double hours = static_cast<double>(s.newest_stamp_ns - s.oldest_stamp_ns) / 3.6e12;
    char age[96];
    std::snprintf(age, sizeof age, " (%.1f h before the newest)", hours);
    oldest = utc(s.oldest_stamp_ns) + age;
  }
  std::snprintf(buf, sizeof buf,
                "store %s\n"
                "  raw observations     %lld\n"
                "  oldest raw           %s\n"
                "  keyframes            %lld (%lld with raw observations)\n"
                "  compacted tiles      %lld (32x32 cells of log-odds: every observation up to row %lld)\n"
                "  size                 %.1f MB in use, %.1f MB file\n",
                path.c_str(), static_cast<long long>(s.rows), oldest.c_str(),
                static_cast<long long>(s.keyframes), static_cast<long long>(s.raw_keyframes),
                static_cast<long long>(s.compacted_tiles), static_cast<long long>(s.compacted_through),
                static_cast<double>(s.bytes) / mb, static_cast<double>(s.file_bytes) / mb);
  return buf;
}

Handler add_store(CLI::App& cli) {
  auto a = std::make_shared<StoreArgs>();
  cli.add_option("what", a->what, "stats: what the store keeps (raw rows, compacted tiles, size)")
      ->check(CLI::IsMember({"stats"}))
      ->required();
  cli.add_option("--store", a->path, "the mapper's SQLite store (its --store)")->capture_default_str();
  return [a](Session&) { return cmd_store(*a); };
}

}  // namespace slam::ctl
