// A path as the error messages of the I/O layer name it: between two QUOTE characters.
#pragma once

#include <filesystem>
#include <string>

namespace stereo::io::detail {

// Built by appending: `"'" + string` trips a GCC 12 -Wrestrict false positive.
inline std::string quoted(const std::filesystem::path& path, char quote = '\'') {
    std::string text(1, quote);
    text += path.string();
    text += quote;
    return text;
}

}  // namespace stereo::io::detail
