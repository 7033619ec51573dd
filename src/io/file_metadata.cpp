// What a file says about itself, between readers and writers (file_metadata.hpp).
#include "file_metadata.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace symcompress {

nlohmann::json writtenExtras(const std::string& sceneExtras, const std::string& writerExtras) {
    nlohmann::json out = nlohmann::json::object();
    // A scene's extras that do not parse, or are no object (glTF allows any value), are written as they are.
    const nlohmann::json scene =
        sceneExtras.empty() ? nlohmann::json() : nlohmann::json::parse(sceneExtras, nullptr, false);
    if (!scene.is_discarded() && !scene.is_null() && !scene.is_object() && writerExtras.empty()) return scene;
    if (scene.is_object())
        for (const auto& [key, value] : scene.items())
            if (key != kDigestMember) out[key] = value;
    if (!writerExtras.empty()) {
        const nlohmann::json writer = nlohmann::json::parse(writerExtras, nullptr, false);
        if (!writer.is_object()) throw std::invalid_argument("extras are not a JSON object: " + writerExtras);
        for (const auto& [key, value] : writer.items()) out[key] = value;
    }
    return out.empty() ? nlohmann::json() : out;
}

std::string passedThroughExtensions(const std::string& extensionsJson) {
    if (extensionsJson.empty()) return "";
    const nlohmann::json extensions = nlohmann::json::parse(extensionsJson, nullptr, false);
    if (!extensions.is_object()) return "";
    nlohmann::json passed = nlohmann::json::object();
    for (const char* name : {"KHR_xmp_json_ld"})
        if (extensions.contains(name)) passed[name] = extensions[name];
    return passed.empty() ? "" : passed.dump();
}

void addMetaTag(nlohmann::json& extras, const std::string& name, const std::string& content) {
    if (!extras.is_object()) extras = nlohmann::json::object();
    auto found = extras.find(name);
    if (found == extras.end()) {
        extras[name] = content;
    } else {
        if (!found->is_array()) *found = nlohmann::json::array({*found});
        found->push_back(content);
    }
}

std::string digestAsMetaContent(const nlohmann::json& digest) {
    std::string content;
    if (!digest.is_array()) return content;
    for (const nlohmann::json& value : digest) {
        if (!value.is_number()) return "";
        std::string number = value.dump();  // the shortest text that reads back, 24.0 as 24
        if (number.size() > 2 && number.compare(number.size() - 2, 2, ".0") == 0) number.resize(number.size() - 2);
        content += (content.empty() ? "" : " ") + number;
    }
    return content;
}

nlohmann::json digestFromMetaContent(const std::string& content) {
    nlohmann::json digest = nlohmann::json::array();
    std::istringstream words(content);
    for (std::string word; words >> word;) {
        char* end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (end != word.c_str() + word.size() || !std::isfinite(value)) return nullptr;
        // The count of triangles is an integer, which the digest reads as one.
        if (word.find_first_of(".eE") == std::string::npos && value >= 0 && value < 9e15)
            digest.push_back(std::uint64_t(value));
        else
            digest.push_back(value);
    }
    return digest.empty() ? nlohmann::json() : digest;
}

std::vector<std::pair<std::string, std::string>> metaTags(const nlohmann::json& extras) {
    std::vector<std::pair<std::string, std::string>> out;
    if (!extras.is_object()) return out;
    for (const auto& [key, value] : extras.items()) {
        if (key == kDigestMember) continue;
        if (value.is_string()) {
            out.emplace_back(key, value.get<std::string>());
        } else if (value.is_array() && !value.empty() &&
                   std::all_of(value.begin(), value.end(), [](const nlohmann::json& v) { return v.is_string(); })) {
            for (const nlohmann::json& v : value) out.emplace_back(key, v.get<std::string>());
        } else {
            out.emplace_back(key, value.dump());
        }
    }
    return out;
}

}  // namespace symcompress
