#include "stereo_io/versioned_json.hpp"

#include <stdexcept>

#include "stereo/version.hpp"

namespace stereo::io {

nlohmann::json versioned(nlohmann::json document) {
    if (!document.is_object()) {
        throw std::logic_error("versioned(): a JSON report must be an object, got " +
                               std::string(document.type_name()));
    }
    if (document.contains("version")) {
        throw std::logic_error("versioned(): the report has a \"version\" field already");
    }
    document["version"] = kVersion;
    return document;
}

}  // namespace stereo::io
