// `stereo`: command-line front end of the golden model. See cli.hpp for the structure.
#include <CLI/CLI.hpp>

#include "cli.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Stereo matching with the bit-exact golden model, and its evaluation.", "stereo"};
    stereo::cli::add_stereo_commands(app);
    return stereo::cli::run(app, argc, argv);
}
