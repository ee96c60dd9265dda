#include "common/config/configurable_command.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <set>
#include <utility>

#include "common/config/config_file.hpp"

namespace fleetmap::config {
namespace {

// A flag takes no value on the command line (--no-quarantine); in a file it is true or false.
bool IsFlag(const CLI::Option& option) { return option.get_items_expected_max() == 0; }

std::string LongName(const CLI::Option& option) {
  return option.get_lnames().empty() ? std::string() : option.get_lnames().front();
}

// The values CLI11 captured as an option's default: "[0,0,0]" for an option of several values.
std::vector<std::string> DefaultValues(const CLI::Option& option) {
  const std::string text = option.get_default_str();
  if (IsFlag(option)) return {text.empty() ? "false" : text};
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') return {text};
  std::vector<std::string> values;
  std::string inner = text.substr(1, text.size() - 2);
  for (size_t start = 0; start <= inner.size();) {
    const size_t comma = std::min(inner.find(',', start), inner.size());
    if (comma > start) values.push_back(inner.substr(start, comma - start));
    start = comma + 1;
  }
  return values;
}

std::vector<std::string> EffectiveValues(const CLI::Option& option) {
  if (option.count() == 0) return DefaultValues(option);
  if (IsFlag(option)) return {option.as<bool>() ? "true" : "false"};
  return option.results();
}

// `key: value` as YAML, a sequence for an option of several values.
std::string YamlLine(const std::string& key, const std::vector<std::string>& values,
                     bool sequence) {
  YAML::Emitter emitter;
  emitter << YAML::BeginMap << YAML::Key << key << YAML::Value;
  if (sequence) {
    emitter << YAML::Flow << YAML::BeginSeq;
    for (const std::string& value : values) emitter << value;
    emitter << YAML::EndSeq;
  } else {
    emitter << (values.empty() ? std::string() : values.front());
  }
  emitter << YAML::EndMap;
  return emitter.c_str();
}

// The option a command-line argument names ("--tile-size=5", "--tile-size", "-h"), if any.
CLI::Option* NamedOption(CLI::App& command, const std::string& argument) {
  if (argument.size() < 2 || argument[0] != '-') return nullptr;
  if (argument[1] != '-' && std::isdigit(static_cast<unsigned char>(argument[1]))) {
    return nullptr;  // a negative number, a value of the option before it
  }
  return command.get_option_no_throw(argument.substr(0, argument.find('=')));
}

}  // namespace

std::vector<EnvironmentSource> DdsEnvironment() {
  return {{"--domain", {"FLEETMAP_DOMAIN"}},
          {"--localhost-only", {"FLEETMAP_LOCALHOST_ONLY", "ROS_LOCALHOST_ONLY"}},
          {"--discovery-server", {"ROS_DISCOVERY_SERVER"}}};
}

ConfigurableCommand::ConfigurableCommand(CLI::App* command, std::string program,
                                         std::string ros_node,
                                         std::vector<EnvironmentSource> environment)
    : command_(command),
      program_(std::move(program)),
      ros_node_(std::move(ros_node)),
      environment_(std::move(environment)) {
  config_option_ = command_->add_option(
      "--config", config_path_,
      "YAML file of settings: the long options' names as keys, or a ROS 2 params file with a " +
          ros_node_ + " section; the command line wins over it (docs/configuration.md)");
  print_option_ =
      command_->add_flag("--print-config", print_requested_,
                         "print the effective settings (each with its source: default, file, "
                         "environment, command line) as a config file, then exit");
}

bool ConfigurableCommand::IsOwnOption(const CLI::Option* option) const {
  return option == config_option_ || option == print_option_ ||
         option == command_->get_help_ptr() || option == command_->get_help_all_ptr() ||
         option->check_lname("version");
}

StatusOr<std::map<CLI::Option*, ConfigurableCommand::Layered>> ConfigurableCommand::FileSettings(
    const std::string& path) const {
  std::string note;
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<ConfigSetting> settings,
                            ReadConfigFile(path, ros_node_, &note));
  if (!note.empty()) std::cerr << program_ << ": warning: " << note << "\n";
  std::map<CLI::Option*, Layered> layered;
  for (const ConfigSetting& setting : settings) {
    CLI::Option* option = command_->get_option_no_throw("--" + setting.key);
    if (option == nullptr) {
      if (setting.for_every_node) continue;  // another node's parameter
      return InvalidArgumentError(setting.location + ": unknown key " + setting.key + ": " +
                                  program_ + " has no option --" + setting.key + " (" + program_ +
                                  " --help lists them)");
    }
    if (IsOwnOption(option)) {
      return InvalidArgumentError(setting.location + ": " + setting.key +
                                  " cannot be set in a config file");
    }
    const size_t most = static_cast<size_t>(std::max(option->get_items_expected_max(), 1));
    const size_t least = static_cast<size_t>(std::max(option->get_items_expected_min(), 1));
    if (setting.values.size() < least || setting.values.size() > most) {
      const std::string wanted =
          most == 1 ? std::string("one value, not a list") : std::to_string(most) + " values";
      return InvalidArgumentError(setting.location + ": " + setting.key + " takes " + wanted +
                                  ", got " + std::to_string(setting.values.size()));
    }
    layered[option] = {setting.values, setting.location, "file " + setting.location};
  }
  return layered;
}

