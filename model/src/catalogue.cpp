#include "stereo/catalogue.hpp"

#include <stdexcept>

namespace stereo::catalogue {
namespace {

// Rows are indexed by their id: the tables must list them in enum order.
template <typename Row, std::size_t N>
constexpr bool in_order(const std::array<Row, N>& rows) {
    for (std::size_t i = 0; i < N; ++i) {
        if (static_cast<std::size_t>(rows[i].id) != i) {
            return false;
        }
    }
    return true;
}
static_assert(in_order(kCosts) && in_order(kMethods));

// The names of the rows `keep` accepts, in table order.
template <typename Row, std::size_t N, typename Keep>
std::vector<std::string> names_of(const std::array<Row, N>& rows, Keep keep) {
    std::vector<std::string> names;
    for (const Row& row : rows) {
        if (keep(row)) {
            names.emplace_back(row.name);
        }
    }
    return names;
}

// "a (summary), b (summary)": the rows `keep` accepts, for --help.
template <typename Row, std::size_t N, typename Keep>
std::string help_of(const std::array<Row, N>& rows, Keep keep) {
    std::string text;
    for (const Row& row : rows) {
        if (keep(row)) {
            text += (text.empty() ? "" : ", ") + std::string(row.name) + " (" +
                    std::string(row.summary) + ")";
        }
    }
    return text;
}

// The row named `name`, or null.
template <typename Row, std::size_t N>
const Row* find_row(const std::array<Row, N>& rows, std::string_view name) {
    for (const Row& row : rows) {
        if (row.name == name) {
            return &row;
        }
    }
    return nullptr;
}

// The row named `name`; throws std::invalid_argument "unknown <kind> "x" (<known>: a, b)".
template <typename Row, std::size_t N>
const Row& row_named(const std::array<Row, N>& rows, std::string_view name, const char* kind,
                     const char* known) {
    if (const Row* row = find_row(rows, name)) {
        return *row;
    }
    throw std::invalid_argument("unknown " + std::string(kind) + " \"" + std::string(name) +
                                "\" (" + known + ": " +
                                join(names_of(rows, [](const Row&) { return true; }), ", ") + ")");
}

constexpr auto kEvery = [](const auto&) { return true; };

}  // namespace

std::string join(const std::vector<std::string>& names, std::string_view last_separator) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) {
            text += i + 1 == names.size() ? last_separator : std::string_view(", ");
        }
        text += names[i];
    }
    return text;
}

bool is_cost(std::string_view name) {
    return find_row(kCosts, name) != nullptr;
}

const CostRow& cost(std::string_view name) {
    return row_named(kCosts, name, "cost", "known");
}

bool usable(const CostRow& row, CostUse use) {
    switch (use) {
        case CostUse::any:
            return true;
        case CostUse::hardware:
            return row.hardware_code != kNoHardware;
        case CostUse::pixel_pair:
            return row.pixel_pair;
        case CostUse::floating:
            return row.floating;
    }
    return false;
}

std::vector<std::string> cost_names(CostUse use) {
    return names_of(kCosts, [use](const CostRow& row) { return usable(row, use); });
}

std::vector<std::string> cost_names_if(bool (*keep)(const CostRow&)) {
    return names_of(kCosts, keep);
}

std::string cost_list(CostUse use) {
    return join(cost_names(use), " and ");
}

std::string cost_help(CostUse use) {
    return help_of(kCosts, [use](const CostRow& row) { return usable(row, use); });
}

void require_cost(std::string_view name, CostUse use, std::string_view what) {
    if (!is_cost(name) || !usable(cost(name), use)) {
        throw std::invalid_argument(std::string(what) + " has the costs " + cost_list(use) +
                                    ", not \"" + std::string(name) + "\"");
    }
}

const MethodRow& method(std::string_view name) {
    return row_named(kMethods, name, "method", "methods");
}

std::vector<std::string> method_names(bool (*keep)(const MethodRow&)) {
    return keep == nullptr ? names_of(kMethods, kEvery) : names_of(kMethods, keep);
}

std::string method_help() {
    return help_of(kMethods, kEvery);
}

const EngineRow& engine(std::string_view name) {
    return row_named(kEngines, name, "engine", "engines");
}

std::vector<std::string> engine_names() {
    return names_of(kEngines, kEvery);
}

std::string engine_help() {
    return help_of(kEngines, kEvery);
}

std::string_view default_cost(std::string_view method_name, std::string_view engine_name) {
    const CostRow& census = cost(kDefaultCost);
    return method(method_name).census_default && usable(census, engine(engine_name).costs)
               ? census.name
               : cost(kFallbackCost).name;
}

}  // namespace stereo::catalogue
