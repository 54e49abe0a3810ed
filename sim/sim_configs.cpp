// The Verilated stereo_top configurations behind the TopSim interface.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string_view>
#include <utility>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_synth_top_census_ndisp8_lanes2.h"
#include "Vstereo_synth_top_ice40_ndisp1.h"
#include "Vstereo_synth_top_ice40_ndisp4_lanes1.h"
#include "Vstereo_top_asw_ad_lanes4.h"
#include "Vstereo_top_asw_census.h"
#include "Vstereo_top_asw_census_lanes4.h"
#include "Vstereo_top_census.h"
#include "Vstereo_top_census_lanes4.h"
#include "Vstereo_top_census_recompute.h"
#include "Vstereo_top_census_recompute_lanes4.h"
#include "Vstereo_top_lanes1.h"
#include "Vstereo_top_lanes4.h"
#include "Vstereo_top_lcdm.h"
#include "Vstereo_top_lcdm_lanes4.h"
#include "Vstereo_top_lean_lanes4.h"
#include "Vstereo_top_ndisp1.h"
#include "Vstereo_top_ndisp2_lanes1.h"
#include "Vstereo_top_ndisp8_lanes2.h"
#include "Vstereo_top_small.h"
#include "axis_driver.hpp"
#include "port_bits.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_top_sim.hpp"
#include "verilated_harness.hpp"
#ifdef STEREO_COSIM_FULL
#include "Vstereo_top_full.h"
#endif
#ifdef STEREO_COSIM_FULL_CENSUS
#include "Vstereo_top_full_census_lean.h"
#endif
#ifdef STEREO_COSIM_FULL_ASW
#include "Vstereo_top_full_asw.h"
#endif
#ifdef STEREO_COSIM_USER
#include "Vstereo_top_user.h"
#endif

namespace stereo::sim {
namespace {

template <typename Model>
class VerilatedTop final : public TopSim {
  public:
    explicit VerilatedTop(TopConfig config)
        : config_(std::move(config)), harness_("stereo_top"), model_(&harness_.model()) {
        idle_inputs();
        model_->clk = 0;
        model_->eval();
    }

    const TopConfig& config() const override { return config_; }

    void reset() override {
        idle_inputs();
        harness_.pulse_reset();
    }

    void set_params(const CoreParams& params) override {
        const PortValues ports = port_values(config_, params);
        model_->cfg_width = ports.width;
        model_->cfg_height = ports.height;
        model_->cfg_ndisp = ports.ndisp;
        model_->cfg_use_ca = ports.use_ca;
        model_->cfg_min_disp = ports.min_disp;
        model_->cfg_uniqueness_en = ports.uniqueness_en;
        model_->cfg_uniqueness = ports.uniqueness;
        model_->cfg_lr_en = ports.lr_en;
        model_->cfg_lr_tolerance = ports.lr_tolerance;
        model_->cfg_subpixel_en = ports.subpixel_en;
        if constexpr (requires(Model & m) { m.cfg_kernel; }) {
            model_->cfg_radius = ports.radius;
            for (std::size_t i = 0; i < ports.kernel.size(); ++i) {
                put_bits(model_->cfg_kernel, static_cast<int>(i) * table::kTapBits, table::kTapBits,
                         static_cast<std::uint64_t>(ports.kernel[i]));
            }
        } else {
            // stereo_synth_top: the default kernel of its window is a constant and the radius is
            // WINDOW/2, so only that matching can be compared.
            if (params.match.window != config_.window ||
                ports.kernel != centred_kernel(MatchParams{params.match.ndisp, config_.window,
                                                           fx::kDefaultSigma, true},
                                               config_.window)) {
                throw std::invalid_argument(
                    "co-simulation model '" + config_.name + "' has the constant default " +
                    std::to_string(config_.window) + "x" + std::to_string(config_.window) +
                    " kernel (sigma " + std::to_string(fx::kDefaultSigma) + "); asked for window " +
                    std::to_string(params.match.window));
            }
        }
    }

    StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                        const Traffic& traffic, std::uint64_t max_cycles) override {
        StreamResult result = stream_axis(harness_, beats, expected_outputs, traffic, max_cycles);
        idle_inputs();
        result.status = model_->status;
        return result;
    }

