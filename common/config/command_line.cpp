#include "common/config/command_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "common/config/version.hpp"

namespace fleetmap::config {
namespace {

// "fleetmap security enroll": the program and the subcommands the command line selected, the
// command a refused option belongs to.
std::string CommandPath(const CLI::App& app, const std::string& program) {
  std::string path = program;
  const CLI::App* command = &app;
  while (true) {
    const std::vector<CLI::App*> selected = command->get_subcommands();
    if (selected.empty()) break;
    command = selected.back();
    path.append(" ").append(command->get_name());
  }
  return path;
}

// A check that `text` is a number above (or, `or_zero`, at least) 0.
std::function<std::string(std::string&)> SignCheck(bool or_zero) {
  return [or_zero](std::string& text) -> std::string {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || std::isnan(value)) {
      return "'" + text + "' is not a number";
    }
    if (value < 0.0 || (value == 0.0 && !or_zero)) {
      return std::string("must be ") + (or_zero ? ">= 0" : "> 0") + ", got " + text;
    }
    return {};
  };
}

// CLI11's PositiveNumber and NonNegativeNumber are ranges up to the largest double, and say so:
// "Value -3 not in range 0.000000 to 179769313486231570814527...000000". The same checks, here on
// every option of `app` and its subcommands, say "must be > 0, got -3".
void RewordSignChecks(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    for (int i = 0;; ++i) {
      CLI::Validator* validator = nullptr;
      try {
        validator = option->get_validator(i);
      } catch (const CLI::OptionNotFound&) {
        break;  // CLI11 lists an option's validators only by index or name
      }
      if (validator->get_description() == "POSITIVE") validator->operation(SignCheck(false));
      if (validator->get_description() == "NONNEGATIVE") validator->operation(SignCheck(true));
    }
  }
  for (CLI::App* subcommand : app.get_subcommands([](CLI::App*) { return true; })) {
    RewordSignChecks(*subcommand);
  }
}

// The arguments of `args` that belong to `command` (after the subcommand names that select it),
// or nullopt when the command line does not select it.
std::optional<std::vector<std::string>> ArgumentsOf(const CLI::App& app,
                                                    const std::vector<std::string>& args,
                                                    const CLI::App* command) {
  const CLI::App* current = &app;
  size_t next = 0;
  while (current != command && next < args.size()) {
    const std::vector<const CLI::App*> subcommands =
        current->get_subcommands([](const CLI::App*) { return true; });
    const auto named = std::find_if(
        subcommands.begin(), subcommands.end(),
        [&](const CLI::App* subcommand) { return subcommand->check_name(args[next]); });
    if (named == subcommands.end()) break;
    current = *named;
    ++next;
  }
  if (current != command) return std::nullopt;
  return std::vector<std::string>(args.begin() + static_cast<std::ptrdiff_t>(next), args.end());
}

bool AsksForHelpOrVersion(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& arg) {
    return arg == "--help" || arg == "-h" || arg == "--help-all" || arg == "--version";
  });
}

}  // namespace

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::vector<ConfigurableCommand*>& configurable) {
  const std::string program =
      argc > 0 ? std::filesystem::path(argv[0]).filename().string() : std::string("fleetmap");
  app.set_version_flag("--version", VersionText(program),
                       "Print the fleetmap version, git commit and Fast DDS version, then exit");
  RewordSignChecks(app);
  app.failure_message([program](const CLI::App* failed, const CLI::Error& error) {
    const std::string command = CommandPath(*failed, program);
    return command + ": " + error.what() + "\n" + "(run " + command + " --help for its options)\n";
  });
  if (app.get_name().empty() && argc > 0) app.name(argv[0]);  // as CLI11 does, for its usage line
  std::vector<std::string> args(argv + std::min(argc, 1), argv + argc);
  // --help and --version come before any file is read, whatever is wrong with the file.
  if (!AsksForHelpOrVersion(args)) {
    for (ConfigurableCommand* command : configurable) {
      const auto own_arguments = ArgumentsOf(app, args, command->command());
      if (!own_arguments) continue;
      const auto layers = command->Layers(*own_arguments);
      if (!layers.ok()) {
        std::cerr << command->program() << ": " << layers.status().message() << "\n";
        return kExitBadCommandLine;
      }
      args.insert(args.end(), layers->begin(), layers->end());
    }
  }
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
  try {
    app.parse(std::move(args));
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : kExitBadCommandLine;
  }
  return std::nullopt;
}

std::optional<int> ParseFleetProgram(CLI::App& app, int argc, char** argv,
                                     const std::string& ros_node) {
  const std::string program =
      argc > 0 ? std::filesystem::path(argv[0]).filename().string() : std::string("fleetmap");
  ConfigurableCommand config(&app, program, ros_node, DdsEnvironment());
  if (const auto exit_now = ParseCommandLine(app, argc, argv, {&config})) return exit_now;
  if (config.print_requested()) {
    config.Print(std::cout);
    return 0;
  }
  return std::nullopt;
}

}  // namespace fleetmap::config
