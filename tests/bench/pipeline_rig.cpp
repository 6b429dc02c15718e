// Starting the whole system for bench_pipeline and reading it from outside: heartbeats, /proc.
#include "pipeline_rig.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>

namespace slam::bench {
namespace {

constexpr double kDoorM = 1.2;

// Reads a positive number from the environment variable `name` into `out` when it is set.
Status env_number(const char* name, double min, double max, double& out) {
  const char* text = std::getenv(name);
  if (text == nullptr) return Status::ok();
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v < min || v > max)
    return Error{fmt::format("{}='{}': must be a number between {} and {}", name, text, min, max)};
  out = v;
  return Status::ok();
}

int cm(double metres) {
  return static_cast<int>(std::lround(metres * 100.0));
}

// "gateway", "gateway2", "gateway3", ...: the first instance keeps the service's name.
std::string instance_name(const std::string& service, int index) {
  return index == 0 ? service : service + std::to_string(index + 1);
}

}  // namespace

Result<PipelineSettings> pipeline_settings_from_env() {
  PipelineSettings s;
  double robots = s.robots;
  double gateways = s.gateways;
  double planners = s.planners;
  SLAM_TRY(env_number("SLAM_BENCH_PIPELINE_ROBOTS", 1, 5000, robots));
  if (auto st = env_number("SLAM_BENCH_PIPELINE_SECONDS", 2, 3600, s.seconds); !st) return st.error();
  SLAM_TRY(env_number("SLAM_BENCH_PIPELINE_GATEWAYS", 1, 8, gateways));
  SLAM_TRY(env_number("SLAM_BENCH_PIPELINE_PLANNERS", 1, 8, planners));
  s.robots = static_cast<int>(robots);
  s.gateways = static_cast<int>(gateways);
  s.planners = static_cast<int>(planners);
  if (const char* dir = std::getenv("SLAM_BENCH_PIPELINE_BIN_DIR")) {
    s.bin_dir = dir;
    if (::access((s.bin_dir + "/slam-gateway").c_str(), X_OK) != 0)
      return Error{fmt::format("SLAM_BENCH_PIPELINE_BIN_DIR='{}': no slam-gateway there", dir)};
  }
  if (const char* slam = std::getenv("SLAM_BENCH_PIPELINE_SLAM")) {
    if (std::string_view(slam) != "on" && std::string_view(slam) != "off")
      return Error{fmt::format("SLAM_BENCH_PIPELINE_SLAM='{}': must be on or off", slam)};
    s.slam = std::string_view(slam) == "on";
  }
  if (const char* bridge = std::getenv("SLAM_BENCH_PIPELINE_BRIDGE")) {
    if (std::string_view(bridge) != "0" && std::string_view(bridge) != "1")
      return Error{fmt::format("SLAM_BENCH_PIPELINE_BRIDGE='{}': must be 0 or 1", bridge)};
    s.bridge = std::string_view(bridge) == "1";
  }
  return s;
}

std::string rooms_world_text(double side_m, double room_m) {
  std::string out = fmt::format("{}:{}\n", cm(side_m), cm(side_m));
  const int rooms = static_cast<int>(std::lround(side_m / room_m));
  for (int line = 1; line < rooms; ++line) {
    const double c = line * room_m;
    for (int r = 0; r < rooms; ++r) {
      const double a = r * room_m;
      const double door_lo = a + 0.5 * (room_m - kDoorM);
      const double door_hi = door_lo + kDoorM;
      const double b = a + room_m;
      // Vertical wall at x = c, then horizontal wall at y = c, each in two pieces around the door.
      out += fmt::format("{},{}:{},{} {},{}:{},{}\n", cm(c), cm(a), cm(c), cm(door_lo), cm(c), cm(door_hi),
                         cm(c), cm(b));
      out += fmt::format("{},{}:{},{} {},{}:{},{}\n", cm(a), cm(c), cm(door_lo), cm(c), cm(door_hi), cm(c),
                         cm(b), cm(c));
    }
  }
  return out;
}

int64_t CounterSample::get(const std::string& name) const {
  const auto it = values.find(name);
  return it == values.end() ? 0 : it->second;
}

int64_t CounterSample::sum_prefixed(const std::string& prefix) const {
  int64_t total = 0;
  for (const auto& [name, value] : values)
    if (name.starts_with(prefix)) total += value;
  return total;
}

double rate_between(const CounterSample& from, const CounterSample& to, const std::string& name) {
  const double dt = static_cast<double>(to.stamp_ns - from.stamp_ns) / 1e9;
  return dt > 0.0 ? static_cast<double>(to.get(name) - from.get(name)) / dt : 0.0;
}

