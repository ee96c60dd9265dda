#pragma once

// A command whose options can also come from a config file and the environment
// (docs/configuration.md). It adds two options to the command:
//   --config FILE     settings from a YAML file (config_file.hpp: plain, or a ROS 2 params file);
//   --print-config    print the effective settings, each with where it came from, and exit.
// A setting is taken from, lowest first: the option's default < the config file < the
// environment (the variables given, e.g. FLEETMAP_DOMAIN for --domain) < the command line. CLI11
// still parses everything: ParseCommandLine (command_line.hpp) asks Layers() for the file's and
// the environment's settings as arguments and appends them to the command line's, so every check,
// requirement and exclusion of the command applies to them alike.
//
//   config::ConfigurableCommand config(&app, "fleetmap_server",
//                                      {{"--domain", {"FLEETMAP_DOMAIN"}}});
//   if (auto exit_now = config::ParseCommandLine(app, argc, argv, {&config})) return *exit_now;
//   if (config.print_requested()) { config.Print(std::cout); return 0; }
//
// Thread-safety: none; used on the main thread while the command line is parsed.

#include <CLI/CLI.hpp>

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::config {

// Environment variables that set an option when the command line does not, first set first.
struct EnvironmentSource {
  std::string option;                  // "--domain"
  std::vector<std::string> variables;  // {"FLEETMAP_DOMAIN"}
};

// The environment variables of the DDS options every fleet program has (--domain,
// --localhost-only, --discovery-server); common/transport/participant.cpp reads the same ones for
// the commands without a config file.
std::vector<EnvironmentSource> DdsEnvironment();

class ConfigurableCommand {
 public:
  // `command` is the program's App or one subcommand (`fleetmap view`); `program` names it in
  // messages ("fleetmap-server"); `ros_node` is the node name its ROS 2 params section has.
  ConfigurableCommand(CLI::App* command, std::string program, std::string ros_node,
                      std::vector<EnvironmentSource> environment = {});
  ConfigurableCommand(const ConfigurableCommand&) = delete;  // the App holds pointers into it
  ConfigurableCommand& operator=(const ConfigurableCommand&) = delete;

  CLI::App* command() const { return command_; }
  const std::string& program() const { return program_; }

  // Given the command line's arguments for this command (after its subcommand name), the
  // arguments that bring in the config file's and the environment's settings for every option
  // the command line leaves out. Each value is checked first, so that an error names its source:
  // "server.yaml:4: --tile-size: must be > 0, got -3". Unknown keys are errors naming the file
  // and line, except keys of a ROS 2 params file's /** section.
  StatusOr<std::vector<std::string>> Layers(const std::vector<std::string>& command_line);

  // After the parse: whether --print-config was given, and the effective settings as a config
  // file (--config reads it back), each line commented with its source.
  bool print_requested() const { return print_requested_; }
  void Print(std::ostream& out) const;

 private:
  struct Layered {
    std::vector<std::string> values;
    std::string origin;  // for messages: "server.yaml:4", "environment FLEETMAP_DOMAIN"
    std::string source;  // for --print-config: "file server.yaml:4", "environment ..."
  };

  StatusOr<std::map<CLI::Option*, Layered>> FileSettings(const std::string& path) const;
  void AddEnvironment(std::map<CLI::Option*, Layered>& settings) const;
  // Settings whose option the command line gives, or excludes, are the command line's business.
  void DropOverridden(std::map<CLI::Option*, Layered>& settings,
                      const std::vector<std::string>& command_line);
  static Status Check(CLI::Option* option, const Layered& setting);
  bool IsOwnOption(const CLI::Option* option) const;

  CLI::App* command_;
  std::string program_;
  std::string ros_node_;
  std::vector<EnvironmentSource> environment_;
  std::string config_path_;
  bool print_requested_ = false;
  CLI::Option* config_option_ = nullptr;
  CLI::Option* print_option_ = nullptr;
  std::map<const CLI::Option*, std::string> sources_;  // options not from the default
};

}  // namespace fleetmap::config
