// A fast, bounds-checked scanner over the text of a file, for the line-based formats (OBJ, MTL, ASCII PLY
// and STL). Numbers are parsed with std::from_chars; errors name the file and the line.
#pragma once

#include "symcompress/io.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace symcompress {

// `text` without the UTF-8 byte order mark that Windows editors put at the start of a file: it would otherwise
// stick to the first line's first word ("\xEF\xBB\xBFmtllib"), and that statement be lost.
inline std::string_view withoutByteOrderMark(std::string_view text) {
    constexpr std::string_view mark = "\xEF\xBB\xBF";
    return text.substr(0, mark.size()) == mark ? text.substr(mark.size()) : text;
}

class TextScanner {
public:
    // A byte order mark at the start is skipped (see withoutByteOrderMark).
    TextScanner(const std::filesystem::path& file, std::string_view text)
        : file_(file), text_(text), position_(text.size() - withoutByteOrderMark(text).size()) {}

    bool atEnd() const { return position_ >= text_.size(); }
    std::size_t line() const { return line_; }
    const std::filesystem::path& file() const { return file_; }

    [[noreturn]] void fail(const std::string& problem) const {
        throw FileError(file_, "line " + std::to_string(line_) + ": " + problem);
    }

    // The next line without its end-of-line characters; advances past it.
    std::string_view nextLine() {
        const std::size_t start = position_;
        std::size_t end = text_.find('\n', start);
        if (end == std::string_view::npos) end = text_.size();
        position_ = end + 1;
        ++line_;
        std::string_view out = text_.substr(start, end - start);
        if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
        return out;
    }

    // The rest of the text from the current position (for formats that switch to binary after a header).
    std::size_t offset() const { return position_; }

private:
    std::filesystem::path file_;
    std::string_view text_;
    std::size_t position_ = 0;
    std::size_t line_ = 0;
};

// Splits off the next whitespace-separated word of `line`; empty when there is none.
inline std::string_view nextWord(std::string_view& line) {
    std::size_t start = 0;
    while (start < line.size() && (line[start] == ' ' || line[start] == '\t')) ++start;
    std::size_t end = start;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
    std::string_view word = line.substr(start, end - start);
    line.remove_prefix(end);
    return word;
}

template <typename Number>
bool parseNumber(std::string_view word, Number& value) {
    if (!word.empty() && word.front() == '+') word.remove_prefix(1);
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return error == std::errc() && end == word.data() + word.size();
}

// The next word of `line` as a number; fails with the scanner's file and line when it is not one.
template <typename Number>
Number nextNumber(std::string_view& line, const TextScanner& scanner, const char* what) {
    const std::string_view word = nextWord(line);
    Number value{};
    if (word.empty()) scanner.fail(std::string("missing ") + what);
    if (!parseNumber(word, value)) scanner.fail(std::string("cannot read ") + what + " '" + std::string(word) + "'");
    return value;
}

// The next word of `line` as a finite real number: text formats spell NaN and infinity too, and no writer
// can give them back.
template <typename Real>
Real nextFiniteNumber(std::string_view& line, const TextScanner& scanner, const char* what) {
    const Real value = nextNumber<Real>(line, scanner, what);
    if (!std::isfinite(value)) scanner.fail(std::string("NaN or infinite ") + what);
    return value;
}

}  // namespace symcompress
