// compose/docker-compose.yml stays deployable: the Compose validator accepts it (skipped when no
// validator is installed), every flag a service's command passes is one its program offers, every
// key of a mounted --config file is one of the program's options, and every file it mounts exists
// (or is an operator-made secret with a committed <name>.example beside it).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "process_group.hpp"

namespace slam::testkit {
namespace {

namespace fs = std::filesystem;

const fs::path kComposeDir = fs::path(SLAM_SOURCE_DIR) / "compose";
const fs::path kComposeFile = kComposeDir / "docker-compose.yml";

// Runs argv to completion in `group` as `name`; returns (exit code, stdout+stderr).
std::pair<int, std::string> run(ProcessGroup& group, const std::string& name,
                                const std::vector<std::string>& argv) {
  group.start(name, argv);
  const int code = group.wait_exit(name, 60s);
  return {code, group.log(name)};
}

// The Compose implementation installed here: docker-compose (v1, Debian's package) or the v2 plugin.
std::vector<std::string> compose_command(ProcessGroup& group) {
  if (run(group, "probe-v1", {"docker-compose", "version"}).first == 0) return {"docker-compose"};
  if (run(group, "probe-v2", {"docker", "compose", "version"}).first == 0) return {"docker", "compose"};
  return {};
}

// A project program from the build tree, else a tool from PATH; "" when neither exists.
std::string resolve_program(ProcessGroup& group, const std::string& name) {
  if (fs::exists(bin_path(name))) return bin_path(name);
  return run(group, "which-" + name, {"sh", "-c", "command -v \"$0\"", name}).first == 0 ? name : "";
}

std::vector<std::string> command_of(const YAML::Node& service) {
  std::vector<std::string> argv;
  const YAML::Node command = service["command"];
  if (!command) return argv;
  if (command.IsSequence()) {
    for (const auto& arg : command) argv.push_back(arg.as<std::string>());
  } else if (command.IsScalar()) {
    std::istringstream words(command.as<std::string>());
    for (std::string w; words >> w;) argv.push_back(w);
  }
  return argv;
}

// Whether `help` lists `flag` as a whole option name (not as a prefix of a longer one).
bool help_lists(const std::string& help, const std::string& flag) {
  for (size_t at = help.find(flag); at != std::string::npos; at = help.find(flag, at + 1)) {
    const size_t end = at + flag.size();
    const bool starts = at == 0 || help[at - 1] == ' ' || help[at - 1] == ',' || help[at - 1] == '\n';
    const bool ends =
        end == help.size() || help[end] == ' ' || help[end] == ',' || help[end] == '=' || help[end] == '\n';
    if (starts && ends) return true;
  }
  return false;
}

// "./a/b:/target:ro" -> {"./a/b", "/target"}; named volumes ("mapdata:/x") have no "./".
std::pair<std::string, std::string> split_mount(const std::string& spec) {
  const size_t colon = spec.find(':');
  if (colon == std::string::npos) return {spec, ""};
  const size_t second = spec.find(':', colon + 1);
  return {spec.substr(0, colon),
          spec.substr(colon + 1, second == std::string::npos ? std::string::npos : second - colon - 1)};
}

TEST(ComposeTest, ValidatorAcceptsTheComposeFile) {
  ProcessGroup group;
  std::vector<std::string> argv = compose_command(group);
  if (argv.empty()) GTEST_SKIP() << "no Compose validator installed (apt-get install docker-compose)";
  argv.insert(argv.end(), {"-f", kComposeFile.string(), "config", "-q"});
  const auto [code, output] = run(group, "compose-config", argv);
  EXPECT_EQ(code, 0) << "the Compose validator rejects " << kComposeFile << ":\n" << output;
}

TEST(ComposeTest, ServiceCommandsUseFlagsTheirProgramsOffer) {
  const YAML::Node services = YAML::LoadFile(kComposeFile.string())["services"];
  ASSERT_TRUE(services.IsMap()) << kComposeFile << " has no services";
  ProcessGroup group;
  int checked = 0;
  for (const auto& entry : services) {
    const std::string service = entry.first.as<std::string>();
    const std::vector<std::string> argv = command_of(entry.second);
    if (argv.empty()) continue;  // an image's own entry point (the broker)
    const std::string program = resolve_program(group, argv[0]);
    ASSERT_FALSE(program.empty())
        << "service " << service << " runs '" << argv[0]
        << "', which is neither built nor installed (scripts/setup.sh installs tools)";
    // The program plus its subcommand words ("fastdds discovery"), then --help.
    std::vector<std::string> help_argv{program};
    for (size_t i = 1; i < argv.size() && argv[i].rfind('-', 0) != 0; ++i) help_argv.push_back(argv[i]);
    help_argv.push_back("--help");
    const auto [code, help] = run(group, "help-" + service, help_argv);
    ASSERT_EQ(code, 0) << "service " << service << ": " << argv[0] << " --help failed:\n" << help;

    std::vector<std::string> flags;
    for (const auto& arg : argv)
      if (arg.rfind("--", 0) == 0) flags.push_back(arg.substr(0, arg.find('=')));
    // A mounted --config file: its keys are long option names of the program.
    for (size_t i = 0; i + 1 < argv.size(); ++i) {
      if (argv[i] != "--config") continue;
      for (const auto& volume : entry.second["volumes"]) {
        const auto [source, target] = split_mount(volume.as<std::string>());
        if (target != argv[i + 1]) continue;
        for (const auto& key : YAML::LoadFile((kComposeDir / source).string()))
          flags.push_back("--" + key.first.as<std::string>());
      }
    }
    for (const auto& flag : flags) {
      EXPECT_TRUE(help_lists(help, flag))
          << "service " << service << " passes " << flag << " (command or config file), which " << argv[0]
          << " does not offer:\n"
          << help;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "no service command passed any flag; is " << kComposeFile
                        << " the deployment file?";
}

// `docker-compose up --scale gateway=2 --scale planner=2`: replicas must not share a container
// name or a published port, nor (on the host's network and host name) a process id, which makes
// their instance ids and MQTT client ids.
TEST(ComposeTest, GatewaysAndPlannersScale) {
  const YAML::Node services = YAML::LoadFile(kComposeFile.string())["services"];
  for (const char* name : {"gateway", "planner"}) {
    const YAML::Node service = services[name];
    ASSERT_TRUE(service) << "no service " << name;
    EXPECT_FALSE(service["container_name"]) << name << " has a fixed container name";
    EXPECT_FALSE(service["ports"]) << name << " publishes fixed ports";
    // From the shared x-service block: yaml-cpp may leave the merge key (<<) unresolved.
    const YAML::Node merged = service["<<"];
    const YAML::Node pid = service["pid"] ? service["pid"] : merged ? merged["pid"] : YAML::Node();
    ASSERT_TRUE(pid) << name << " replicas would all be pid 1 on the same host name";
    EXPECT_EQ(pid.as<std::string>(), "host");
    for (const auto& volume : service["volumes"]) {
      EXPECT_NE(split_mount(volume.as<std::string>()).first.rfind("mapdata", 0), 0u)
          << name << " replicas would share one data volume: " << volume.as<std::string>();
    }
  }
}

TEST(ComposeTest, MountedFilesExistOrHaveAnExample) {
  const YAML::Node services = YAML::LoadFile(kComposeFile.string())["services"];
  ASSERT_TRUE(services.IsMap());
  for (const auto& entry : services) {
    for (const auto& volume : entry.second["volumes"]) {
      const std::string source = split_mount(volume.as<std::string>()).first;
      if (source.rfind("./", 0) != 0 && source.rfind("../", 0) != 0) continue;  // a named volume
      const fs::path path = kComposeDir / source;
      // Docker creates a missing bind-mount source as an empty directory, which the service then
      // fails on: secrets made by the operator must at least have a committed example.
      EXPECT_TRUE(fs::exists(path) || fs::exists(path.string() + ".example"))
          << "service " << entry.first.as<std::string>() << " mounts " << source
          << ", which does not exist and has no " << source << ".example";
    }
  }
}

}  // namespace
}  // namespace slam::testkit
