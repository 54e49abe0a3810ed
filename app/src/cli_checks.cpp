#include "cli_checks.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace stereo::cli::checks {
namespace {

// The value of a plain decimal integer ("+12", "-064"), or nothing for anything else (octal and
// hex prefixes, spaces, fractions, exponents, out of range).
std::optional<std::int64_t> decimal(std::string_view text) {
    if (!text.empty() && text.front() == '+') {
        text.remove_prefix(1);
    }
    if (text.empty() || text.front() == '+') {
        return std::nullopt;
    }
    std::int64_t value = 0;
    const char* const end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value, 10);
    if (error != std::errc() || stop != end) {
        return std::nullopt;
    }
    return value;
}

// The value of a finite real number, or nothing (inf, nan, overflow, trailing text).
std::optional<double> finite(const std::string& text) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) != 0) {
        return std::nullopt;
    }
    char* stop = nullptr;
    const double value = std::strtod(text.c_str(), &stop);
    if (stop != text.c_str() + text.size() || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

std::string got(const std::string& text) {
    return ", got '" + text + "'";
}

}  // namespace

CLI::Validator integer_in(std::int64_t min, std::int64_t max) {
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    return {[min, max](std::string& text) -> std::string {
                const std::optional<std::int64_t> value = decimal(text);
                if (!value || *value < min || *value > max) {
                    return "must be an integer in [" + std::to_string(min) + ", " +
                           std::to_string(max) + "]" + got(text);
                }
                return {};
            },
            "INT in " + range, "integer_in"};
}

CLI::Validator odd_in(std::int64_t min, std::int64_t max) {
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    return {[min, max, range](std::string& text) -> std::string {
                const std::optional<std::int64_t> value = decimal(text);
                if (!value || *value < min || *value > max || *value % 2 == 0) {
                    return "must be an odd integer in " + range + got(text);
                }
                return {};
            },
            "odd INT in " + range, "odd_in"};
}

CLI::Validator integer_at_least(std::int64_t min) {
    return {[min](std::string& text) -> std::string {
                const std::optional<std::int64_t> value = decimal(text);
                if (!value || *value < min) {
                    return "must be an integer >= " + std::to_string(min) + got(text);
                }
                return {};
            },
            "INT >= " + std::to_string(min), "integer_at_least"};
}

CLI::Validator real_in(double min, double max, Bound lower, Bound upper) {
    std::ostringstream range;
    range << (lower == Bound::inclusive ? "[" : "(") << min << ", " << max
          << (upper == Bound::inclusive ? "]" : ")");
    const std::string description = range.str();
    return {
        [min, max, lower, upper, description](std::string& text) -> std::string {
            const std::optional<double> value = finite(text);
            const bool above = value && (lower == Bound::inclusive ? *value >= min : *value > min);
            const bool below = value && (upper == Bound::inclusive ? *value <= max : *value < max);
            if (!above || !below) {
                return "must be a number in " + description + got(text);
            }
            return {};
        },
        "NUMBER in " + description, "real_in"};
}

CLI::Validator png_output() {
    return {[](std::string& text) -> std::string {
                std::string extension = std::filesystem::path(text).extension().string();
                for (char& c : extension) {
                    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
                }
                if (extension != ".png") {
                    return "must name a .png file (it is written as PNG), got '" + text + "'";
                }
                return {};
            },
            "", "png_output"};
}

void plain_numbers(CLI::App& app) {
    // Applied after the option's own validators; they parse decimal themselves, so the order
    // does not matter.
    const CLI::Validator integer(
        [](std::string& text) -> std::string {
            const std::optional<std::int64_t> value = decimal(text);
            if (!value) {
                return "must be a decimal integer" + got(text);
            }
            text = std::to_string(*value);  // "064" -> "64": CLI11 would read it as octal
            return {};
        },
        "", "decimal");
    const CLI::Validator real(
        [](std::string& text) -> std::string {
            return finite(text) ? std::string() : "must be a finite number" + got(text);
        },
        "", "finite");
    for (CLI::Option* option : app.get_options()) {
        const std::string type = option->get_type_name();
        if (option->get_type_size() == 0) {
            continue;  // a flag
        }
        if (type == "INT" || type == "UINT") {
            option->transform(integer);
        } else if (type == "FLOAT") {
            option->check(real);
        }
    }
    for (CLI::App* command : app.get_subcommands({})) {
        plain_numbers(*command);
    }
}

}  // namespace stereo::cli::checks
