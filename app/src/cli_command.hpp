// How every subcommand of `stereo` and `stereo_experiments` is registered: its options object
// and its callback. CLI11 runs the callback after the add_*_command function has returned, so
// the options live in a shared_ptr that the callback holds.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include <CLI/CLI.hpp>

#include "cli_checks.hpp"
#include "stereo_io/data_dir.hpp"

namespace stereo::cli {

template <class Options>
struct Command {
    CLI::App* app;                     // the subcommand, to register its options on
    std::shared_ptr<Options> options;  // what they parse into; run() receives it
};

// Adds the subcommand `name` to `app` with a default-constructed Options; parsing it calls
// run(options).
template <class Options, class Run>
Command<Options> add_command(CLI::App& app, const std::string& name, const std::string& description,
                             Run run) {
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(name, description);
    command->callback([options, run] { run(*options); });
    return {command, options};
}

// add_command for an Options that names its command beside its fields (Options::kName,
// Options::kDescription).
template <class Options, class Run>
Command<Options> add_command(CLI::App& app, Run run) {
    return add_command<Options>(app, std::string(Options::kName),
                                std::string(Options::kDescription), std::move(run));
}

// --data: the folder that holds middlebury2003/ (its default shown by --help).
inline void add_data_option(CLI::App& command, std::string& folder) {
    command.add_option("--data", folder, "Data folder (middlebury2003/ and the other data sets)")
        ->capture_default_str();
}

// The options every result generator shares: the data folder it reads (--data), and besides
// stdout a Markdown file of its tables (--markdown) and a JSON file of every number (--json).
struct ReportOptions {
    std::string data_dir = io::data_dir().string();
    std::string markdown;   // empty: stdout only
    std::string json_path;  // empty: no JSON file
};

// add_command for a result generator: Options derives from ReportOptions and names its command
// beside its fields (Options::kName, Options::kDescription); --data, --markdown and --json are
// registered here, so that its add_*_command lists only the options of its own.
template <class Options, class Run>
Command<Options> add_report_command(CLI::App& app, Run run) {
    static_assert(std::is_base_of_v<ReportOptions, Options>);
    const Command<Options> command = add_command<Options>(app, std::move(run));
    ReportOptions& report = *command.options;
    add_data_option(*command.app, report.data_dir);
    command.app->add_option("--markdown", report.markdown,
                            "Also write the tables (Markdown) to FILE");
    command.app->add_option("--json", report.json_path, "Also write every number as JSON to FILE");
    return command;
}

// A numeric option whose --help shows its default, with its range check when it has one. A run
// of them is registered as one table instead of one add_option block each.
struct NumberOption {
    const char* name;
    std::variant<int*, double*, std::uint32_t*> value;
    const char* help;
    std::optional<CLI::Validator> range = std::nullopt;
};

inline void add_number_options(CLI::App& command, std::initializer_list<NumberOption> options) {
    for (const NumberOption& option : options) {
        std::visit(
            [&](auto* value) {
                CLI::Option* added =
                    command.add_option(option.name, *value, option.help)->capture_default_str();
                if (option.range) {
                    added->check(*option.range);
                }
            },
            option.value);
    }
}

// --downscale F (>= 1): every command that reads a pair shrinks it by the same rule.
inline void add_downscale_option(CLI::App& command, int& factor,
                                 const char* help = "Shrink both images by integer F first") {
    command.add_option("--downscale", factor, help)
        ->capture_default_str()
        ->check(checks::integer_at_least(1));
}

// The K of a PNG that stores disparity * K: 1e-3 .. 1e6 covers every format in use (Middlebury
// 1..16, KITTI 256); a denormal like 1e-320 made every disparity infinite.
inline CLI::Validator disparity_scale() {
    return checks::real_in(1e-3, 1e6);
}

// --threads N: 0 means every core; more than 256 is a typing error, not a machine.
inline CLI::Validator thread_count() {
    return checks::integer_in(0, 256);
}

// A switch and its negation: `name` sets `value`, `negation` clears it (`name=false` too); the
// help ends with the one that holds now, "[default: --name]" or "[default: --negation]".
inline CLI::Option* add_switch(CLI::App& command, const std::string& name,
                               const std::string& negation, bool& value, const std::string& help) {
    return command.add_flag(name + ",!" + negation, value,
                            help + " [default: " + (value ? name : negation) + "]");
}

}  // namespace stereo::cli
