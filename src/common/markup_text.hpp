// Text inside XML or HTML markup (an attribute value in either quotes, or an element's text): the X3D
// writer's and the HTML report's one escaping.
#pragma once

#include <string>

namespace symcompress {

inline std::string escapedMarkup(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&apos;"; break;
        default: out += c;
        }
    }
    return out;
}

}  // namespace symcompress
