// The catalogue (stereo/catalogue.hpp) against everything that must agree with it: each cost's
// factory and naive reference, the hardware codes in the generated fx_pkg.sv and
// stage_table.json, the costs each engine and method really accepts, the registry's methods and
// engines, what each method's run really produces, and the one default run on every engine.
// A row that says one thing while an engine, a binding or a generated file does another fails
// here (issue 44). The CLI and Python sides of the default run are tested in tests/cli and
// python/tests (test_default_map_is_the_same_through_cli_python_and_cosim).
#include <fstream>
#include <iterator>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/matcher.hpp"
#include "stereo/quad.hpp"
#include "stereo/reference.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using catalogue::CostUse;

std::string source_file(const std::string& relative) {
    std::ifstream in(std::string(STEREO_SOURCE_DIR) + "/" + relative);
    if (!in) {
        throw std::runtime_error("cannot read " + relative);
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

MatcherRegistry every_engine() {
    MatcherRegistry registry;
    register_model_matchers(registry);
    hls::register_matchers(registry);
    return registry;
}

// The default run of (method, engine), made small enough for the pair.
MatchConfig small_config(const std::string& method, const std::string& engine) {
    MatchConfig config = defaults::match_config(method, engine);
    config.pipeline.ndisp = 8;
    config.pipeline.window = 5;
    config.vrange = 8;
    config.asw.diameter = 9;
    // The hardware engines compute the separable variant only (the HLS ASW core, issue 46).
    config.asw.separable = engine == "hls" || engine == "rtl";
    config.speckle.max_size = std::min(config.speckle.max_size, 10);
    return config;
}

// Every test of the catalogue has the registry of every engine and a small colour pair shifted
// by 3 pixels, which every method and engine of the registry can run with small_config().
class Catalogue : public ::testing::Test {
  protected:
    const io::ImagePair pair = test::seeded_shifted_pair(96, 80, 3, 3, 2);
    const MatcherRegistry registry = every_engine();
};

TEST_F(Catalogue, NamesAreUniqueAndFindTheirRows) {
    std::set<std::string> names;
    for (const auto& row : catalogue::kCosts) {
        EXPECT_TRUE(names.insert(std::string(row.name)).second) << row.name;
        EXPECT_EQ(&catalogue::cost(row.name), &row);
        EXPECT_EQ(&catalogue::cost(row.id), &row);
        EXPECT_FALSE(row.summary.empty());
    }
    for (const auto& row : catalogue::kMethods) {
        EXPECT_TRUE(names.insert(std::string(row.name)).second) << row.name;
        EXPECT_EQ(&catalogue::method(row.name), &row);
    }
    EXPECT_THROW(catalogue::cost("sad"), std::invalid_argument);
    EXPECT_THROW(catalogue::method("sgm"), std::invalid_argument);
    EXPECT_THROW(catalogue::engine("gpu"), std::invalid_argument);
    EXPECT_EQ(cost_names(), catalogue::cost_names());
}

TEST_F(Catalogue, EveryCostHasItsFactoryAndNaiveReference) {
    for (const auto& row : catalogue::kCosts) {
        const auto cost = make_cost(row.name);
        ASSERT_NE(cost, nullptr) << row.name;
        // The plug-in and the naive reference compute the same volume.
        EXPECT_EQ(cost_volume(*cost, pair.left, pair.right, 8),
                  naive::cost_volume(std::string(row.name), pair.left, pair.right, 8, 0))
            << row.name;
    }
}

TEST_F(Catalogue, HardwareCodesAreTheGeneratedOnes) {
    // fx_pkg.sv and stage_table.json are generated from the catalogue; a stale or hand-edited
    // file fails here.
    const std::string json = source_file("scripts/stage_table.json");
    // The items of fx_pkg::cost_e, stereo_top's COST type.
    const std::string package_text = source_file("rtl/fx_pkg.sv");
    std::smatch cost_type;
    ASSERT_TRUE(std::regex_search(package_text, cost_type,
                                  std::regex("typedef enum int \\{([^}]*)\\} cost_e;")));
    const std::string cost_items = cost_type[1];
    int hardware = 0;
    for (const auto& row : catalogue::kCosts) {
        std::string upper(row.name);
        for (char& c : upper) {
            c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        }
        const std::regex sv("\\bCOST_" + upper + " = (\\d+)\\b");
        const std::regex entry("\"name\": \"" + std::string(row.name) + "\", \"code\": (\\d+)");
        std::smatch found;
        if (row.hardware_code == catalogue::kNoHardware) {
            EXPECT_FALSE(std::regex_search(cost_items, found, sv)) << row.name;
            EXPECT_FALSE(std::regex_search(json, found, entry)) << row.name;
            continue;
        }
        ++hardware;
        ASSERT_TRUE(std::regex_search(cost_items, found, sv)) << row.name;
        EXPECT_EQ(std::stoi(found[1]), row.hardware_code) << row.name;
        ASSERT_TRUE(std::regex_search(json, found, entry)) << row.name;
        EXPECT_EQ(std::stoi(found[1]), row.hardware_code) << row.name;
    }
    EXPECT_EQ(hardware, table::kCostCount);
    // ... and nothing else: one item per hardware row.
    const std::regex item("\\bCOST_\\w+ = \\d+");
    EXPECT_EQ(std::distance(std::sregex_iterator(cost_items.begin(), cost_items.end(), item),
                            std::sregex_iterator()),
              table::kCostCount);
    EXPECT_EQ(table::kCostCensus, catalogue::cost(catalogue::Cost::census).hardware_code);
}

TEST_F(Catalogue, EachEngineAndMethodTakesExactlyItsCosts) {
    for (const auto& row : catalogue::kCosts) {
        const std::string name(row.name);
        SCOPED_TRACE(name);
        // The hierarchical search and the vertical pair: the pixel-pair costs.
        hierarchical::Params levels;
        levels.ndisp = 8;
        levels.cost = name;
        if (row.pixel_pair) {
            EXPECT_NO_THROW(hierarchical::validate(levels, 96, 80));
        } else {
            EXPECT_THROW(hierarchical::validate(levels, 96, 80), std::invalid_argument);
        }
        MatchParams params{8, 5};
        params.cost = name;
        if (row.pixel_pair) {
            EXPECT_NO_THROW(quad::validate_pair(quad::Pair::vertical, params, 96, 80));
        } else {
            EXPECT_THROW(quad::validate_pair(quad::Pair::vertical, params, 96, 80),
                         std::invalid_argument);
        }
        // Where the row says the 2-D methods take the cost, they compute it: a cost other than AD
        // gives another map on this textured pair (an engine that fell back to AD would not).
        if (row.pixel_pair) {
            for (const std::string method : {"hierarchical", "vertical"}) {
                MatchConfig config = small_config(method, "model");
                config.pipeline.cost = name;
                const MatchResult with_cost =
                    registry.create(method, "model", config)->compute(pair.left, pair.right);
                config.pipeline.cost = "ad";
                const MatchResult with_ad =
                    registry.create(method, "model", config)->compute(pair.left, pair.right);
                // The validated output's sub-pixel disparities where there is one: on this clean
                // pair both costs may find the same integer labels everywhere.
                const bool same = with_cost.validated.fixed.empty()
                                      ? with_cost.disparity == with_ad.disparity
                                      : with_cost.validated == with_ad.validated;
                EXPECT_EQ(same, row.id == catalogue::Cost::ad) << method;
                const DisparityMap& map = with_cost.disparity;
                // ... and by its definition along that direction: the naive reference agrees (the
                // vertical pair's; the hierarchical one is slow here and has its own tests).
                if (method != "vertical") {
                    continue;
                }
                config.pipeline.cost = name;
                EXPECT_EQ(registry.create(method, "naive", config)
                              ->compute(pair.left, pair.right)
                              .disparity,
                          map)
                    << method;
            }
        }
        // The double-precision engine and the HLS kernels, run for real.
        for (const auto& [engine, use] :
             {std::pair{"float", CostUse::floating}, std::pair{"hls", CostUse::hardware}}) {
            MatchConfig config = small_config("pipeline", engine);
            config.pipeline.cost = name;
            const auto run = [&] {
                registry.create("pipeline", engine, config)->compute(pair.left, pair.right);
            };
            if (catalogue::usable(row, use)) {
                EXPECT_NO_THROW(run()) << engine;
            } else {
                EXPECT_THROW(run(), std::invalid_argument) << engine;
            }
        }
    }
}

TEST_F(Catalogue, TheRegistryHasEveryMethodAndEngineOfTheCatalogueAndNoOther) {
    const auto methods = registry.methods();
    const auto catalogue_methods = catalogue::method_names();
    EXPECT_EQ(std::set<std::string>(methods.begin(), methods.end()),
              std::set<std::string>(catalogue_methods.begin(), catalogue_methods.end()));
    std::set<std::string> engines;
    for (const auto& entry : registry.entries()) {
        engines.insert(entry.engine);
    }
    // rtl registers in the simulation library, not linked here.
    engines.insert("rtl");
    const auto catalogue_engines = catalogue::engine_names();
    EXPECT_EQ(engines, std::set<std::string>(catalogue_engines.begin(), catalogue_engines.end()));
    // A matcher outside the catalogue cannot be registered.
    MatcherRegistry other;
    EXPECT_THROW(other.add({"sgm", "model", "", {}}), std::logic_error);
}

TEST_F(Catalogue, MethodRowsSayWhatTheMethodsProduce) {
    for (const auto& row : catalogue::kMethods) {
        const std::string method(row.name);
        SCOPED_TRACE(method);
        const MatchResult result = registry.create(method, "model", small_config(method, "model"))
                                       ->compute(pair.left, pair.right);
        EXPECT_EQ(!result.validated.fixed.empty(), row.validated_output);
        EXPECT_TRUE(row.validated_output || !row.stage6);
        EXPECT_EQ(!result.vertical.empty(), row.two_d);
        // The default cost is census exactly where the row says so.
        EXPECT_EQ(defaults::match_config(method, "model").pipeline.cost,
                  row.census_default ? "census" : "ad");
        if (!row.takes_cost) {
            MatchConfig config = small_config(method, "model");
            config.pipeline.cost = "census";
            EXPECT_THROW(registry.create(method, "model", config)->compute(pair.left, pair.right),
                         std::invalid_argument);
        }
    }
}

TEST_F(Catalogue, TheDefaultRunRunsOnEveryEngine) {
    for (const auto& entry : registry.entries()) {
        SCOPED_TRACE(entry.method + "/" + entry.engine);
        const MatchConfig config = small_config(entry.method, entry.engine);
        const catalogue::EngineRow& engine = catalogue::engine(entry.engine);
        EXPECT_TRUE(catalogue::usable(catalogue::cost(config.pipeline.cost), engine.costs));
        EXPECT_EQ(config.pipeline.validation.subpixel,
                  catalogue::method(entry.method).stage6 && engine.stage6);
        EXPECT_NO_THROW(entry.create(config)->compute(pair.left, pair.right));
    }
}

TEST_F(Catalogue, DefaultsFollowTheCostRows) {
    for (const auto& row : catalogue::kCosts) {
        const auto chosen = defaults::validation_for(row.name);
        EXPECT_EQ(chosen.uniqueness, row.validation.uniqueness) << row.name;
        EXPECT_EQ(chosen.lr_tolerance, row.validation.lr_tolerance) << row.name;
    }
    const MatchConfig standard = defaults::match_config();
    EXPECT_EQ(standard.pipeline.cost, defaults::kCost);
    EXPECT_EQ(standard.pipeline.validation.uniqueness_ratio, defaults::kCensusUniqueness);
    EXPECT_EQ(standard.pipeline.validation.lr_tolerance, defaults::kCensusLrTolerance);
    EXPECT_TRUE(standard.pipeline.validation.uniqueness &&
                standard.pipeline.validation.left_right && standard.pipeline.validation.subpixel);
    EXPECT_EQ(standard.speckle.max_size, speckle::Params::defaults().max_size);
}

}  // namespace
}  // namespace stereo