    void trace_to(const std::string& path) override {
        check_trace_path(path);
        harness_.trace_to(path);
    }

  private:
    void idle_inputs() {
        model_->s_axis_tvalid = 0;
        model_->s_axis_tdata = 0;
        model_->s_axis_tlast = 0;
        model_->s_axis_tuser = 0;
        model_->m_axis_tready = 0;
    }

    TopConfig config_;
    VerilatedHarness<Model> harness_;
    Model* model_;
};

// A stereo_top configuration of the stage table (stage_table.hpp).
// The stereo_top or stereo_synth_top build of that Verilator prefix, under its cosim name.
// The prefixes Verilated with FST tracing, "A,B,...", from sim/CMakeLists.txt.
#ifndef STEREO_TRACED_PREFIXES
#define STEREO_TRACED_PREFIXES ""
#endif
bool traced(std::string_view prefix) {
    const std::string_view list = STEREO_TRACED_PREFIXES;
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        if (list.substr(start, end - start) == prefix) {
            return true;
        }
        start = end + 1;
    }
    return false;
}

TopConfig top_config(std::string_view prefix) {
    const table::VerilatedConfig& config = table::verilated(prefix);
    const table::Params& p = config.params;
    return {std::string(config.cosim_name),
            p.width,
            p.height,
            p.ndisp,
            p.window,
            p.max_min_disp == table::kUnset ? table::kDefaultMaxMinDisp : p.max_min_disp,
            p.lanes == table::kUnset ? p.ndisp : p.lanes,
            p.cost == table::kUnset ? table::kCostAd : p.cost,
            p.asw != table::kUnset && p.asw != 0,
            traced(prefix)};
}

std::vector<TopConfig> top_configs(std::initializer_list<std::string_view> prefixes) {
    std::vector<TopConfig> configs;
    for (const std::string_view prefix : prefixes) {
        configs.push_back(top_config(prefix));
    }
    return configs;
}

}  // namespace

const std::vector<TopConfig>& built_top_configs() {
    static const std::vector<TopConfig> configs = [] {
        std::vector<TopConfig> list = {
            top_config("Vstereo_top_small"),
#ifdef STEREO_COSIM_FULL
            top_config("Vstereo_top_full"),
#endif
#ifdef STEREO_COSIM_USER
            // -DSTEREO_COSIM_USER (sim/cosim_user.cmake)
            TopConfig{"user", STEREO_COSIM_USER_WIDTH, STEREO_COSIM_USER_HEIGHT,
                      STEREO_COSIM_USER_NDISP, STEREO_COSIM_USER_WINDOW,
                      STEREO_COSIM_USER_MAX_MIN_DISP, STEREO_COSIM_USER_LANES},
#endif
        };
        // Smallest first (covering_config takes the first that covers a run): by the work of a
        // frame, pixels times labels, then by the window.
        std::stable_sort(list.begin(), list.end(), [](const TopConfig& a, const TopConfig& b) {
            const auto work = [](const TopConfig& c) {
                return std::int64_t{c.width} * c.height * c.ndisp;
            };
            return work(a) != work(b) ? work(a) < work(b) : a.window < b.window;
        });
        return list;
    }();
    return configs;
}

const TopConfig& lcdm_top_config() {
    static const TopConfig config = top_config("Vstereo_top_lcdm");
    return config;
}

const TopConfig& lcdm_lanes_top_config() {
    static const TopConfig config = top_config("Vstereo_top_lcdm_lanes4");
    return config;
}

const TopConfig& census_top_config() {
    static const TopConfig config = top_config("Vstereo_top_census");
    return config;
}

const TopConfig& census_lanes_top_config() {
    static const TopConfig config = top_config("Vstereo_top_census_lanes4");
    return config;
}

const std::vector<TopConfig>& census_recompute_top_configs() {
    static const std::vector<TopConfig> configs = {
        top_config("Vstereo_top_census_recompute"),
        top_config("Vstereo_top_census_recompute_lanes4"),
#ifdef STEREO_COSIM_FULL_CENSUS
        top_config("Vstereo_top_full_census_lean"),
#endif
    };
    return configs;
}