void ConfigurableCommand::AddEnvironment(std::map<CLI::Option*, Layered>& settings) const {
  for (const EnvironmentSource& source : environment_) {
    CLI::Option* option = command_->get_option_no_throw(source.option);
    if (option == nullptr) continue;
    for (const std::string& variable : source.variables) {
      const char* value = std::getenv(variable.c_str());
      if (value == nullptr || *value == '\0') continue;
      // A flag's variable is on when it is 1, as ROS_LOCALHOST_ONLY is.
      const std::string text =
          IsFlag(*option) ? (std::string(value) == "1" ? "true" : "false") : std::string(value);
      settings[option] = {{text}, "environment " + variable, "environment " + variable};
      break;
    }
  }
}

void ConfigurableCommand::DropOverridden(std::map<CLI::Option*, Layered>& settings,
                                         const std::vector<std::string>& command_line) {
  std::set<CLI::Option*> given;
  for (const std::string& argument : command_line) {
    if (argument == "--") break;
    if (CLI::Option* option = NamedOption(*command_, argument)) {
      given.insert(option);
      sources_[option] = "command line";
    }
  }
  for (auto setting = settings.begin(); setting != settings.end();) {
    CLI::Option* option = setting->first;
    const bool overridden =
        std::any_of(given.begin(), given.end(), [option](CLI::Option* on_command_line) {
          return on_command_line == option || on_command_line->get_excludes().count(option) > 0 ||
                 option->get_excludes().count(on_command_line) > 0;
        });
    setting = overridden ? settings.erase(setting) : std::next(setting);
  }
}

Status ConfigurableCommand::Check(CLI::Option* option, const Layered& setting) {
  // The option's own conversion and checks, run on the value alone and undone; the parse that
  // follows runs them again with everything else.
  Status checked = Status::Ok();
  try {
    option->add_result(setting.values);
    option->run_callback();
  } catch (const CLI::Error& error) {
    checked = InvalidArgumentError(setting.origin + ": " + error.what());
  }
  option->clear();
  return checked;
}

StatusOr<std::vector<std::string>> ConfigurableCommand::Layers(
    const std::vector<std::string>& command_line) {
  // The defaults --print-config shows, captured before any value is stored in the variables.
  for (CLI::Option* option : command_->get_options()) {
    if (option->get_default_str().empty()) option->capture_default_str();
  }
  std::string path;
  for (size_t i = 0; i < command_line.size(); ++i) {
    if (command_line[i] == "--config" && i + 1 < command_line.size()) path = command_line[i + 1];
    if (command_line[i].rfind("--config=", 0) == 0) path = command_line[i].substr(9);
  }
  std::map<CLI::Option*, Layered> settings;
  if (!path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(settings, FileSettings(path));
  }
  AddEnvironment(settings);
  DropOverridden(settings, command_line);

  std::vector<std::string> arguments;
  for (const auto& [option, setting] : settings) {
    FLEETMAP_RETURN_IF_ERROR(Check(option, setting));
    sources_[option] = setting.source;
    const std::string name = "--" + LongName(*option);
    if (setting.values.size() == 1) {
      arguments.push_back(name + "=" + setting.values.front());
    } else {
      arguments.push_back(name);
      arguments.insert(arguments.end(), setting.values.begin(), setting.values.end());
    }
  }
  return arguments;
}

void ConfigurableCommand::Print(std::ostream& out) const {
  out << "# " << program_ << ": the effective settings; --config FILE reads them back.\n"
      << "# After each value, where it came from. Defaults are commented out: uncomment to "
         "change.\n";
  struct Line {
    std::string text;
    std::string source;
  };
  std::vector<Line> lines;
  size_t width = 0;
  for (const CLI::Option* option : command_->get_options()) {
    if (IsOwnOption(option) || LongName(*option).empty()) continue;
    const auto source = sources_.find(option);
    const bool from_default = source == sources_.end();
    const bool sequence = option->get_items_expected_max() > 1;
    Line line{YamlLine(LongName(*option), EffectiveValues(*option), sequence),
              from_default ? "default" : source->second};
    if (from_default) line.text.insert(0, "# ");
    width = std::max(width, line.text.size());
    lines.push_back(std::move(line));
  }
  width = std::min<size_t>(width, 48);
  for (const Line& line : lines) {
    out << line.text << std::string(width > line.text.size() ? width - line.text.size() : 0, ' ')
        << "  # " << line.source << "\n";
  }
}

}  // namespace fleetmap::config
