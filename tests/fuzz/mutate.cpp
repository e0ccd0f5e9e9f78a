#include "mutate.hpp"

#include <array>
#include <cctype>
#include <cstdlib>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace nodus::fuzz {

namespace {

/// A scalar of the text outside comments: its byte range, its line (from 1) and whether a ':' follows it
/// (a key).
struct Token {
  std::size_t begin = 0, end = 0;
  int line = 0;
  bool key = false;
};

bool token_char(char c) {
  return !std::isspace(static_cast<unsigned char>(c)) && c != '[' && c != ']' && c != '{' && c != '}' &&
         c != ',' && c != ':' && c != '#' && c != '\'' && c != '"';
}

std::vector<Token> tokens_of(const std::string& text) {
  std::vector<Token> out;
  int line = 1;
  bool comment = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      comment = false;
      ++i;
      continue;
    }
    // A '#' at a line's start or after a blank opens a comment (YAML's rule).
    if (c == '#' && (i == 0 || std::isspace(static_cast<unsigned char>(text[i - 1])))) comment = true;
    if (comment || !token_char(c)) {
      ++i;
      continue;
    }
    Token t{i, i, line, false};
    while (t.end < text.size() && token_char(text[t.end])) ++t.end;
    std::size_t next = t.end;
    while (next < text.size() && text[next] == ' ') ++next;
    t.key = next < text.size() && text[next] == ':';
    i = t.end;
    if (t.end - t.begin == 1 && text[t.begin] == '-') continue;  // a list item's dash
    out.push_back(t);
  }
  return out;
}

/// The lines of `text`, each with its newline.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
    out.push_back(text.substr(start, stop - start));
    start = stop;
  }
  return out;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l;
  return out;
}

bool blank_or_comment(std::string_view line) {
  const std::size_t first = line.find_first_not_of(" \t\r\n");
  return first == std::string_view::npos || line[first] == '#';
}

/// What a value may be replaced by: the values that broke programs before, and `old` scaled.
std::vector<std::string> replacements(const std::string& old) {
  std::vector<std::string> out = {"0",
                                  "-1",
                                  "1",
                                  "2",
                                  ".nan",
                                  ".inf",
                                  "-.inf",
                                  "1e308",
                                  "-1e308",
                                  "1e-308",
                                  "abc",
                                  "''",
                                  "[]",
                                  "{}",
                                  "true",
                                  "null",
                                  "2147483648",
                                  "-2147483649",
                                  "99999999999999999999",
                                  "0.5",
                                  "1e-12",
                                  "[1, 2, 3]",
                                  "-0",
                                  "1e6"};
  char* end = nullptr;
  const double value = std::strtod(old.c_str(), &end);
  if (!old.empty() && end == old.c_str() + old.size()) {
    out.push_back(fmt::format("{}", -value));
    out.push_back(fmt::format("{}", value * 1e6));
    out.push_back(fmt::format("{}", value * 1e-6));
    out.push_back(fmt::format("{}", value * 10));
    out.push_back(fmt::format("{}", value + 1));
  }
  return out;
}

}  // namespace

Mutant Mutator::mutate(const std::string& text) {
  const auto pick = [this](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  };
  const std::vector<Token> tokens = tokens_of(text);
  std::vector<std::size_t> values, keys;
  for (std::size_t i = 0; i < tokens.size(); ++i) (tokens[i].key ? keys : values).push_back(i);
  const auto piece = [&](const Token& t) { return text.substr(t.begin, t.end - t.begin); };
  const auto replaced = [&](const Token& t, const std::string& by) {
    return text.substr(0, t.begin) + by + text.substr(t.end);
  };

  // Kinds, by weight: a value replaced (12), two values swapped (2), a key replaced (2), a line deleted (2),
  // duplicated (1) or swapped with the next (1), the text cut (1).
  static constexpr std::array<int, 7> kWeights = {12, 2, 2, 2, 1, 1, 1};
  int total = 0;
  for (int w : kWeights) total += w;
  int draw = static_cast<int>(pick(static_cast<std::size_t>(total)));
  int kind = 0;
  while (draw >= kWeights[static_cast<std::size_t>(kind)]) draw -= kWeights[static_cast<std::size_t>(kind++)];

  if ((kind == 0 || kind == 1) && values.empty()) kind = 6;
  if (kind == 2 && keys.size() < 2) kind = 3;
  switch (kind) {
    case 0: {
      const Token& t = tokens[values[pick(values.size())]];
      std::vector<std::string> by = replacements(piece(t));
      by.push_back(piece(tokens[values[pick(values.size())]]));  // another value of the file
      const std::string with = by[pick(by.size())];
      return {replaced(t, with), fmt::format("{}: value '{}' -> '{}'", t.line, piece(t), with)};
    }
    case 1: {
      std::size_t a = values[pick(values.size())], b = values[pick(values.size())];
      if (a > b) std::swap(a, b);
      const Token &ta = tokens[a], &tb = tokens[b];
      if (a == b) return {text, fmt::format("{}: unchanged", ta.line)};
      const std::string out = text.substr(0, ta.begin) + piece(tb) + text.substr(ta.end, tb.begin - ta.end) +
                              piece(ta) + text.substr(tb.end);
      return {out,
              fmt::format("{}, {}: values '{}' and '{}' swapped", ta.line, tb.line, piece(ta), piece(tb))};
    }
    case 2: {
      const Token& t = tokens[keys[pick(keys.size())]];
      const std::string with = piece(tokens[keys[pick(keys.size())]]);
      return {replaced(t, with), fmt::format("{}: key '{}' -> '{}'", t.line, piece(t), with)};
    }
    case 3:
    case 4:
    case 5: {
      std::vector<std::string> lines = lines_of(text);
      std::vector<std::size_t> code;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (!blank_or_comment(lines[i])) code.push_back(i);
      if (code.empty()) return {text, "0: unchanged"};
      const std::size_t i = code[pick(code.size())];
      const int line = static_cast<int>(i) + 1;
      if (kind == 3) {
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
        return {joined(lines), fmt::format("{}: line deleted", line)};
      }
      if (kind == 4) {
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
        return {joined(lines), fmt::format("{}: line duplicated", line)};
      }
      if (i + 1 < lines.size()) std::swap(lines[i], lines[i + 1]);
      return {joined(lines), fmt::format("{}: line swapped with the next", line)};
    }
    default: {
      const std::size_t at = pick(text.size() + 1);
      int line = 1;
      for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n';
      return {text.substr(0, at), fmt::format("{}: text cut at byte {}", line, at)};
    }
  }
}

}  // namespace nodus::fuzz