const std::vector<TopConfig>& asw_top_configs() {
    static const std::vector<TopConfig> configs = top_configs({
        "Vstereo_top_asw_census",
        "Vstereo_top_asw_census_lanes4",
        "Vstereo_top_asw_ad_lanes4",
#ifdef STEREO_COSIM_FULL_ASW
        "Vstereo_top_full_asw",
#endif
    });
    return configs;
}

namespace {

std::string model_cost_name_of(int hardware_code) {
    for (const catalogue::CostRow& row : catalogue::kCosts) {
        if (row.hardware_code == hardware_code) {
            return std::string(row.name);
        }
    }
    return "?";
}

}  // namespace

const TopConfig& asw_top_config(int width, int height, const MatchParams& params,
                                const asw::Params& weights) {
    asw::check_hardware_variant(weights, "the ASW core (engine rtl)", false);
    const TopConfig* best = nullptr;
    for (const TopConfig& config : asw_top_configs()) {
        const bool fits = config.cost == catalogue::cost(params.cost).hardware_code &&
                          config.window == weights.diameter && width <= config.width &&
                          height <= config.height && params.ndisp <= config.ndisp &&
                          std::abs(params.min_disp) <= config.max_min_disp;
        if (fits && (best == nullptr || config.lanes > best->lanes)) {
            best = &config;
        }
    }
    if (best == nullptr) {
        std::string built;
        for (const TopConfig& config : asw_top_configs()) {
            built += (built.empty() ? "" : ", ") + config.name + " (" +
                     model_cost_name_of(config.cost) + ", diameter " +
                     std::to_string(config.window) + ", " + std::to_string(config.width) + "x" +
                     std::to_string(config.height) + ", ndisp " + std::to_string(config.ndisp) +
                     ")";
        }
        throw std::invalid_argument("no Verilated ASW core runs cost " + params.cost +
                                    ", diameter " + std::to_string(weights.diameter) + " at " +
                                    std::to_string(width) + "x" + std::to_string(height) +
                                    " ndisp " + std::to_string(params.ndisp) + "; built: " + built);
    }
    return *best;
}

const std::vector<TopConfig>& lanes_top_configs() {
    static const std::vector<TopConfig> configs =
        top_configs({"Vstereo_top_lanes4", "Vstereo_top_lanes1", "Vstereo_top_ndisp8_lanes2",
                     "Vstereo_top_ndisp2_lanes1", "Vstereo_top_ndisp1", "Vstereo_top_lean_lanes4"});
    return configs;
}

const std::vector<TopConfig>& fpga_top_configs() {
    static const std::vector<TopConfig> configs =
        top_configs({"Vstereo_synth_top_ice40_ndisp1", "Vstereo_synth_top_ice40_ndisp4_lanes1",
                     "Vstereo_synth_top_census_ndisp8_lanes2"});
    return configs;
}

std::vector<const TopConfig*> all_top_configs() {
    std::vector<const TopConfig*> all;
    for (const auto* list : {&built_top_configs(), &lanes_top_configs(), &fpga_top_configs(),
                             &census_recompute_top_configs(), &asw_top_configs()}) {
        for (const TopConfig& config : *list) {
            all.push_back(&config);
        }
    }
    for (const TopConfig* config : {&lcdm_top_config(), &lcdm_lanes_top_config(),
                                    &census_top_config(), &census_lanes_top_config()}) {
        all.push_back(config);
    }
    return all;
}

const TopConfig& top_config_named(const std::string& name) {
    for (const TopConfig* config : all_top_configs()) {
        if (config->name == name) {
            return *config;
        }
    }
    throw std::invalid_argument("no co-simulation model named '" + name + "' was built");
}

namespace {

bool covers(const TopConfig& config, int width, int height, int ndisp, int window, int min_disp) {
    return width <= config.width && height <= config.height && ndisp <= config.ndisp &&
           window <= config.window && min_disp <= config.max_min_disp &&
           -min_disp <= config.max_min_disp;
}

}  // namespace

const TopConfig& largest_config(const std::string& cost) {
    switch (catalogue::cost(cost).id) {
        case catalogue::Cost::lcdm:
            return lcdm_top_config();
        case catalogue::Cost::census:
            return census_top_config();
        case catalogue::Cost::ad:
            return built_top_configs().back();
        case catalogue::Cost::zncc:
            break;
    }
    throw std::invalid_argument("no Verilated configuration has the cost " + cost);
}

