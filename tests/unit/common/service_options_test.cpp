// Command-line parsing shared by every service: flags, YAML config files and their precedence,
// and the exit codes for --help and bad input.
#include "common/core/service_options.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.hpp"

namespace slam {
namespace {

struct Parsed {
  std::optional<int> exit;
  ServiceOptions options;
  double rate = 10.0;
  std::string broker = "tcp://127.0.0.1:1883";
};

Parsed parse(std::vector<std::string> args) {
  Parsed p;
  CLI::App app{"test"};
  add_service_options(app, p.options);
  app.add_option("--rate", p.rate);
  app.add_option("--mqtt-broker", p.broker);
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  p.exit = parse_command_line(app, static_cast<int>(argv.size()), argv.data());
  return p;
}

// `text` as config.yaml in `dir`, replacing the previous one.
std::string write_config(const testkit::TempDir& dir, const std::string& text) {
  const auto path = dir / "config.yaml";
  std::ofstream(path) << text;
  return path.string();
}

TEST(ServiceOptions, DefaultsWithoutArguments) {
  const Parsed p = parse({});
  EXPECT_FALSE(p.exit);
  EXPECT_EQ(p.options.domain, 0);
  EXPECT_EQ(p.options.log_level, "info");
}

TEST(ServiceOptions, HelpExitsZero) {
  EXPECT_EQ(parse({"--help"}).exit, 0);
}

TEST(ServiceOptions, BadValuesExitTwo) {
  EXPECT_EQ(parse({"--domain", "500"}).exit, 2);
  EXPECT_EQ(parse({"--domain", "x"}).exit, 2);
  EXPECT_EQ(parse({"--no-such-flag"}).exit, 2);
}

TEST(ServiceOptions, YamlConfigSetsOptionsWithUnderscoresAndNesting) {
  const testkit::TempDir dir("service-options");
  const std::string path = write_config(dir, "domain: 7\nrate: 2.5\nmqtt:\n  broker: tcp://10.0.0.1:1883\n");
  const Parsed p = parse({"--config", path});
  EXPECT_FALSE(p.exit);
  EXPECT_EQ(p.options.domain, 7);
  EXPECT_DOUBLE_EQ(p.rate, 2.5);
  EXPECT_EQ(p.broker, "tcp://10.0.0.1:1883");
}

TEST(ServiceOptions, CommandLineWinsOverConfigFile) {
  const testkit::TempDir dir("service-options");
  const std::string path = write_config(dir, "log_level: debug\ndomain: 7\n");
  const Parsed p = parse({"--config", path, "--domain", "9"});
  EXPECT_EQ(p.options.domain, 9);
  EXPECT_EQ(p.options.log_level, "debug");
}

TEST(ServiceOptions, BadConfigFilesAreRejected) {
  const testkit::TempDir dir("service-options");
  const std::string unknown = write_config(dir, "no_such_option: 1\n");
  EXPECT_EQ(parse({"--config", unknown}).exit, 2);
  const std::string broken = write_config(dir, "domain: [1, \n");
  EXPECT_EQ(parse({"--config", broken}).exit, 2);
  const std::string scalar = write_config(dir, "just text\n");
  EXPECT_EQ(parse({"--config", scalar}).exit, 2);
  EXPECT_EQ(parse({"--config", "/nonexistent/config.yaml"}).exit, 2);
}

struct ToyOptions {
  ServiceOptions service;
  int robots = 1;
};

void add_toy_options(CLI::App& app, ToyOptions& options) {
  add_service_options(app, options.service);
  app.add_option("--robots", options.robots);
}

// Found by start_service through argument-dependent lookup, as each service's validate is.
Status validate(const ToyOptions& options) {
  if (options.robots < 1) return Error{"--robots must be at least 1"};
  return Status::ok();
}

struct Started {
  std::optional<int> exit;
  std::string stderr_text;
};

Started start_toy(std::vector<std::string> args) {
  args.insert(args.begin(), "slam-toy");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  ToyOptions options;
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  Started s;
  s.exit = start_service("toy", "slam-toy: a test", static_cast<int>(argv.size()), argv.data(), options,
                         add_toy_options);
  testing::internal::GetCapturedStdout();
  s.stderr_text = testing::internal::GetCapturedStderr();
  return s;
}

TEST(StartService, CarriesOnWithGoodOptions) {
  const Started s = start_toy({"--robots", "3"});
  EXPECT_EQ(s.exit, std::nullopt);
  EXPECT_EQ(s.stderr_text, "");
}

TEST(StartService, HelpExitsZero) {
  EXPECT_EQ(start_toy({"--help"}).exit, kExitOk);
}

TEST(StartService, InvalidOptionsExitTwoWithOneErrorLine) {
  const Started s = start_toy({"--robots", "0"});
  EXPECT_EQ(s.exit, kExitUsage);
  EXPECT_EQ(s.stderr_text, "slam-toy: error: --robots must be at least 1 (see --help)\n");
}

TEST(StartService, BadLogLevelExitsTwoWithOneErrorLine) {
  const Started s = start_toy({"--log-level", "loud"});
  EXPECT_EQ(s.exit, kExitUsage);
  EXPECT_EQ(s.stderr_text,
            "slam-toy: error: --log-level loud is not one of trace, debug, info, warn, error, off\n");
}

TEST(ReportError, WritesOneLineNamingTheProgram) {
  testing::internal::CaptureStderr();
  report_error("slamctl", "no service seen on DDS domain 3");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "slamctl: error: no service seen on DDS domain 3\n");
}

TEST(ReportError, ExitErrorReportsAndReturnsTheCode) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(exit_error("slam-toy", "no world"), kExitFailure);
  EXPECT_EQ(exit_error("slam-toy", "--world: no such file", kExitUsage), kExitUsage);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "slam-toy: error: no world\nslam-toy: error: --world: no such file\n");
}

TEST(ReportError, ExitCodeIsZeroForAnOkOutcomeAndReportsAFailure) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(exit_code("slam-toy", Status::ok()), kExitOk);
  EXPECT_EQ(exit_code("slam-toy", Error{"log ended early"}), kExitFailure);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "slam-toy: error: log ended early\n");
}

}  // namespace
}  // namespace slam
