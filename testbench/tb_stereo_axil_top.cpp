// stereo_axil_top (stereo_top behind AXI4-Lite registers) against its register map
// (docs/integration.md) and against stereo::match_validated: reset values, byte strobes, both
// orders of write address and data, configurations written through the registers and whole
// frames under stalls compared pixel for pixel, the frame and stall counters, the clamped-
// configuration status and the soft reset.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_axil_top.h"
#include "Vstereo_axil_top_census.h"
#include "axis_driver.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_driver.h"
#include "stereo_io/test_support.hpp"
#include "stereo_regs.h"
#include "tb_compare.hpp"
#include "tb_options.hpp"
#include "verilated_harness.hpp"

namespace stereo::sim {
namespace {

constexpr table::Params kConfig = table::verilated("Vstereo_axil_top").params;

// Register offsets (rtl/stereo_axil_top.sv, docs/integration.md).
enum Register : std::uint32_t {
    kId = 0x00,
    kVersion = 0x04,
    kMaxSize = 0x08,
    kBuild = 0x0C,
    kFrame = 0x10,
    kMatch = 0x14,
    kStage6 = 0x18,
    kThresholds = 0x1C,
    kStatus = 0x20,
    kControl = 0x24,
    kFramesIn = 0x28,
    kFramesOut = 0x2C,
    kStalls = 0x30,
    kKernel = 0x40,
};

enum class Order { together, address_first, data_first };

// One Verilated build of the wrapper (Model: Vstereo_axil_top or Vstereo_axil_top_census, both at
// kConfig's size and window).
template <class Model>
class AxilTopOf {
  public:
    AxilTopOf() : harness_("stereo_axil_top") {
        Model& m = harness_.model();
        m.s_axil_awvalid = 0;
        m.s_axil_wvalid = 0;
        m.s_axil_bready = 0;
        m.s_axil_arvalid = 0;
        m.s_axil_rready = 0;
        reset_axis_core(harness_);  // the streams idle as well
    }

    void write(std::uint32_t addr, std::uint32_t data, std::uint8_t strobe = 0xF,
               Order order = Order::together) {
        Model& m = harness_.model();
        bool address_done = false;
        bool data_done = false;
        m.s_axil_awaddr = static_cast<std::uint8_t>(addr);
        m.s_axil_wdata = data;
        m.s_axil_wstrb = strobe;
        m.s_axil_bready = 0;
        for (int cycle = 0; !(address_done && data_done); ++cycle) {
            if (cycle > 20) {
                throw std::runtime_error("AXI4-Lite write not accepted");
            }
            m.s_axil_awvalid = !address_done && (order != Order::data_first || data_done);
            m.s_axil_wvalid = !data_done && (order != Order::address_first || address_done);
            settle();
            const bool address_taken = m.s_axil_awvalid && m.s_axil_awready;
            const bool data_taken = m.s_axil_wvalid && m.s_axil_wready;
            harness_.tick();
            address_done = address_done || address_taken;
            data_done = data_done || data_taken;
        }
        m.s_axil_awvalid = 0;
        m.s_axil_wvalid = 0;
        m.s_axil_bready = 1;
        await([&] { return m.s_axil_bvalid != 0; }, "AXI4-Lite write response missing");
        EXPECT_EQ(m.s_axil_bresp, 0) << "bresp";
        harness_.tick();
        m.s_axil_bready = 0;
    }

    std::uint32_t read(std::uint32_t addr) {
        Model& m = harness_.model();
        m.s_axil_araddr = static_cast<std::uint8_t>(addr);
        m.s_axil_arvalid = 1;
        m.s_axil_rready = 0;
        await([&] { return m.s_axil_arready != 0; }, "AXI4-Lite read not accepted");
        harness_.tick();
        m.s_axil_arvalid = 0;
        m.s_axil_rready = 1;
        await([&] { return m.s_axil_rvalid != 0; }, "AXI4-Lite read data missing");
        EXPECT_EQ(m.s_axil_rresp, 0) << "rresp";
        const std::uint32_t data = m.s_axil_rdata;
        harness_.tick();
        m.s_axil_rready = 0;
        return data;
    }

