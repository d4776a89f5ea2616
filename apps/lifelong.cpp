// lifelong: the command-line front of the testbed. Thin: parses arguments, runs
// `optimize` itself (slam + io only) and loads liblifelong_commands.so for run, replay,
// simulate and sweep (apps/commands.hpp), so that --help and optimize start without OpenCV or GL.
// Exit codes (apps/exit_codes.hpp): 0 success, 2 bad input or usage, 1 internal failure,
// 130 interrupted.
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "apps/cli_commands.hpp"
#include "apps/commands.hpp"
#include "apps/exit_codes.hpp"
#include "apps/module_loader.hpp"
#include "io/output_path.hpp"
#include "lifelong_build_info.hpp"  // generated: LIFELONG_VERSION, LIFELONG_COMMIT

namespace {

using lifelong::apps::CommandTable;

constexpr const char* kDefaultScenario = LIFELONG_SOURCE_DIR "/scenarios/corridor_100.yaml";
constexpr const char* kDefaultBook = LIFELONG_SOURCE_DIR "/book/chapter6.yaml";
constexpr const char* kCommandsModule = "liblifelong_commands.so";

std::string CommandLine(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

const CommandTable* LoadCommands() {
  using Entry = const CommandTable* (*)();
  return reinterpret_cast<Entry>(
      lifelong::apps::ModuleEntry(kCommandsModule, lifelong::apps::kCommandTableSymbol))();
}

// The first word that is not an option must be a command; CLI11 alone would call an
// unknown one an "extra argument".
std::optional<std::string> UnknownCommand(int argc, char** argv, const CLI::App& app) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == argv[1]) return std::nullopt;
  }
  return std::string(argv[1]);
}

// optimize and sparsify run here; the other commands in the module they load.
int Dispatch(const lifelong::apps::CliCommands& c, lifelong::apps::CliArgs& args) {
  const auto never_interrupted = [](const std::exception&) { return false; };
  if (*c.optimize) {
    return lifelong::apps::Guarded(
        [&] {
          if (!args.optimize.out.empty()) lifelong::io::CheckWritableFile(args.optimize.out, "-o");
          return lifelong::apps::OptimizeGraph(args.optimize);
        },
        never_interrupted);
  }
  if (*c.sparsify) {
    return lifelong::apps::Guarded([&] { return lifelong::apps::Sparsify(args.sparsify); },
                                   never_interrupted);
  }
  const CommandTable* commands = nullptr;
  const int loaded = lifelong::apps::Guarded(
      [&] {
        commands = LoadCommands();
        return 0;
      },
      never_interrupted);
  if (loaded != 0) return loaded;
  if (*c.run) return commands->run(args.run);
  if (*c.simulate) return commands->simulate(args.simulate);
  if (*c.sweep) return commands->sweep(args.sweep);
  if (*c.score) return commands->score(args.score);
  if (*c.reproduce) return commands->reproduce(args.reproduce);
  if (*c.replay) return commands->replay(args.replay);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lifelong: a testbed for life-long graph-based 2D laser SLAM"};
  app.require_subcommand(1);
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "lifelong " LIFELONG_VERSION " (commit " LIFELONG_COMMIT ")");
  lifelong::apps::CliArgs args;
  const lifelong::apps::CliCommands commands = lifelong::apps::AddCommands(
      app, &args, CommandLine(argc, argv), kDefaultScenario, kDefaultBook);
  if (const auto unknown = UnknownCommand(argc, argv, app)) {
    std::cerr << "error: unknown command " << *unknown
              << " (known: run, simulate, replay, score, optimize, sparsify, sweep, reproduce; see "
                 "lifelong "
                 "--help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (const auto problem = lifelong::apps::UsageProblem(commands, &args)) {
    std::cerr << "error: " << *problem << "\n";
    return 2;
  }
  return Dispatch(commands, args);
}
