// lifelong: the command-line front of the testbed. Thin: parses arguments and calls eval.
#include <iostream>

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"lifelong: a testbed for life-long graph-based 2D laser SLAM"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return 0;
}
