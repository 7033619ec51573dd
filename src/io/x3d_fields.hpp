// Parsing of X3D XML field values (SFVec3f, MFInt32, MFString, ...), shared by the X3D reader's parts.
#pragma once

#include "symcompress/io.hpp"

#include <pugixml.hpp>

#include <charconv>
#include <string>
#include <vector>

namespace symcompress::x3d {

// Numbers of a multi-valued field: separated by white space and/or commas.
inline bool parseNumbers(const char* text, std::vector<double>& out) {
    out.clear();
    const char* p = text;
    const char* end = text + std::char_traits<char>::length(text);
    while (p < end) {
        while (p < end && (*p == ' ' || *p == ',' || *p == '\t' || *p == '\n' || *p == '\r')) ++p;
        if (p >= end) break;
        if (*p == '+') ++p;
        double value;
        const auto result = std::from_chars(p, end, value);
        if (result.ec != std::errc()) return false;
        out.push_back(value);
        p = result.ptr;
    }
    return true;
}

// The strings of an MFString field ("a" "b" or a single unquoted value).
inline std::vector<std::string> parseStrings(const std::string& text) {
    std::vector<std::string> out;
    std::size_t p = 0;
    while (p < text.size()) {
        const std::size_t open = text.find('"', p);
        if (open == std::string::npos) break;
        std::string value;
        std::size_t q = open + 1;
        for (; q < text.size() && text[q] != '"'; ++q) {
            if (text[q] == '\\' && q + 1 < text.size()) ++q;
            value += text[q];
        }
        out.push_back(value);
        p = q + 1;
    }
    if (out.empty()) {
        std::string trimmed = text;
        trimmed.erase(0, trimmed.find_first_not_of(" \t\r\n"));
        trimmed.erase(trimmed.find_last_not_of(" \t\r\n") + 1);
        if (!trimmed.empty()) out.push_back(trimmed);
    }
    return out;
}

}  // namespace symcompress::x3d
