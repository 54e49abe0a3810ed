// `stereo cosim` in a build without the RTL (-DSTEREO_WITH_RTL=OFF): the subcommand parses the
// same options as with the RTL (cli_cosim_options.hpp), and running it says why it cannot
// co-simulate (exit 2, a usage error).
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_cosim_options.hpp"

namespace stereo::cli {

void add_cosim_command(CLI::App& app) {
    const auto [command, options] = add_command<CosimOptions>(
        app, "cosim",
        "Co-simulation of the Verilated RTL (not in this build: -DSTEREO_WITH_RTL=OFF)",
        [](const CosimOptions&) {
            throw std::invalid_argument(
                "cosim: this stereo was built without the RTL (-DSTEREO_WITH_RTL=OFF); rebuild "
                "with Verilator (scripts/setup.sh) to co-simulate");
        });
    add_cosim_options(*command, *options);
}

}  // namespace stereo::cli
