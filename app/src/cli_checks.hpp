// Validators of numeric options, with short messages ("--downscale: must be >= 1, got 0"), and the
// one rule every numeric option of the tool follows (plain_numbers): integers are decimal ("064"
// is 64, where CLI11 alone reads octal 52, and "0x40" is refused) and real numbers are finite.
#pragma once

#include <cstdint>

#include <CLI/CLI.hpp>

namespace stereo::cli::checks {

// An integer option's value in [min, max].
CLI::Validator integer_in(std::int64_t min, std::int64_t max);
// An odd integer in [min, max] (a window's side).
CLI::Validator odd_in(std::int64_t min, std::int64_t max);
// An integer option's value >= min (no upper bound but the type's).
CLI::Validator integer_at_least(std::int64_t min);

// How a real option's bound is compared: inclusive (x >= min) or exclusive (x > min).
enum class Bound { inclusive, exclusive };
// A finite real option's value between min and max, each bound inclusive unless said otherwise.
CLI::Validator real_in(double min, double max, Bound lower = Bound::inclusive,
                       Bound upper = Bound::inclusive);

// An output that is written as PNG whatever its name: the name must end in .png (any case), so
// that "map.jpg" or "map.xyz" is refused before any work instead of receiving PNG bytes.
CLI::Validator png_output();

// Adds the decimal-integer and finite-real rule to every numeric option of `app` and of its
// subcommands, recursively (by the type name CLI11 gives the option: INT, UINT or FLOAT).
void plain_numbers(CLI::App& app);

}  // namespace stereo::cli::checks