    // The pipeline configuration through the registers.
    void configure(int width, int height, const MatchParams& p) {
        write(kFrame, static_cast<std::uint32_t>(width) | static_cast<std::uint32_t>(height) << 16);
        write(kMatch, static_cast<std::uint32_t>(p.ndisp) |
                          static_cast<std::uint32_t>(p.window / 2) << 16 |
                          (p.use_ca ? 1U : 0U) << 24);
        const ValidationParams& v = p.validation;
        write(kStage6, (static_cast<std::uint32_t>(p.min_disp) & 0xFFFU) |
                           (v.uniqueness ? 1U : 0U) << 12 | (v.left_right ? 1U : 0U) << 13 |
                           (v.subpixel ? 1U : 0U) << 14);
        write(kThresholds, static_cast<std::uint32_t>(v.uniqueness_ratio) |
                               static_cast<std::uint32_t>(v.lr_tolerance) << 8);
        const std::vector<std::int32_t> taps = centred_kernel(p, kConfig.window);
        for (int i = 0; i < kConfig.window; ++i) {
            write(kKernel + 4 * static_cast<std::uint32_t>(i),
                  static_cast<std::uint32_t>(taps[static_cast<std::size_t>(i)]));
        }
    }

    ValidatedDisparity frame(const Image& left, const Image& right, const Traffic& traffic) {
        const auto beats = frame_beats(left, right);
        const StreamResult result =
            stream_axis(harness_, beats, beats.size(), traffic, 100 * beats.size() + 10000);
        harness_.model().s_axis_tvalid = 0;
        harness_.model().m_axis_tready = 0;
        EXPECT_TRUE(result.completed) << "the core stalled";
        EXPECT_EQ(result.protocol_error, "");
        return assemble_validated(result.outputs, 0, left.width, left.height);
    }

  private:
    void settle() {
        harness_.model().clk = 0;
        harness_.model().eval();
    }

    // Clocks until ready() holds on settled inputs (not clocking that cycle); throws `what` if
    // it has not after 20 cycles.
    template <typename Ready>
    void await(Ready&& ready, const char* what) {
        for (int cycle = 0;; ++cycle) {
            settle();
            if (ready()) {
                return;
            }
            if (cycle > 20) {
                throw std::runtime_error(what);
            }
            harness_.tick();
        }
    }

