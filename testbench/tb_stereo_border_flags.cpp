// stereo_border_flags against the two comparisons it replaces, 0 <= p + o < limit computed in
// 64-bit integers: every 18-bit position p, for limits at and around every edge the equality
// tests of the module treat specially (0 .. 6, the co-simulation widths, the largest frame side
// and the largest 16-bit values) and a sample of random limits.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <verilated.h>
#include <verilated_fst_c.h>
#pragma GCC diagnostic pop

#include "Vstereo_border_flags.h"
#include "verilated_harness.hpp"

namespace stereo::tb {
namespace {

// The module's default parameters, which is what the Verilated configuration builds.
constexpr int kOffsetLo = -2;
constexpr int kOffsetHi = 2;
constexpr int kPositionBits = 18;

// Sign-extends the low kPositionBits bits of a Verilated port value.
std::int64_t position_of(std::uint32_t bits) {
    const std::int64_t value = bits & ((1U << kPositionBits) - 1U);
    return value >= (1 << (kPositionBits - 1)) ? value - (1 << kPositionBits) : value;
}

// Every position for one limit; returns the number of mismatching (p, o) pairs, after reporting
// the first few.
int mismatches_for_limit(Vstereo_border_flags& model, std::uint32_t limit) {
    int errors = 0;
    model.limit = static_cast<std::uint16_t>(limit);
    for (std::uint32_t bits = 0; bits < (1U << kPositionBits); ++bits) {
        model.position = bits;
        model.eval();
        const std::int64_t p = position_of(bits);
        for (int o = kOffsetLo; o <= kOffsetHi; ++o) {
            const bool expected = p + o >= 0 && p + o < static_cast<std::int64_t>(limit);
            const bool actual = ((model.in_frame >> (o - kOffsetLo)) & 1U) != 0;
            if (expected != actual && ++errors <= 5) {
                ADD_FAILURE() << "limit " << limit << ", position " << p << ", offset " << o
                              << ": RTL " << actual << ", expected " << expected;
            }
        }
    }
    return errors;
}

TEST(StereoBorderFlags, EveryPositionAtEdgeLimits) {
    sim::VerilatedHarness<Vstereo_border_flags> harness("border_flags");
    std::vector<std::uint32_t> limits = {0, 1, 2, 3, 4, 5, 6, 48, 64, 16383, 16384, 65534, 65535};
    std::mt19937 rng(19);
    std::uniform_int_distribution<std::uint32_t> any_limit(0, 65535);
    for (int i = 0; i < 4; ++i) {
        limits.push_back(any_limit(rng));
    }
    for (const std::uint32_t limit : limits) {
        EXPECT_EQ(mismatches_for_limit(harness.model(), limit), 0) << "limit " << limit;
    }
}

}  // namespace
}  // namespace stereo::tb
