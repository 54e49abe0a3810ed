// Test vectors for the SystemVerilog testbench (testbench/sv/README.md): the input beats of a
// pair, the golden model's output beats and the configuration, as $readmemh files, so that a
// simulator without C++ (Questa, Xcelium, Vivado xsim, Verilator --binary) can check the RTL
// bit for bit. `stereo vectors` writes them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::io {

// config.hex: one 32-bit word per line, in this order (testbench/sv/tb_vector_config.sv reads
// them by these indices); the kernel's `window` taps follow kVectorKernel.
enum VectorWord : int {
    kVectorMagic = 0,  // kVectorMagicValue
    kVectorCost,       // stereo_top's COST code of the cost the vectors were computed with
    kVectorWidth,      // frame width
    kVectorHeight,     // frame height
    kVectorFrames,     // frames streamed back to back (the same pair each time)
    kVectorNdisp,      // labels searched
    kVectorWindow,     // the frame's window (odd): cfg_radius = window / 2
    kVectorUseCa,      // CA rules on
    kVectorMinDisp,    // minimum disparity, two's complement in table::kCfgMinDispBits
    kVectorUniquenessEn,
    kVectorUniqueness,  // ratio U, percent
    kVectorLrEn,
    kVectorLrTolerance,
    kVectorSubpixelEn,
    kVectorKernel,  // `window` taps of the 1-D kernel, tap 0 first
};
inline constexpr std::uint32_t kVectorMagicValue = 0x5354'5631;  // "STV1"

// The three files' texts. input.hex: {tuser, tlast, s_axis_tdata} per beat (50 bits, 13 hex
// digits); expected.hex: {tuser, tlast, m_axis_tdata} per beat (34 bits, 9 hex digits).
struct VectorTexts {
    std::string config;
    std::string input;
    std::string expected;
};

// The vectors of `frames` copies of the pair and `expected` (match_validated of the pair with
// `params`, computed by the caller). Throws std::invalid_argument when the sizes disagree.
VectorTexts make_vectors(const Image& left, const Image& right, const MatchParams& params,
                         const ValidatedDisparity& expected, int frames);

// Writes config.hex, input.hex and expected.hex into `folder` (created if missing).
void write_vectors(const std::filesystem::path& folder, const VectorTexts& texts);

}  // namespace stereo::io