double process_cpu_s(pid_t pid) {
  std::ifstream file("/proc/" + std::to_string(pid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // The command name (field 2) is in parentheses and may contain spaces: count from the last ')'.
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(stat.substr(close + 1));
  std::string skip;
  for (int field = 3; field < 14; ++field) fields >> skip;  // state .. cmajflt
  long long utime = 0, stime = 0;
  if (!(fields >> utime >> stime)) return -1.0;
  return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

int64_t process_waits(pid_t pid) {
  int64_t total = 0;
  std::error_code error;
  const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
  for (const auto& task : std::filesystem::directory_iterator(tasks, error)) {
    std::ifstream status(task.path() / "status");
    std::string line;
    constexpr std::string_view kKey = "voluntary_ctxt_switches:";
    while (std::getline(status, line)) {
      if (line.starts_with(kKey)) total += std::strtoll(line.c_str() + kKey.size(), nullptr, 10);
    }
  }
  return total;
}

MachineCpu machine_cpu() {
  std::ifstream file("/proc/stat");
  std::string label;
  file >> label;  // "cpu": the sum over all cores
  long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  file >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  const double tick = static_cast<double>(::sysconf(_SC_CLK_TCK));
  const auto busy = user + nice + system + irq + softirq + steal;
  return {static_cast<double>(busy) / tick, static_cast<double>(busy + idle + iowait) / tick};
}

Result<std::unique_ptr<PipelineRig>> PipelineRig::start(const PipelineSettings& settings) {
  std::unique_ptr<PipelineRig> rig(new PipelineRig());
  if (Status s = rig->launch(settings); !s) return s.error();
  return rig;
}

Status PipelineRig::launch(const PipelineSettings& s) {
  robots_ = s.robots;
  gateways_ = s.gateways;
  planners_ = s.planners;
  const auto program = [&](const std::string& name) {
    return s.bin_dir.empty() ? testkit::bin_path(name) : s.bin_dir + "/" + name;
  };
  const std::string world = group_.dir() + "/rooms.txt";
  std::ofstream(world) << rooms_world_text(s.world_side_m, s.room_m);

  port_ = group_.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(port_);
  const std::string domain = std::to_string(domain_.id());
  const GridLayout& g = s.grid;
  // With DDS Security on (docs/security.md) each service runs as its identity, and the Cyclone
  // simulator keeps its DDS side on a plain domain of its own, as run.sh --secure does.
  const bool secure = testkit::dds_security_on();
  const std::string sim_domain = std::to_string(secure ? sim_domain_.id() : domain_.id());
  // Several gateways share the robots through the broker's shared subscription (their default).
  for (int i = 0; i < s.gateways; ++i) {
    group_.start(instance_name("gateway", i),
                 testkit::with_dds_identity("gateway", {program("slam-gateway"), "--domain", domain,
                                                        "--broker", broker, "--log-level", "warn"}));
  }
  group_.start(
      "mapper",
      testkit::with_dds_identity(
          "mapper", {program("slam-mapper"), "--domain", domain, "--store", group_.dir() + "/map.db",
                     "--grid-resolution", fmt::format("{}", g.resolution), "--grid-origin-x",
                     fmt::format("{}", g.origin_x), "--grid-origin-y", fmt::format("{}", g.origin_y),
                     "--grid-width-m", fmt::format("{}", g.side_m), "--grid-height-m",
                     fmt::format("{}", g.side_m), "--slam", s.slam ? "on" : "off", "--log-level", "warn"}));
  for (int i = 0; i < s.planners; ++i) {
    const std::string name = instance_name("planner", i);
    group_.start(name, testkit::with_dds_identity(
                           "planner", {program("slam-planner"), "--domain", domain, "--log-level", "warn",
                                       "--goal-store", group_.dir() + "/goals-" + name + ".json"}));
  }
  if (s.bridge) {
    bridge_port_ = testkit::free_tcp_port();
    group_.start("bridge", testkit::with_dds_identity(
                               "bridge", {program("slam-bridge"), "--domain", domain, "--bind",
                                          fmt::format("127.0.0.1:{}", bridge_port_), "--log-level", "warn"}));
  }
  group_.start("simulator", {program("slam-simulator"),
                             "--domain",
                             sim_domain,
                             "--broker",
                             broker,
                             "--world",
                             world,
                             "--robots",
                             std::to_string(s.robots),
                             "--protocol",
                             "v1",
                             "--rate",
                             "10",
                             "--beams",
                             std::to_string(s.beams),
                             "--max-range",
                             fmt::format("{}", s.max_range_m),
                             "--dropout",
                             "0",
                             "--random-walk",
                             "--mqtt-multiplex",
                             "--log-level",
                             "warn"});

  auto participant = dds::Participant::create(domain_.id(), "bench-pipeline");
  if (!participant) return Error{"DDS participant: " + participant.message()};
  participant_ = std::move(*participant);
  if (secure) {
    auto plain = dds::Participant::create(sim_domain_.id(), "bench-pipeline-sim", std::nullopt);
    if (!plain) return Error{"DDS participant on the simulator's domain: " + plain.message()};
    sim_participant_ = std::move(*plain);
  }
  dds::Participant& sim_side = secure ? *sim_participant_ : *participant_;
  const auto heartbeat = [this](const Heartbeat& h, const auto&) {
    CounterSample sample;
    sample.stamp_ns = h.stamp_ns();
    for (const Counter& c : h.counters()) sample.values[c.name().to_string()] = c.value();
    std::lock_guard lock(mutex_);
    latest_[h.service().to_string()][h.instance_id().to_string()] = std::move(sample);
  };
  auto reader = dds::make_reader(*participant_, dds::kHeartbeat, heartbeat);
  if (!reader) return Error{"heartbeat reader: " + reader.message()};
  heartbeats_ = std::move(*reader);
  if (secure) {
    auto sim_reader = dds::make_reader(sim_side, dds::kHeartbeat, heartbeat);
    if (!sim_reader) return Error{"simulator heartbeat reader: " + sim_reader.message()};
    sim_heartbeats_ = std::move(*sim_reader);
  }
  auto control = dds::make_writer(sim_side, dds::kSimControl);
  if (!control) return Error{"SimControl writer: " + control.message()};
  sim_control_ = std::move(*control);
  return Status::ok();
}

Status PipelineRig::control_simulator(SimCommandKind kind) {
  if (!sim_control_->wait_for_readers(std::chrono::seconds(10)))
    return Error{"the simulator's SimControl reader did not match"};
  SimControl c;
  c.command_id(++commands_sent_);
  c.kind(kind);
  c.speed_factor(1.0);
  if (!sim_control_->write(c)) return Error{"SimControl write failed"};
  return Status::ok();
}

Status PipelineRig::wait_until_running(std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  int64_t first_observations = -1;
  while (std::chrono::steady_clock::now() < until) {
    if (Status s = check_running(); !s) return s;
    bool all = instances("gateway").size() == static_cast<size_t>(gateways_) &&
               instances("planner").size() == static_cast<size_t>(planners_);
    for (const char* service : {"mapper", "simulator"}) all = all && latest(service).stamp_ns > 0;
    const int64_t observations = latest("mapper").get("observations");
    if (all && latest("simulator").get("robots") >= robots_ && observations > 0) {
      if (first_observations < 0) first_observations = observations;
      if (observations > first_observations) return Status::ok();  // integrating, not a one-off
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  std::string missing;
  for (const char* service : {"gateway", "mapper", "planner", "simulator"})
    missing += fmt::format(" {}: {} heartbeating", service, instances(service).size());
  // Where the stream stops (broker, gateway or mapper) and what the services said, e.g. a DDS
  // Security error on a secure domain.
  return Error{fmt::format(
      "the pipeline did not start within {} s (simulator robots {}, gateway messages in {}, gateway "
      "observations {}, mapper observations {});{}\ngateway log:\n{}\nmapper log:\n{}",
      timeout.count(), latest("simulator").get("robots"), latest("gateway").get("messages_in"),
      latest("gateway").get("observations"), latest("mapper").get("observations"), missing,
      log_tail("gateway"), log_tail("mapper"))};
}

Status PipelineRig::check_running() {
  for (const auto& [name, pid] : processes()) {
    if (!group_.running(name)) return Error{name + " exited:\n" + log_tail(name)};
  }
  return Status::ok();
}

CounterSample PipelineRig::latest(const std::string& service) const {
  CounterSample total;
  for (const auto& [instance, sample] : instances(service)) {
    total.stamp_ns = std::max(total.stamp_ns, sample.stamp_ns);
    for (const auto& [name, value] : sample.values) total.values[name] += value;
  }
  return total;
}

std::map<std::string, CounterSample> PipelineRig::instances(const std::string& service) const {
  std::lock_guard lock(mutex_);
  const auto it = latest_.find(service);
  return it == latest_.end() ? std::map<std::string, CounterSample>{} : it->second;
}

std::vector<std::pair<std::string, pid_t>> PipelineRig::processes() const {
  std::vector<std::pair<std::string, pid_t>> out;
  out.emplace_back("mosquitto", group_.pid("mosquitto"));
  for (int i = 0; i < gateways_; ++i) out.emplace_back(instance_name("gateway", i), 0);
  out.emplace_back("mapper", 0);
  for (int i = 0; i < planners_; ++i) out.emplace_back(instance_name("planner", i), 0);
  out.emplace_back("simulator", 0);
  if (bridge_port_ != 0) out.emplace_back("bridge", 0);
  for (auto& [name, pid] : out) pid = group_.pid(name);
  return out;
}

std::string PipelineRig::service_of(const std::string& process) {
  return process.substr(0, process.find_last_not_of("0123456789") + 1);
}

std::string PipelineRig::log_tail(const std::string& name) const {
  const std::string log = group_.log(name);
  return log.size() > 2000 ? "..." + log.substr(log.size() - 2000) : log;
}

}  // namespace slam::bench
