// Command-line options shared by the testbenches: --seed=N replays a random run (the seed is
// printed by every test that uses it) and --trace[=DIR] writes FST waveforms.
#pragma once

#include <cstdint>
#include <string>

namespace stereo::tb {

struct Options {
    bool seed_given = false;
    std::uint32_t seed = 0;
    std::string trace_dir;  // empty: no waveforms
};

Options& options();

// The seed for one test: --seed if given, else a fresh random one; printed either way.
std::uint32_t test_seed();

// "<trace_dir>/<test name>.fst", or empty when tracing is off.
std::string trace_path();

}  // namespace stereo::tb