    VerilatedHarness<Model> harness_;
};

using AxilTop = AxilTopOf<Vstereo_axil_top>;

TEST(AxilRegisters, ResetValuesAndReadOnlyFields) {
    AxilTop top;
    EXPECT_EQ(top.read(kId), 0x53544552U);  // "STER", by hand
    EXPECT_EQ(top.read(kVersion), table::kRegmapVersion);
    EXPECT_EQ(top.read(kMaxSize), static_cast<std::uint32_t>(kConfig.width | kConfig.height << 16));
    const std::uint32_t build = top.read(kBuild);
    EXPECT_EQ(build & 0x1FFU, static_cast<std::uint32_t>(kConfig.ndisp));
    EXPECT_EQ(build >> 9 & 0x1FU, static_cast<std::uint32_t>(kConfig.window / 2));
    EXPECT_EQ(build >> 14 & 0xFFFU, static_cast<std::uint32_t>(table::kDefaultMaxMinDisp));
    EXPECT_EQ(build >> 26 & 1U, 1U);  // RUNTIME_KERNEL
    EXPECT_EQ(build >> 27 & 3U, 0U);  // COST: AD
    EXPECT_EQ(build >> 29, 0U);       // reserved
    EXPECT_EQ(top.read(kFrame), static_cast<std::uint32_t>(kConfig.width | kConfig.height << 16));
    EXPECT_EQ(top.read(kMatch),
              static_cast<std::uint32_t>(kConfig.ndisp | (kConfig.window / 2) << 16 | 1 << 24));
    EXPECT_EQ(top.read(kStage6), 0U);
    EXPECT_EQ(top.read(kThresholds), 20U);
    EXPECT_EQ(top.read(kStatus), 0U);
    // The model's default kernel for the core's window, tap by tap.
    const std::vector<std::int32_t> taps = gaussian_kernel(kConfig.window, fx::kDefaultSigma);
    for (int i = 0; i < kConfig.window; ++i) {
        EXPECT_EQ(top.read(kKernel + 4 * static_cast<std::uint32_t>(i)),
                  static_cast<std::uint32_t>(taps[static_cast<std::size_t>(i)]))
            << "tap " << i;
    }
    // Writes to read-only words change nothing; unmapped words read 0.
    top.write(kId, 0);
    top.write(kMaxSize, 0);
    EXPECT_EQ(top.read(kId), 0x53544552U);  // "STER", by hand
    EXPECT_EQ(top.read(kMaxSize), static_cast<std::uint32_t>(kConfig.width | kConfig.height << 16));
    EXPECT_EQ(top.read(0x3C), 0U);
    EXPECT_EQ(top.read(0xFC), 0U);
}

TEST(AxilRegisters, ByteStrobesAndBothOrdersOfAddressAndData) {
    AxilTop top;
    top.write(kThresholds, 0x0000'0237U, 0x1, Order::address_first);  // low byte only
    EXPECT_EQ(top.read(kThresholds), 0x37U);
    top.write(kThresholds, 0x0000'0500U, 0x2, Order::data_first);  // second byte only
    EXPECT_EQ(top.read(kThresholds), 0x0537U);
    top.write(kFrame, 0x0011'0022U, 0xF, Order::data_first);
    EXPECT_EQ(top.read(kFrame), 0x0011'0022U);
    top.write(kFrame, 0xFFFF'0033U, 0x3, Order::address_first);  // height kept
    EXPECT_EQ(top.read(kFrame), 0x0011'0033U);
    top.write(kStage6, 0xFFFF'FFFFU);  // reserved bits read 0
    EXPECT_EQ(top.read(kStage6), 0x7FFFU);
}

// Configurations written through the registers, frames under input gaps and output stalls, every
// pixel's fixed disparity, reason and certainty against the golden model.
TEST(AxilFrames, RegisterConfigurationsEqualTheModel) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    AxilTop top;
    struct Case {
        int width, height, ndisp, window, min_disp;
        bool ca, validation;
    };
    int frames = 0;
    for (const Case& c :
         {Case{64, 48, 16, 5, 0, true, false}, Case{37, 23, 12, 3, -4, true, true},
          Case{50, 30, 16, 5, 3, false, true}, Case{64, 48, 9, 1, -8, true, true}}) {
        const auto [left, right] = test::shifted_pair(c.width, c.height, 3, 3, 20, rng);
        MatchParams params{c.ndisp, c.window, c.window == 3 ? 1.0 : fx::kDefaultSigma, c.ca};
        params.min_disp = c.min_disp;
        if (c.validation) {
            params.validation = ValidationParams::all_on();
            params.validation.lr_tolerance = 1;
        }
        top.configure(c.width, c.height, params);
        EXPECT_TRUE(tb::same_validated(match_validated(left, right, params),
                                       top.frame(left, right, {0.2, 0.3, seed + frames})))
            << c.width << "x" << c.height << " ndisp " << c.ndisp << " window " << c.window;
        ++frames;
    }
    EXPECT_EQ(top.read(kFramesIn), static_cast<std::uint32_t>(frames));
    EXPECT_EQ(top.read(kFramesOut), static_cast<std::uint32_t>(frames));
    EXPECT_GT(top.read(kStalls), 0U);  // 30 % of the cycles had tready low
    EXPECT_EQ(top.read(kStatus), 0U);
}

// The census build (constant kernel, 4 labels per clock, SHIFT_ADD = 1): BUILD says so, and frames
// configured through the registers equal the model's census matcher pixel for pixel.
TEST(AxilFrames, CensusBuildReportsItsCostAndEqualsTheModel) {
    constexpr table::Params census = table::verilated("Vstereo_axil_top_census").params;
    static_assert(census.window == kConfig.window && census.cost == table::kCostCensus);
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    AxilTopOf<Vstereo_axil_top_census> top;
    const std::uint32_t build = top.read(kBuild);
    EXPECT_EQ(build & 0x1FFU, static_cast<std::uint32_t>(census.ndisp));
    EXPECT_EQ(build >> 26 & 1U, 0U);  // RUNTIME_KERNEL 0: the default kernel as constants
    EXPECT_EQ(build >> 27 & 3U, 2U);  // COST: census
    int frames = 0;
    for (const auto& [width, height, min_disp] :
         {std::tuple{64, 48, 0}, std::tuple{41, 17, -3}, std::tuple{64, 48, 5}}) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 4, 15, rng);
        MatchParams params{census.ndisp, census.window, fx::kDefaultSigma, true};
        params.cost = "census";
        params.min_disp = min_disp;
        params.validation = ValidationParams::all_on();
        top.configure(width, height, params);
        EXPECT_TRUE(tb::same_validated(match_validated(left, right, params),
                                       top.frame(left, right, {0.2, 0.2, seed + frames})))
            << width << "x" << height << " min_disp " << min_disp;
        ++frames;
    }
    EXPECT_EQ(top.read(kFramesOut), static_cast<std::uint32_t>(frames));
    EXPECT_EQ(top.read(kStatus), 0U);
}

TEST(AxilFrames, ClampedConfigurationSetsStatusAndSoftResetClearsIt) {
    std::mt19937 rng(tb::test_seed());
    AxilTop top;
    const auto [left, right] = test::shifted_pair(64, 48, 3, 2, 10, rng);
    top.write(kMatch, 0U | 2U << 16 | 1U << 24);  // ndisp 0: out of range, clamped to NDISP
    const MatchParams clamped{kConfig.ndisp, kConfig.window, fx::kDefaultSigma, true};
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, clamped),
                                   top.frame(left, right, {0.0, 0.0, 1})));
    EXPECT_EQ(top.read(kStatus), 1U << table::kStatusConfigClamped);
    top.write(kControl, 1);
    EXPECT_EQ(top.read(kStatus), 0U);
    EXPECT_EQ(top.read(kFramesIn), 0U);
    EXPECT_EQ(top.read(kFramesOut), 0U);
    // The registers survive the soft reset; a valid configuration streams cleanly again.
    EXPECT_EQ(top.read(kMatch), 0U | 2U << 16 | 1U << 24);
    top.write(kMatch, static_cast<std::uint32_t>(kConfig.ndisp) | 2U << 16 | 1U << 24);
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, clamped),
                                   top.frame(left, right, {0.1, 0.1, 2})));
    EXPECT_EQ(top.read(kStatus), 0U);
    EXPECT_EQ(top.read(kFramesIn), 1U);
}

