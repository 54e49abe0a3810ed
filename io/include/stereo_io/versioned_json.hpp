// Every JSON document the tools print or write names the version of the code that made it
// (issue 23): one helper, used by each --json path of `stereo` and `stereo_experiments`.
#pragma once

#include <nlohmann/json.hpp>

namespace stereo::io {

// `document` with "version": stereo::kVersion added. Throws std::logic_error when `document` is
// not a JSON object (wrap arrays in an object first) or already has a "version" field.
nlohmann::json versioned(nlohmann::json document);

}  // namespace stereo::io
