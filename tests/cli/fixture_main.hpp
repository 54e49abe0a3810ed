// The main() of the fixture writers (make_cli_fixtures, make_slam_fixtures): OUTPUT_FOLDER as the
// only argument, the writer run on it, any exception one line on stderr and a failing exit code.
#pragma once

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>

namespace stereo::test {

inline int fixture_main(int argc, char** argv, const char* name,
                        void (*write)(const std::filesystem::path&)) {
    if (argc != 2) {
        std::cerr << "usage: " << name << " OUTPUT_FOLDER\n";
        return 2;
    }
    try {
        write(argv[1]);
        return EXIT_SUCCESS;
    } catch (const std::exception& error) {
        std::cerr << name << ": " << error.what() << '\n';
        return EXIT_FAILURE;
    }
}

}  // namespace stereo::test