// ---- The C driver (drivers/c) through a register-access shim ---------------------------------
// stereo_device's read and write, each one AXI4-Lite transaction on the Verilated wrapper.
std::uint32_t shim_read(void* context, std::uint32_t offset) {
    return static_cast<AxilTop*>(context)->read(offset);
}
void shim_write(void* context, std::uint32_t offset, std::uint32_t value) {
    static_cast<AxilTop*>(context)->write(offset, value);
}

// A pair in three bands of rows with true disparities -1, 2 and 5 (right(x) = left(x + d)).
io::ImagePair banded_pair(int width, int height, std::mt19937& rng) {
    io::ImagePair pair{test::random_image(width, height, 3, rng), Image(width, height, 3)};
    for (const int d : {-1, 2, 5}) {
        const Image shifted = test::shifted_copy(pair.left, d, 10, rng);
        const int band = d == -1 ? 0 : d == 2 ? 1 : 2;
        for (int y = band * height / 3; y < (band + 1) * height / 3; ++y) {
            for (int x = 0; x < width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    pair.right.at(x, y, c) = shifted.at(x, y, c);
                }
            }
        }
    }
    return pair;
}

// The driver probes the build, configures a frame (a 3x3 kernel centred in the 5x5 core, a
// negative minimum disparity, every stage-6 check and sub-pixel on), the frame streams under
// gaps and stalls and equals the golden model pixel for pixel; the driver's wait and counters
// see the frame, and its soft reset clears them.
TEST(CDriver, ConfiguresAndRunsAFrameEqualToTheModel) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    AxilTop top;
    const stereo_device dev{&shim_read, &shim_write, &top};
    stereo_build build{};
    ASSERT_EQ(stereo_probe(&dev, &build), STEREO_OK);
    tb::expect_reported_build(kConfig, build.version, build.max_width, build.max_height,
                              build.ndisp, build.window, build.max_min_disp);
    EXPECT_EQ(build.runtime_kernel, 1);
    EXPECT_EQ(build.cost, STEREO_COST_AD);

    const auto [left, right] = banded_pair(60, 45, rng);
    MatchParams params{12, 3, 1.0, true};
    params.min_disp = -2;
    params.validation = ValidationParams::all_on();
    params.validation.uniqueness_ratio = 10;
    params.validation.lr_tolerance = 1;
    const std::vector<std::int32_t> taps = gaussian_kernel(params.window, params.sigma);
    const std::vector<std::uint16_t> kernel(taps.begin(), taps.end());
    const stereo_config config{left.width,
                               left.height,
                               params.ndisp,
                               params.window,
                               1,
                               params.min_disp,
                               1,
                               params.validation.uniqueness_ratio,
                               1,
                               params.validation.lr_tolerance,
                               1,
                               kernel.data()};
    ASSERT_EQ(stereo_configure(&dev, &build, &config), STEREO_OK);
    const ValidatedDisparity expected = match_validated(left, right, params);
    EXPECT_TRUE(tb::same_validated(expected, top.frame(left, right, {0.2, 0.3, seed})));
    // The map exercises the configuration: every band's disparity, sub-pixel values, rejects.
    std::set<int> labels;
    int valid = 0;
    int rejected = 0;
    for (std::size_t i = 0; i < expected.fixed.size(); ++i) {
        valid += expected.valid(i) ? 1 : 0;
        rejected += expected.reason[i] > fx::kReasonBorder ? 1 : 0;
        if (expected.valid(i)) {
            labels.insert(expected.fixed[i]);
        }
    }
    EXPECT_GT(valid, static_cast<int>(expected.fixed.size()) / 2);
    EXPECT_GT(labels.size(), 8U);
    for (const int band : {-16, 32, 80}) {  // -1, 2 and 5 pixels, x 16
        EXPECT_NE(labels.lower_bound(band - 8), labels.upper_bound(band + 8)) << band;
    }
    EXPECT_GT(rejected, 0);

    ASSERT_EQ(stereo_wait_frames(&dev, 1, 4), STEREO_OK);
    stereo_counters counters{};
    stereo_read_counters(&dev, &counters);
    EXPECT_EQ(counters.status, 0U);
    EXPECT_EQ(counters.frames_in, 1U);
    EXPECT_EQ(counters.frames_out, 1U);
    EXPECT_GT(counters.stalls, 0U);  // 30 % of the cycles had tready low
    EXPECT_EQ(stereo_wait_frames(&dev, 2, 4), STEREO_E_TIMEOUT);
    stereo_soft_reset(&dev);
    stereo_read_counters(&dev, &counters);
    EXPECT_EQ(counters.frames_in, 0U);
    EXPECT_EQ(counters.frames_out, 0U);
    EXPECT_EQ(counters.stalls, 0U);
}

