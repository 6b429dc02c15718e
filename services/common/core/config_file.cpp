#include "common/core/config_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <sstream>

namespace slam {
namespace {

std::string option_name(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

void flatten(const YAML::Node& node, const std::string& prefix, std::vector<CLI::ConfigItem>& out) {
  for (const auto& kv : node) {
    const std::string key = option_name(kv.first.as<std::string>());
    const std::string name = prefix.empty() ? key : prefix + "-" + key;
    const YAML::Node& value = kv.second;
    CLI::ConfigItem item;
    item.name = name;
    if (value.IsMap()) {
      flatten(value, name, out);
      continue;
    }
    if (value.IsSequence()) {
      for (const auto& v : value) item.inputs.push_back(v.as<std::string>());
    } else if (value.IsScalar()) {
      item.inputs.push_back(value.as<std::string>());
    }
    out.push_back(std::move(item));
  }
}

}  // namespace

std::vector<CLI::ConfigItem> YamlConfig::from_config(std::istream& input) const {
  std::vector<CLI::ConfigItem> result;
  try {
    const YAML::Node root = YAML::Load(input);
    if (root.IsNull()) return result;
    if (!root.IsMap())
      throw CLI::ConversionError("config file: the top level must be a map of option: value");
    flatten(root, "", result);
  } catch (const YAML::Exception& e) {
    throw CLI::ConversionError(std::string("config file: ") + e.what());
  }
  return result;
}

std::string YamlConfig::to_config(const CLI::App* app, bool default_also, bool write_description,
                                  std::string /*prefix*/) const {
  std::ostringstream out;
  for (const CLI::Option* opt : app->get_options()) {
    if (opt->get_lnames().empty() || !opt->get_configurable()) continue;
    const std::string name = opt->get_lnames().front();
    std::string value;
    if (opt->count() > 0) {
      value = CLI::detail::join(opt->results(), ", ");
    } else if (default_also) {
      value = opt->get_default_str();
    }
    if (value.empty()) continue;
    if (write_description && !opt->get_description().empty()) out << "# " << opt->get_description() << '\n';
    out << name << ": " << value << '\n';
  }
  return out.str();
}

}  // namespace slam
