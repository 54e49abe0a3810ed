// `stereo cosim` in a build without the RTL (-DSTEREO_WITH_RTL=OFF): the subcommand stays
// listed, and running it says why it cannot co-simulate (exit 2, a usage error).
#include <cstddef>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "cli.hpp"

namespace stereo::cli {

void add_cosim_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "cosim", "Co-simulation of the Verilated RTL (not in this build: -DSTEREO_WITH_RTL=OFF)");
    // Thrown as soon as the subcommand is seen, before its arguments are parsed (they would be
    // unknown options): one line naming the build option, exit 2.
    command->preparse_callback([](std::size_t) {
        throw std::invalid_argument(
            "cosim: this stereo was built without the RTL (-DSTEREO_WITH_RTL=OFF); rebuild with "
            "Verilator (scripts/setup.sh) to co-simulate");
    });
}

}  // namespace stereo::cli