// The driver refuses what the build cannot take before writing anything, and a device without
// the ID.
TEST(CDriver, RefusesImpossibleConfigurationsWithoutWriting) {
    AxilTop top;
    const stereo_device dev{&shim_read, &shim_write, &top};
    stereo_build build{};
    ASSERT_EQ(stereo_probe(&dev, &build), STEREO_OK);
    const std::uint16_t taps3[] = {64, 128, 64};
    const std::uint16_t bad_sum[] = {64, 128, 65};
    const stereo_config good{32, 24, 8, 3, 1, -2, 0, 20, 0, 0, 0, taps3};
    ASSERT_EQ(stereo_configure(&dev, &build, &good), STEREO_OK);
    const std::uint32_t frame = top.read(STEREO_REG_FRAME);
    const std::uint32_t match = top.read(STEREO_REG_MATCH);
    const std::uint32_t stage6 = top.read(STEREO_REG_STAGE6);
    struct Bad {
        stereo_config config;
        int code;
    };
    const auto with = [&good](auto change) {
        stereo_config config = good;
        change(config);
        return config;
    };
    for (const Bad& bad : {
             Bad{with([&](stereo_config& c) { c.width = kConfig.width + 1; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.height = 0; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.ndisp = kConfig.ndisp + 1; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.window = kConfig.window + 2; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.window = 2; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.min_disp = -table::kDefaultMaxMinDisp - 1; }),
                 STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.uniqueness = 256; }), STEREO_E_RANGE},
             Bad{with([&](stereo_config& c) { c.kernel = bad_sum; }), STEREO_E_KERNEL},
         }) {
        EXPECT_EQ(stereo_configure(&dev, &build, &bad.config), bad.code)
            << stereo_error_text(bad.code);
    }
    // A constant-kernel build takes no taps.
    stereo_build constant = build;
    constant.runtime_kernel = 0;
    EXPECT_EQ(stereo_configure(&dev, &constant, &good), STEREO_E_KERNEL);
    EXPECT_EQ(top.read(STEREO_REG_FRAME), frame);
    EXPECT_EQ(top.read(STEREO_REG_MATCH), match);
    EXPECT_EQ(top.read(STEREO_REG_STAGE6), stage6);
    // Something that is not the core.
    const stereo_device nothing{[](void*, std::uint32_t) -> std::uint32_t { return 0; },
                                [](void*, std::uint32_t, std::uint32_t) {}, nullptr};
    EXPECT_EQ(stereo_probe(&nothing, &build), STEREO_E_ID);
}

}  // namespace
}  // namespace stereo::sim