const TopConfig* covering_config(int width, int height, int ndisp, int window, int min_disp,
                                 const std::string& cost) {
    const catalogue::Cost id = catalogue::cost(cost).id;
    if (id == catalogue::Cost::lcdm || id == catalogue::Cost::census) {
        const TopConfig& config = largest_config(cost);
        if (covers(config, width, height, ndisp, window, min_disp)) {
            return &config;
        }
        if (id == catalogue::Cost::census) {  // the larger census builds (the small lean ones are
                                              // not larger)
            for (const TopConfig& lean : census_recompute_top_configs()) {
                if (lean.width > config.width &&
                    covers(lean, width, height, ndisp, window, min_disp)) {
                    return &lean;
                }
            }
        }
        return nullptr;
    }
    for (const TopConfig& config : built_top_configs()) {
        if (covers(config, width, height, ndisp, window, min_disp)) {
            return &config;
        }
    }
    return nullptr;
}

void check_trace_path(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (extension == ".fst") {
        return;
    }
    if (extension == ".vcd") {
        throw std::invalid_argument(
            "--trace " + path +
            ": VCD is not built in (the co-simulation models trace FST only); write a .fst and "
            "convert it with `fst2vcd TRACE.fst > TRACE.vcd` (Debian gtkwave) if a VCD is needed");
    }
    throw std::invalid_argument("--trace " + path +
                                ": the trace format is chosen by the extension and only .fst "
                                "(FST, GTKWave's format) is built in");
}

namespace {

template <class Model>
std::unique_ptr<TopSim> make_verilated(const TopConfig& config) {
    return std::make_unique<VerilatedTop<Model>>(config);
}

// The Verilated class behind each configuration name (one per kVerilatedConfigs entry of
// stereo_top that this library links).
using TopFactory = std::unique_ptr<TopSim> (*)(const TopConfig&);
const std::pair<std::string_view, TopFactory> kFactories[] = {
    {"small", &make_verilated<Vstereo_top_small>},
    {"small-lcdm", &make_verilated<Vstereo_top_lcdm>},
    {"lcdm-lanes4", &make_verilated<Vstereo_top_lcdm_lanes4>},
    {"small-census", &make_verilated<Vstereo_top_census>},
    {"census-lanes4", &make_verilated<Vstereo_top_census_lanes4>},
    {"census-recompute", &make_verilated<Vstereo_top_census_recompute>},
    {"census-recompute-lanes4", &make_verilated<Vstereo_top_census_recompute_lanes4>},
    {"lanes4", &make_verilated<Vstereo_top_lanes4>},
    {"lanes1", &make_verilated<Vstereo_top_lanes1>},
    {"ndisp8-lanes2", &make_verilated<Vstereo_top_ndisp8_lanes2>},
    {"ndisp2-lanes1", &make_verilated<Vstereo_top_ndisp2_lanes1>},
    {"ndisp1", &make_verilated<Vstereo_top_ndisp1>},
    {"lean-lanes4", &make_verilated<Vstereo_top_lean_lanes4>},
    {"asw-census", &make_verilated<Vstereo_top_asw_census>},
    {"asw-census-lanes4", &make_verilated<Vstereo_top_asw_census_lanes4>},
    {"asw-ad-lanes4", &make_verilated<Vstereo_top_asw_ad_lanes4>},
    {"ice40-ndisp1", &make_verilated<Vstereo_synth_top_ice40_ndisp1>},
    {"ice40-ndisp4-lanes1", &make_verilated<Vstereo_synth_top_ice40_ndisp4_lanes1>},
    {"fpga-census-ndisp8-lanes2", &make_verilated<Vstereo_synth_top_census_ndisp8_lanes2>},
#ifdef STEREO_COSIM_FULL
    {"full", &make_verilated<Vstereo_top_full>},
#endif
#ifdef STEREO_COSIM_FULL_CENSUS
    {"full-census-lean", &make_verilated<Vstereo_top_full_census_lean>},
#endif
#ifdef STEREO_COSIM_FULL_ASW
    {"full-asw", &make_verilated<Vstereo_top_full_asw>},
#endif
#ifdef STEREO_COSIM_USER
    {"user", &make_verilated<Vstereo_top_user>},
#endif
};

}  // namespace

