// The data arrays of a VTK XML file checked as written, before VTK's reader trusts them: binary
// headers (inline and appended, raw or base64, compressed or not) against the data that comes
// with them and the arrays' sizes, and each piece's cell offsets against the memory (VTK
// allocates the connectivity the last offset gives, and aborts when it cannot).
#pragma once

#include <string>

/// "" or the problem, starting with 'NAME'. `head`: the input's first bytes, which hold the tags
/// checked; `text`: the whole input when read from a string, else null (the file `name` is read
/// where an array's data lies).
std::string igaXMLArrayProblem(
  const std::string& name, const std::string* text, const std::string& head, double memory);
