#pragma once
// YAML configuration files for CLI11: `--config FILE` loads flat `key: value` pairs whose keys
// are the long option names (`units-per-meter: 100` or `units_per_meter: 100`); nested maps join
// their keys with '-' (`mqtt: {qos: 1}` sets --mqtt-qos). Command-line flags win over the file.
#include <CLI/CLI.hpp>

namespace slam {

class YamlConfig : public CLI::Config {
 public:
  std::string to_config(const CLI::App* app, bool default_also, bool write_description,
                        std::string prefix) const override;
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override;
};

}  // namespace slam