std::unique_ptr<TopSim> make_top_sim(const TopConfig& config) {
    for (const auto& [name, factory] : kFactories) {
        if (config.name == name) {
            return factory(config);
        }
    }
    throw std::invalid_argument("no co-simulation model named '" + config.name + "' was built");
}

std::vector<InputBeat> frame_beats(const Image& left, const Image& right) {
    check_pair(left, right);
    std::vector<InputBeat> beats;
    beats.reserve(static_cast<std::size_t>(left.width) * left.height);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            beats.push_back(
                {table::in_beat_data(left, right, x, y), x == left.width - 1, x == 0 && y == 0});
        }
    }
    return beats;
}

ValidatedDisparity assemble_validated(const std::vector<OutputBeat>& beats, std::size_t first,
                                      int width, int height) {
    ValidatedDisparity out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t n = first + static_cast<std::size_t>(y) * width + x;
            if (n >= beats.size()) {
                throw std::runtime_error("output ended early at pixel (" + std::to_string(x) +
                                         ", " + std::to_string(y) + ")");
            }
            const OutputBeat& beat = beats[n];
            if (beat.user != (x == 0 && y == 0) || beat.last != (x == width - 1)) {
                throw std::runtime_error("wrong tuser/tlast framing at output pixel (" +
                                         std::to_string(x) + ", " + std::to_string(y) + ")");
            }
            if (get_bits(beat.data, table::kOutReasonLsb + fx::kReasonBits, table::kOutPadBits) !=
                0) {
                throw std::runtime_error("non-zero padding bits at output pixel (" +
                                         std::to_string(x) + ", " + std::to_string(y) + ")");
            }
            const std::size_t i = out.index(x, y);
            out.fixed[i] = static_cast<std::int16_t>(static_cast<std::uint16_t>(
                get_bits(beat.data, table::kOutFixedLsb, fx::kFixedDisparityBits)));
            out.reason[i] = static_cast<std::uint8_t>(
                get_bits(beat.data, table::kOutReasonLsb, fx::kReasonBits));
            out.certainty[i] = static_cast<std::uint8_t>(
                get_bits(beat.data, table::kOutCertaintyLsb, table::kOutCertaintyBits));
        }
    }
    return out;
}

DisparityMap assemble_frame(const std::vector<OutputBeat>& beats, std::size_t first, int width,
                            int height) {
    return to_label_map(assemble_validated(beats, first, width, height));
}

PortValues port_values(const TopConfig& config, const CoreParams& params) {
    PortValues ports;
    ports.width = static_cast<std::uint16_t>(params.width);
    ports.height = static_cast<std::uint16_t>(params.height);
    ports.ndisp = static_cast<std::uint16_t>(params.match.ndisp);
    ports.use_ca = params.match.use_ca ? 1 : 0;
    // Two's complement in the port's kCfgMinDispBits.
    ports.min_disp = static_cast<std::uint16_t>(static_cast<unsigned>(params.match.min_disp) &
                                                ((1U << table::kCfgMinDispBits) - 1));
    const ValidationParams& v = params.match.validation;
    ports.uniqueness_en = v.uniqueness ? 1 : 0;
    ports.uniqueness = static_cast<std::uint8_t>(v.uniqueness_ratio);
    ports.lr_en = v.left_right ? 1 : 0;
    ports.lr_tolerance = static_cast<std::uint8_t>(v.lr_tolerance);
    ports.subpixel_en = v.subpixel ? 1 : 0;
    ports.radius = static_cast<std::uint8_t>(params.match.window / 2);
    ports.kernel = centred_kernel(params.match, config.window);
    return ports;
}

std::vector<std::int32_t> centred_kernel(const MatchParams& params, int window) {
    if (params.window > window) {
        throw std::invalid_argument("window " + std::to_string(params.window) +
                                    " exceeds the core's " + std::to_string(window));
    }
    const auto taps = gaussian_kernel(params.window, params.sigma);
    std::vector<std::int32_t> centred(static_cast<std::size_t>(window), 0);
    const int offset = (window - params.window) / 2;
    std::copy(taps.begin(), taps.end(), centred.begin() + offset);
    return centred;
}

}  // namespace stereo::sim
