#include "stereo/catalogue.hpp"

#include <stdexcept>

namespace stereo::catalogue {
namespace {

// Rows are indexed by their id: the tables must list them in enum order.
constexpr bool costs_in_order() {
    for (std::size_t i = 0; i < kCosts.size(); ++i) {
        if (static_cast<std::size_t>(kCosts[i].id) != i) {
            return false;
        }
    }
    return true;
}
constexpr bool methods_in_order() {
    for (std::size_t i = 0; i < kMethods.size(); ++i) {
        if (static_cast<std::size_t>(kMethods[i].id) != i) {
            return false;
        }
    }
    return true;
}
static_assert(costs_in_order() && methods_in_order());

std::string joined(const std::vector<std::string>& names, std::string_view last_separator) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) {
            text += i + 1 == names.size() ? last_separator : std::string_view(", ");
        }
        text += names[i];
    }
    return text;
}

}  // namespace

bool is_cost(std::string_view name) {
    for (const CostRow& row : kCosts) {
        if (row.name == name) {
            return true;
        }
    }
    return false;
}

const CostRow& cost(std::string_view name) {
    for (const CostRow& row : kCosts) {
        if (row.name == name) {
            return row;
        }
    }
    throw std::invalid_argument("unknown cost \"" + std::string(name) +
                                "\" (known: " + joined(cost_names(), ", ") + ")");
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
    std::vector<std::string> names;
    for (const CostRow& row : kCosts) {
        if (usable(row, use)) {
            names.emplace_back(row.name);
        }
    }
    return names;
}

std::string cost_list(CostUse use) {
    return joined(cost_names(use), " and ");
}

std::string cost_help(CostUse use) {
    std::string text;
    for (const CostRow& row : kCosts) {
        if (usable(row, use)) {
            text += (text.empty() ? "" : ", ") + std::string(row.name) + " (" +
                    std::string(row.summary) + ")";
        }
    }
    return text;
}

void require_cost(std::string_view name, CostUse use, std::string_view what) {
    if (!is_cost(name) || !usable(cost(name), use)) {
        throw std::invalid_argument(std::string(what) + " has the costs " + cost_list(use) +
                                    ", not \"" + std::string(name) + "\"");
    }
}

const MethodRow& method(std::string_view name) {
    for (const MethodRow& row : kMethods) {
        if (row.name == name) {
            return row;
        }
    }
    throw std::invalid_argument("unknown method \"" + std::string(name) +
                                "\" (methods: " + joined(method_names(), ", ") + ")");
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (const MethodRow& row : kMethods) {
        names.emplace_back(row.name);
    }
    return names;
}

std::string method_help() {
    std::string text;
    for (const MethodRow& row : kMethods) {
        text += (text.empty() ? "" : ", ") + std::string(row.name) + " (" +
                std::string(row.summary) + ")";
    }
    return text;
}

const EngineRow& engine(std::string_view name) {
    for (const EngineRow& row : kEngines) {
        if (row.name == name) {
            return row;
        }
    }
    throw std::invalid_argument("unknown engine \"" + std::string(name) +
                                "\" (engines: " + joined(engine_names(), ", ") + ")");
}

std::vector<std::string> engine_names() {
    std::vector<std::string> names;
    for (const EngineRow& row : kEngines) {
        names.emplace_back(row.name);
    }
    return names;
}

std::string engine_help() {
    std::string text;
    for (const EngineRow& row : kEngines) {
        text += (text.empty() ? "" : ", ") + std::string(row.name) + " (" +
                std::string(row.summary) + ")";
    }
    return text;
}

std::string_view default_cost(std::string_view method_name, std::string_view engine_name) {
    const CostRow& census = cost(kDefaultCost);
    return method(method_name).census_default && usable(census, engine(engine_name).costs)
               ? census.name
               : cost(kFallbackCost).name;
}

}  // namespace stereo::catalogue
