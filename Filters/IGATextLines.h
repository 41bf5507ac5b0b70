// The data lines of a text file (comments and blank lines left out) read one at a time as lines
// of numbers, each problem an IGAReadError naming the line: shared by the text-format readers
// (GeoPDEs, MFEM).
#pragma once

#include "IGAReadError.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

struct IGATextLine
{
  long number = 0;
  std::string text;
};

class IGATextLines
{
public:
  /// `text` split into lines; a line whose first non-blank character is `comment` is a comment,
  /// given to `onComment` (with its number) if set, and, like blank lines, not a data line.
  IGATextLines(const std::string& text, char comment,
    const std::function<void(const std::string&, long)>& onComment = {})
  {
    std::istringstream in(text);
    std::string line;
    long number = 1;
    for (; std::getline(in, line); ++number)
    {
      if (!line.empty() && line.back() == '\r')
      {
        line.pop_back();
      }
      const size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos)
      {
        continue;
      }
      if (line[first] == comment)
      {
        if (onComment)
        {
          onComment(line, number);
        }
        continue;
      }
      this->Lines.push_back({ number, line });
    }
    this->LastLine = number - 1;
  }

  bool atEnd() const { return this->Next >= this->Lines.size(); }
  const IGATextLine& peek(const char* what) const
  {
    if (this->atEnd())
    {
      throw IGAReadError(
        this->LastLine, std::string("the file ends where ") + what + " should follow");
    }
    return this->Lines[this->Next];
  }
  const IGATextLine& take(const char* what)
  {
    const IGATextLine& line = this->peek(what);
    ++this->Next;
    return line;
  }

  /// The numbers of the next line: exactly `count` of them (any count when -1).
  std::vector<double> numbers(const char* what, long count = -1)
  {
    const IGATextLine& line = this->take(what);
    std::vector<double> values;
    if (!parseNumbers(line.text, values))
    {
      throw IGAReadError(
        line.number, std::string(what) + ": '" + line.text + "' is not a line of finite numbers");
    }
    if (count >= 0 && static_cast<long>(values.size()) != count)
    {
      throw IGAReadError(line.number, std::string(what) + ": " + std::to_string(values.size()) +
                                        " values, expected " + std::to_string(count));
    }
    return values;
  }

  /// Integers of the next line, each in [lo, hi].
  std::vector<int> integers(const char* what, long count, long lo, long hi)
  {
    const long number = this->peek(what).number;
    std::vector<int> result;
    for (double value : this->numbers(what, count))
    {
      if (value != std::floor(value) || value < lo || value > hi)
      {
        throw IGAReadError(number, std::string(what) + ": " + std::to_string(value) +
                                     " is not an integer in " + std::to_string(lo) + ".." +
                                     std::to_string(hi));
      }
      result.push_back(static_cast<int>(value));
    }
    return result;
  }

  static bool parseNumbers(const std::string& text, std::vector<double>& values)
  {
    std::istringstream in(text);
    std::string token;
    while (in >> token)
    {
      errno = 0;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
      {
        return false;
      }
      values.push_back(value);
    }
    return !values.empty();
  }

private:
  std::vector<IGATextLine> Lines;
  size_t Next = 0;
  long LastLine = 0;
};
