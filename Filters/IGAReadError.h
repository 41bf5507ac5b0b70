// A problem at a line of a file being read (line 0: the file as a whole), shared by the NURBS
// readers: the message reads "LINE: problem" so the reader base can prefix the file name.
#pragma once

#include <stdexcept>
#include <string>

struct IGAReadError : std::runtime_error
{
  IGAReadError(long line, const std::string& what)
    : std::runtime_error(line > 0 ? std::to_string(line) + ": " + what : what)
  {
  }
};
