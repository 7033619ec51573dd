// Text inside XML or HTML markup (an attribute value in either quotes, or an element's text): the X3D
// writer's and the HTML report's one escaping. Control characters, which XML 1.0 cannot hold at all (a NUL
// or a BEL in an OBJ's texture name), become U+FFFD.
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
        default:
            if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') out += "\xEF\xBF\xBD";
            else out += c;
        }
    }
    return out;
}

}  // namespace symcompress
