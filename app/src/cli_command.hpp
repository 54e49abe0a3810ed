// How every subcommand of `stereo` and `stereo_experiments` is registered: its options object
// and its callback. CLI11 runs the callback after the add_*_command function has returned, so
// the options live in a shared_ptr that the callback holds.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <variant>

#include <CLI/CLI.hpp>

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

// --data: the folder that holds middlebury2003/ (its default shown by --help).
inline void add_data_option(CLI::App& command, std::string& folder) {
    command.add_option("--data", folder, "Data folder (middlebury2003/ and the other data sets)")
        ->capture_default_str();
}

// The options of every result generator: the data folder, and besides stdout a Markdown file of
// the tables and a JSON file of every number.
inline void add_report_options(CLI::App& command, std::string& data_folder, std::string& markdown,
                               std::string& json) {
    add_data_option(command, data_folder);
    command.add_option("--markdown", markdown, "Also write the tables (Markdown) to FILE");
    command.add_option("--json", json, "Also write every number as JSON to FILE");
}

// A numeric option whose --help shows its default. A run of them is registered as one table
// instead of one add_option block each.
struct NumberOption {
    const char* name;
    std::variant<int*, double*, std::uint32_t*> value;
    const char* help;
};

inline void add_number_options(CLI::App& command, std::initializer_list<NumberOption> options) {
    for (const NumberOption& option : options) {
        std::visit(
            [&](auto* value) {
                command.add_option(option.name, *value, option.help)->capture_default_str();
            },
            option.value);
    }
}

}  // namespace stereo::cli
