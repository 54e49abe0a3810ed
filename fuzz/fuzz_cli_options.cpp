// libFuzzer harness: the command line of `stereo`. The input is split at newlines into at most
// 32 arguments after the program name; the application is built exactly as main() builds it
// (cli::add_stereo_commands) and parsed by cli::run, stopped after parsing and before any
// subcommand's callback, so options, validators, --max-pixels and the error handler run but no
// command works on files. Findings: crashes, undefined behaviour, leaks, and an exit code outside
// 0..2.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"

namespace {

constexpr std::size_t kMaxArguments = 32;

std::vector<std::string> split_arguments(std::string_view input) {
    std::vector<std::string> arguments{"stereo"};
    while (arguments.size() <= kMaxArguments) {
        const auto end = input.find('\n');
        arguments.emplace_back(input.substr(0, end));
        if (end == std::string_view::npos) {
            break;
        }
        input.remove_prefix(end + 1);
    }
    return arguments;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> arguments =
        split_arguments(std::string_view(reinterpret_cast<const char*>(data), size));
    std::vector<char*> argv;
    for (std::string& argument : arguments) {
        argv.push_back(argument.data());
    }
    argv.push_back(nullptr);

    CLI::App app{"stereo (fuzzed command line)", "stereo"};
    stereo::cli::add_stereo_commands(app);
    // Parse only: once every option is parsed, converted and validated, and before any
    // subcommand's callback runs, end the way --help does (CLI::Success, exit 0). The callbacks
    // stay in place: they own the options objects the parsed values are written into.
    app.parse_complete_callback([] { throw CLI::Success(); });
    const int status = stereo::cli::run(app, static_cast<int>(arguments.size()), argv.data());
    if (status < stereo::cli::kExitOk || status > stereo::cli::kExitUsageError) {
        std::abort();  // parsing alone can only succeed or be a usage error
    }
    return 0;
}
