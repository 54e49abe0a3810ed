// main() of the testbenches: our options first, then GoogleTest's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "tb_options.hpp"

namespace stereo::tb {

Options& options() {
    static Options instance;
    return instance;
}

std::uint32_t test_seed() {
    const std::uint32_t seed = options().seed_given ? options().seed : std::random_device{}();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::cout << "[seed] " << (info != nullptr ? info->name() : "") << ": --seed=" << seed << '\n';
    return seed;
}

std::string trace_path() {
    if (options().trace_dir.empty()) {
        return {};
    }
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "." + info->name();
    for (char& c : name) {
        if (c == '/') {
            c = '_';
        }
    }
    std::filesystem::create_directories(options().trace_dir);
    return options().trace_dir + "/" + name + ".fst";
}

}  // namespace stereo::tb

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);  // removes the flags it knows
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--seed=", 0) == 0) {
            stereo::tb::options().seed_given = true;
            stereo::tb::options().seed =
                static_cast<std::uint32_t>(std::strtoul(arg.c_str() + 7, nullptr, 10));
        } else if (arg == "--trace") {
            stereo::tb::options().trace_dir = "traces";
        } else if (arg.rfind("--trace=", 0) == 0) {
            stereo::tb::options().trace_dir = arg.substr(8);
        } else {
            std::cerr << "unknown option " << arg << " (known: --seed=N, --trace[=DIR])\n";
            return 2;
        }
    }
    return RUN_ALL_TESTS();
}
